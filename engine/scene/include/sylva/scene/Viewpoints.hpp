#pragma once
// Where the first camera of a world the options describe stands (over the grass, by a tree, watching balls),
// and where balls are dropped into the grass (`sylva render --grass/--trees/--physics balls`, `sylva view`'s
// "drop balls"): decisions on the terrain's heights, a grass layer's density and a forest, no GL.

#include <sylva/core/Geometry.hpp>
#include <sylva/grass/GrassField.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/trees/Forest.hpp>

#include <glm/glm.hpp>

namespace sylva::scene {

/**
 * The steepest grassy slope (density at least 0.6, slope at most 25°, where balls roll without bouncing away)
 * within `radius` metres of `camera` on a 2-m grid, as world x, z in metres; the camera's own x, z when there
 * is none.
 */
glm::vec2 ballDropPoint(const terrain::HeightField& terrain, const grass::GrassField& field,
                        const render::Camera& camera, float radius = 40.0f);

/**
 * A camera that watches balls dropped at `drop` (world x, z, metres) roll down towards it: 9 m downhill of
 * the drop point and 2.5 m to the side, 1.8 m above the ground, looking back up the slope at a point 4 m
 * downhill; clip planes fitted to `bounds` (world box, metres) with a 5-cm near plane for the blades close
 * by.
 */
render::Camera ballCamera(const terrain::HeightField& terrain, const Aabb& bounds, glm::vec2 drop,
                          float fovY);

/** Near clip plane of every camera among grass blades, metres: a blade 5 cm from the eye still draws. */
inline constexpr float kGrassNearPlane = 0.05f;
/** Near clip plane of forestCamera, metres. */
inline constexpr float kForestNearPlane = 0.1f;

/**
 * A camera at eye height (1.7 m) over the densest grass near the terrain's centre (a 25 × 25 grid over the
 * middle half, ties nearest the centre, steep ground avoided), looking 25 m along the wind turned 35° across
 * the field, slightly down: the default view of a grass render. `terrain` heights as drawn, metres;
 * `maxHeight` where the eye goes when the ground has no height there; clip planes fitted to `bounds` with a
 * 5-cm near plane.
 */
render::Camera grassCamera(const terrain::HeightField& terrain, const Aabb& bounds, float maxHeight,
                           const grass::GrassField& field, float fovY, float windDirectionDegrees);

/**
 * `base` (the terrain's default camera) moved to the forest's tree nearest the terrain's centre: seen from
 * 2.5 heights away (8–60 m) towards +x+z, 2.5 m above the ground (`terrain` in true metres, drawn ×
 * `exaggeration`), looking at 45 % of the tree's height. `base` itself when there are no trees.
 */
render::Camera forestCamera(const terrain::HeightField& terrain, float exaggeration,
                            const render::Camera& base, const trees::Forest& forest, float fovY);

} // namespace sylva::scene

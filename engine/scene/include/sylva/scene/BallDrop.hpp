#pragma once
// Where balls are dropped into the grass and from where to watch them roll (`sylva render --physics balls`,
// `sylva view`'s "drop balls"): decisions on the terrain's heights and a grass layer's density, no GL.

#include <sylva/core/Geometry.hpp>
#include <sylva/grass/GrassField.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/terrain/HeightField.hpp>

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

} // namespace sylva::scene

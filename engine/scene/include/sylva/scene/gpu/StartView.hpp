#pragma once
// The first camera on a world a command's options describe (`sylva render` and `sylva view` without a scene
// file): a camera the user places, or the grass, forest or ball camera of Viewpoints.hpp for what the world
// holds; and, with simulated grass, where its balls drop.

#include <sylva/render/Camera.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace sylva::terrain {
class TerrainScene;
}

namespace sylva::scene {

class SceneWorld;

/** A camera framing the terrain from a side, or placed by the user. */
struct CameraPlacement {
  std::string viewFrom = "south-west"; ///< render::parseViewFrom: the side the terrain is framed from
  float fovDegrees = 50.0f;            ///< vertical field of view
  std::optional<glm::vec3> position;   ///< the eye, world x, z and true height y (metres)
  std::optional<glm::vec3> lookAt;     ///< what it looks at (default: the terrain's middle), same units
};

/**
 * The camera `placement` describes on `terrain` at `aspect` (width / height): framed from its side, turned to
 * look at `lookAt` and moved to `position` when given (heights × the terrain's exaggeration; straight down
 * keeps north at the top), with clip planes fitted to the terrain. Throws sylva::Error when the position and
 * the point looked at are the same.
 */
render::Camera placedCamera(const terrain::TerrainScene& terrain, const CameraPlacement& placement,
                            float aspect);

/** What the first view of an options-built world starts from. */
struct StartSettings {
  /** Where the first camera is. */
  CameraPlacement camera;
  float windDirectionDegrees = 0.0f; ///< the grass camera looks along the wind (the options' direction)
  /** Balls dropped into the first grass layer (needs simulated grass); 0: none. */
  int balls = 0;
  /** Seed of where the balls drop. */
  std::uint64_t ballSeed = 1;
  /** Where they drop (world x, z, metres); none: the steepest grassy slope near the camera. */
  std::optional<glm::vec2> ballsAt;
};

/** The first camera and where its balls dropped. */
struct StartView {
  /** The first camera. */
  render::Camera camera;
  std::optional<glm::vec2> dropCentre; ///< world x, z of the ball drop, metres; none without balls
};

/**
 * The first view of `world` at `aspect`: the placed camera when settings.camera has a position; otherwise the
 * grass camera over its first grass layer, else the forest camera by its first forest, else the framed one.
 * With balls, drops them into `world` and (without a placed position) watches them roll. A placed camera
 * clips as the chosen one would (5 cm among blades; among trees alone the forest camera's planes), so a
 * logged camera renders the same bytes again.
 */
StartView startView(SceneWorld& world, const StartSettings& settings, float aspect);

} // namespace sylva::scene

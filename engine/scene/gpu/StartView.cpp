#include <sylva/scene/gpu/StartView.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/scene/Viewpoints.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

namespace sylva::scene {

render::Camera placedCamera(const terrain::TerrainScene& terrain, const CameraPlacement& placement,
                            float aspect) {
  if (placement.position && placement.lookAt && *placement.position == *placement.lookAt) {
    fail("--camera-pos and --look-at: the same point ({:g},{:g},{:g}); the camera needs a direction",
         placement.position->x, placement.position->y, placement.position->z);
  }
  const Aabb box = terrain.bounds();
  const float fov = glm::radians(placement.fovDegrees);
  const float e = terrain.exaggeration();
  // Y is given in the data's metres; the scene is drawn with heights × exaggeration.
  const auto toWorld = [e](glm::vec3 p) { return glm::vec3(p.x, p.y * e, p.z); };
  const glm::vec3 target = placement.lookAt ? toWorld(*placement.lookAt) : box.center();
  render::Camera camera =
      render::frameBox(box, render::parseViewFrom(placement.viewFrom), fov, aspect, target);
  if (placement.lookAt) {
    camera.target = target; // frameBox re-aims at the middle of what it sees; a point the user names is kept
  }
  if (placement.position) {
    camera.position = toWorld(*placement.position);
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 dir = glm::normalize(camera.target - camera.position);
    if (std::abs(dir.y) > 0.999f) {
      camera.up = glm::vec3(0.0f, 0.0f, -1.0f); // straight down or up: keep north at the top of the image
    }
  }
  // A camera inside or beyond the terrain still sees all of it between the clip planes.
  render::fitClipPlanes(camera, box);
  return camera;
}

StartView startView(SceneWorld& world, const StartSettings& settings, float aspect) {
  terrain::TerrainScene& ground = world.terrain();
  StartView start;
  render::Camera& view = start.camera;
  view = placedCamera(ground, settings.camera, aspect);
  const float fov = glm::radians(settings.camera.fovDegrees);
  const bool placed = settings.camera.position.has_value();
  const bool grass = world.grassCount() > 0;
  const bool trees = world.forestCount() > 0;
  if (grass && !placed) {
    view = grassCamera(ground.field(), ground.bounds(), ground.maxHeight(), world.grass(0).field(), fov,
                       settings.windDirectionDegrees);
  }
  if (trees && !placed && !grass) {
    view = forestCamera(ground.field(), ground.exaggeration(), ground.defaultCamera(),
                        world.forest(0).forest(), fov);
  }
  if (settings.balls > 0 && grass) {
    BodyDrop drop;
    drop.centre =
        settings.ballsAt ? *settings.ballsAt : ballDropPoint(ground.field(), world.grass(0).field(), view);
    drop.radius = 1.5f;
    drop.count = settings.balls;
    drop.seed = settings.ballSeed;
    drop.height = 0.5f;
    world.addDrop(drop);
    start.dropCentre = drop.centre;
    if (!placed) {
      view = ballCamera(ground.field(), ground.bounds(), drop.centre, fov);
    }
  }
  if (grass) {
    view.nearPlane = kGrassNearPlane;
  } else if (placed && trees) {
    view.nearPlane = kForestNearPlane;
    view.farPlane = ground.defaultCamera().farPlane;
  }
  return start;
}

} // namespace sylva::scene

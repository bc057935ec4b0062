// A terrain with a grass field, rendered offscreen into a PNG: the world is described in code (a procedural
// terrain 256 m across and one grass layer over all of it), the engine composes it (SceneWorld: terrain,
// grass, sky, sun shadows, in one frame) and draws it into an offscreen target through a headless OpenGL 4.5
// context (EGL: a GPU, or Mesa's llvmpipe on the CPU).
//
//   terrain_grass [OUT.png] [WIDTH HEIGHT]      (default: terrain_grass.png, 640 × 360)
#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/platform/GlContext.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/shader/Library.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

#include <glm/trigonometric.hpp>

int main(int argc, char** argv) {
  namespace scene = sylva::scene;
  const std::string out = argc > 1 ? argv[1] : "terrain_grass.png";
  const int width = argc > 3 ? std::atoi(argv[2]) : 640;
  const int height = argc > 3 ? std::atoi(argv[3]) : 360;
  if (width < 16 || height < 16 || width > 8192 || height > 8192) {
    std::fprintf(stderr, "usage: terrain_grass [OUT.png] [WIDTH HEIGHT] (16 to 8192 pixels)\n");
    return 2;
  }
  try {
    scene::SceneDesc desc;
    desc.path = "terrain_grass";
    desc.name = "terrain with grass";
    desc.terrain.size = 129;     // samples per side
    desc.terrain.spacing = 2.0f; // metres between samples: 256 m across
    desc.terrain.relief = 40.0f; // metres from the lowest to the highest point
    desc.terrain.seed = 4;
    scene::GrassLayer grass;
    grass.layer = "none"; // everywhere, not only on the terrain's grass splat layer
    grass.density = 1.5f;
    grass.distance = 80.0f;
    desc.grass.push_back(grass);
    desc.sun.elevation = 35.0f;

    // The context must be current before anything touches GL; the shaders are the ones embedded in the
    // library (shader::Library's default).
    const auto context = sylva::platform::createHeadlessContext();
    const sylva::shader::Library shaders;
    scene::SceneWorld world(shaders, desc);

    // Standing in the grass south-west of the terrain's centre, 6 m above the ground, looking down across it
    // (world metres: x east, y up, z south).
    sylva::render::Camera camera;
    camera.position = glm::vec3(70.0f, world.groundHeight(70.0f, 190.0f) + 6.0f, 190.0f);
    camera.target = glm::vec3(110.0f, world.groundHeight(110.0f, 150.0f), 150.0f);
    camera.fovY = glm::radians(55.0f);
    sylva::render::fitClipPlanes(camera, world.bounds());

    world.advanceToFrame(0);
    sylva::render::RenderTarget target(width, height);
    target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    world.draw(camera, width, height, 0.0, &target.depth(), nullptr);
    sylva::savePng(out, target.readColor());
    std::printf("%s: %d x %d, %zu grass layer(s), drawn with %s\n", out.c_str(), width, height,
                world.grassCount(), context->description().c_str());
    return 0;
  } catch (const sylva::Error& e) {
    std::fprintf(stderr, "terrain_grass: %s\n", e.what());
    return 1;
  }
}

#include "Commands.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/media/Export.hpp>
#include <sylva/render/gpu/DemoScene.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/scene/gpu/GrassSimulation.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>

#include "cmd/CmdScene.hpp"
#include "flags/StreamFlags.hpp"
#include "flags/WorldFlags.hpp"
#include "view/Viewer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace sylva::app {

namespace {

/** The options of `sylva render`. */
struct Options {
  ContextFlags context;
  std::string scene = "terrain";
  WorldFlags world;
  StreamFlags stream;
  std::string frames;
  SceneRenderOptions sceneFile;
  CLI::Option* outOption = nullptr;
  CLI::Option* widthOption = nullptr;
  CLI::Option* heightOption = nullptr;
  double fps = 30.0;
  std::string gif;
  std::string view = "shaded";
  std::string out = "out/terrain.png";
  int width = 1280;
  int height = 720;
  double time = 1.0;
  render::DemoSettings demo;
  bool wireframe = false;
  std::string shaderDir;
};

/**
 * Draws `count` frames (`draw(time)` at --time + i / --fps) into `target`; with several, writes --gif (all
 * frames) and -o (the last) and returns true. One frame stays in `target` (false).
 */
bool renderFrames(const Options& o, int count, render::RenderTarget& target,
                  const std::function<void(double)>& draw) {
  std::vector<Image> frames;
  Progress progress("render", static_cast<std::size_t>(count));
  for (int f = 0; f < count; ++f) {
    draw(o.time + f / o.fps);
    if (count > 1) {
      frames.push_back(target.readColor());
    }
    progress.advance(1);
  }
  if (frames.empty()) {
    return false;
  }
  if (!o.gif.empty()) {
    media::writeGif(o.gif, frames, std::max(1, static_cast<int>(std::lround(100.0 / o.fps))));
    std::printf("%s\n", o.gif.c_str());
  }
  saveImage(o.out, frames.back());
  std::printf("%s\n", o.out.c_str());
  return true;
}

/**
 * A still of streamed terrain (--procedural-world, --pyramid): the view complete (every tile it wants loaded,
 * within the budgets), from --camera-pos/--look-at or the source's start camera.
 */
void renderStreamed(const Options& o) {
  if (o.world.grass.enabled || o.world.trees.enabled || !o.frames.empty() || !o.gif.empty()) {
    fail("--procedural-world and --pyramid render a still of streamed terrain alone (no --grass, --trees, "
         "--frames or --gif)");
  }
  if (o.view != "shaded" && o.view != "lod") {
    fail("--view {}: streamed terrain shows shaded or lod (level colours)", o.view);
  }
  const CameraFlags& flags = o.world.camera;
  if (flags.cameraPos.empty() != flags.lookAt.empty()) {
    fail("--camera-pos and --look-at: give both for streamed terrain (or neither: the source's start view)");
  }
  checkOutputFile(o.out, "--out");
  auto context = platform::createHeadlessContext(o.context.options());
  shader::Library library(o.shaderDir);
  const auto source = o.stream.source(o.world.terrain.source.seed);
  terrain::StreamedTerrain terrain(library, source, o.stream.options());
  render::Camera camera = streamStartCamera(*source, glm::radians(flags.fovDegrees));
  if (!flags.cameraPos.empty()) {
    const std::vector<float> p = parseNumbers("--camera-pos", flags.cameraPos, 3, "X,Y,Z");
    const std::vector<float> t = parseNumbers("--look-at", flags.lookAt, 3, "X,Y,Z");
    camera.position = glm::vec3(p[0], p[1], p[2]);
    camera.target = glm::vec3(t[0], t[1], t[2]);
  }
  render::RenderTarget target(o.width, o.height);
  const terrain::StreamedFrame frame = terrain.updateComplete(
      glm::dvec3(camera.position), glm::dvec3(camera.target), camera.fovY, target.aspect(), camera.farPlane);
  const render::Environment environment = terrain::StreamedTerrain::wideEnvironment(streamViewDepth(*source));
  target.begin(terrain::StreamedTerrain::clearColour(environment));
  terrain.draw(terrain.relativeCamera(camera.fovY, camera.nearPlane, camera.farPlane), o.width, o.height,
               o.time, o.view == "lod" ? terrain::StreamedView::LevelColours : terrain::StreamedView::Shaded,
               environment);
  const terrain::StreamerStats stats = terrain.streamer().stats();
  log::info("{}: {} tiles drawn, {} loaded, RAM {:.1f} MB of {:.0f}, GPU {} of {} layers", source->describe(),
            frame.tiles, stats.loaded, static_cast<double>(stats.peakBytes) / 1.0e6,
            static_cast<double>(terrain.streamer().budget()) / 1.0e6, frame.layersUsed, terrain.layers());
  saveImage(o.out, target.readColor());
  std::printf("%s\n", o.out.c_str());
}

} // namespace

void registerRender(CLI::App& app) {
  auto* command = app.add_subcommand(
      "render", "Render a scene headless into PNG images: a scene file (docs/scenes.md: a still, "
                "or a resumable frame sequence with --frames), or terrain with --grass/--trees");
  auto o = std::make_shared<Options>();
  o->context.add(*command);
  command
      ->add_option(
          "file", o->sceneFile.job.file,
          "A scene file (data/scenes/*.json): renders its output camera; with --frames A-B a numbered "
          "PNG sequence into --out DIR (resumable, --shard i/n, --gif/--mp4)")
      ->check(CLI::ExistingFile);
  addSceneRenderOptions(*command, o->sceneFile);
  command->add_option("--scene", o->scene, "terrain, or demo (the small built-in pipeline test scene)")
      ->check(CLI::IsMember({"terrain", "demo"}))
      ->capture_default_str();
  o->world.add(*command);
  o->stream.add(*command);
  command->add_option(
      "--frames", o->frames,
      "Scene file: frame numbers A-B (or A-B,C-D) of its fixed clock, written to --out DIR as "
      "frame_NNNNN.png. Otherwise: a count N of frames from --time on at --fps (wind, physics "
      "move); -o gets the last (default 1)");
  command->add_option("--fps", o->fps, "Frames per second of --frames")
      ->check(finiteRange(1.0, 240.0))
      ->capture_default_str();
  command->add_option("--gif", o->gif, "Also write the frames as an animated GIF here");
  command->add_option("--view", o->view, "Terrain view: shaded, lod (LOD colours), normals or splat")
      ->check(CLI::IsMember({"shaded", "lod", "normals", "splat"}))
      ->capture_default_str();
  o->outOption =
      command
          ->add_option("-o,--out", o->out,
                       "Output PNG path, or with a scene file and --frames the sequence's directory "
                       "(default out/<scene name>); directories are created")
          ->capture_default_str();
  o->widthOption =
      command->add_option("--width", o->width, "Image width in pixels (scene file: its output's)")
          ->check(CLI::Range(16, 16384))
          ->capture_default_str();
  o->heightOption =
      command->add_option("--height", o->height, "Image height in pixels (scene file: its output's)")
          ->check(CLI::Range(16, 16384))
          ->capture_default_str();
  command->add_option("--time", o->time, "Scene time in seconds (fixed clock: same time, same image)")
      ->check(finiteRange(-1.0e6, 1.0e6))
      ->capture_default_str();
  command->add_option("--patches", o->demo.patches, "Demo patches per side")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  command->add_flag("--wireframe", o->wireframe, "Draw triangle edges only");
  command
      ->add_option("--shader-dir", o->shaderDir,
                   "Read shaders from this directory instead of the embedded copies")
      ->check(CLI::ExistingDirectory);
  command->callback([o] {
    if (!o->sceneFile.job.file.empty()) {
      SceneRenderOptions scene = o->sceneFile;
      scene.job.frames = o->frames;
      scene.job.gif = o->gif;
      scene.job.out = o->outOption->count() > 0 ? o->out : std::string();
      scene.context = o->context.options();
      scene.shaderDir = o->shaderDir;
      scene.job.width = o->widthOption->count() > 0 ? o->width : 0;
      scene.job.height = o->heightOption->count() > 0 ? o->height : 0;
      renderSceneFile(scene);
      return;
    }
    if (!o->sceneFile.job.mp4.empty() || !o->sceneFile.job.camera.empty() ||
        o->sceneFile.job.shard != "0/1") {
      fail("--mp4, --camera and --shard need a scene file (sylva render SCENE.json ...)");
    }
    o->stream.check();
    if (o->stream.enabled()) {
      renderStreamed(*o);
      return;
    }
    int frameCount = 1;
    if (!o->frames.empty()) {
      char* end = nullptr;
      const long n = std::strtol(o->frames.c_str(), &end, 10);
      if (*end != '\0' || n < 1 || n > 100000) {
        fail("--frames {}: without a scene file, a count of frames in [1, 100000]", o->frames);
      }
      frameCount = static_cast<int>(n);
    }
    o->world.check(false);
    checkOutputFile(o->out, "--out");
    if (!o->gif.empty()) {
      checkOutputFile(o->gif, "--gif", "anim.gif");
    }
    auto context = platform::createHeadlessContext(o->context.options());
    shader::Library library(o->shaderDir);
    render::RenderTarget target(o->width, o->height);
    const render::Environment environment;
    if (o->scene == "demo") {
      target.begin(glm::vec4(environment.fogColor, 1.0f));
      render::DemoScene scene(library, o->demo);
      scene.render(scene.defaultCamera(), o->width, o->height, o->time, nullptr, o->wireframe);
    } else if (!o->world.grass.enabled && !o->world.trees.enabled) {
      // Terrain alone: the terrain's own frame (its debugging views, sea and fog by --fog).
      auto scene = o->world.terrain.build(library);
      const render::Camera camera = o->world.camera.camera(*scene, target.aspect());
      terrain::TerrainDrawOptions options = scene->drawOptions(camera, o->world.camera.fog);
      options.view = parseTerrainView(o->view);
      options.wireframe = o->wireframe;
      if (renderFrames(*o, frameCount, target, [&](double time) {
            target.begin(glm::vec4(options.environment.fogColor, 1.0f));
            scene->update(camera, target.aspect(), o->height);
            scene->draw(camera, o->width, o->height, time, nullptr, options);
          })) {
        return;
      }
    } else {
      // Grass, trees, bodies: the world the options describe, drawn by the scene's one frame path (sun
      // shadows, sky, aerial perspective), as a scene file would be.
      scene::SceneWorld world(library, o->world.desc("render", false));
      const render::Camera camera = o->world.start(world, target.aspect());
      scene::SceneDrawOptions draw;
      draw.terrainView = parseTerrainView(o->view);
      draw.wireframe = o->wireframe;
      draw.grassView = o->world.grass.grassView();
      draw.treeView = o->world.trees.treeView();
      draw.treeLod = o->world.trees.lod;
      world.setDrawOptions(draw);
      const bool kept = renderFrames(*o, frameCount, target, [&](double time) {
        world.advanceTo(time);
        target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        world.draw(camera, o->width, o->height, time, &target.depth(), nullptr);
      });
      if (const scene::GrassSimulation* simulation = world.simulation()) {
        const grass::SimStats& s = simulation->stats();
        log::info(
            "grass simulation: {} bodies, {} tiles ({} blades) simulated at the end, {} refused (pool full)",
            simulation->bodies(), s.activeTiles, s.simulatedBlades, s.refusedTiles);
      }
      if (kept) {
        return;
      }
    }
    saveImage(o->out, target.readColor());
    std::printf("%s\n", o->out.c_str());
  });
}

} // namespace sylva::app

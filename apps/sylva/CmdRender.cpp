#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/folding/Export.hpp>
#include <sylva/render/DemoScene.hpp>
#include <sylva/render/RenderTarget.hpp>

#include "CmdScene.hpp"
#include "GrassFlags.hpp"
#include "GrassSim.hpp"
#include "TerrainFlags.hpp"
#include "TreeFlags.hpp"

#include <cmath>
#include <cstdio>

namespace sylva::app {

void registerRender(CLI::App& app) {
  auto* command = app.add_subcommand(
      "render", "Render a scene headless into PNG images: a scene file (docs/scenes.md: a still, "
                "or a resumable frame sequence with --frames), or terrain with --grass/--trees");
  struct Options {
    ContextFlags context;
    std::string scene = "terrain";
    TerrainFlags terrain;
    CameraFlags camera;
    GrassFlags grass;
    SimulationFlags simulation;
    TreeFlags trees;
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
  auto o = std::make_shared<Options>();
  o->context.add(*command);
  command
      ->add_option(
          "file", o->sceneFile.file,
          "A scene file (data/scenes/*.json): renders its output camera; with --frames A-B a numbered "
          "PNG sequence into --out DIR (resumable, --shard i/n, --gif/--mp4)")
      ->check(CLI::ExistingFile);
  addSceneRenderOptions(*command, o->sceneFile);
  command->add_option("--scene", o->scene, "terrain, or demo (the small built-in pipeline test scene)")
      ->check(CLI::IsMember({"terrain", "demo"}))
      ->capture_default_str();
  o->terrain.add(*command);
  o->camera.add(*command);
  o->grass.add(*command);
  o->simulation.add(*command);
  o->trees.add(*command);
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
    if (!o->sceneFile.file.empty()) {
      SceneRenderOptions scene = o->sceneFile;
      scene.frames = o->frames;
      scene.gif = o->gif;
      scene.out = o->outOption->count() > 0 ? o->out : std::string();
      scene.context = o->context.options();
      scene.shaderDir = o->shaderDir;
      scene.width = o->widthOption->count() > 0 ? o->width : 0;
      scene.height = o->heightOption->count() > 0 ? o->height : 0;
      renderSceneFile(scene);
      return;
    }
    if (!o->sceneFile.mp4.empty() || !o->sceneFile.camera.empty() || o->sceneFile.shard != "0/1") {
      fail("--mp4, --camera and --shard need a scene file (sylva render SCENE.json ...)");
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
    o->camera.check();
    if (o->grass.enabled) {
      o->grass.check();
    }
    if (o->simulation.enabled() && !o->grass.enabled) {
      fail("--physics: needs --grass (the bodies move through the grass field)");
    }
    if (o->trees.enabled) {
      o->trees.check();
    }
    if (o->simulation.enabled()) {
      (void)o->simulation.solverSettings();
      (void)o->simulation.poolSettings();
    }
    auto context = platform::createHeadlessContext(o->context.options());
    shader::Library library(o->shaderDir);
    render::RenderTarget target(o->width, o->height);
    const render::Environment environment;
    if (o->scene == "demo") {
      target.begin(glm::vec4(environment.fogColor, 1.0f));
      render::DemoScene scene(library, o->demo);
      scene.render(scene.defaultCamera(), o->width, o->height, o->time, nullptr, o->wireframe);
    } else {
      auto scene = o->terrain.build(library);
      std::unique_ptr<grass::GrassRenderer> grass;
      render::Camera camera = o->camera.camera(*scene, target.aspect());
      if (o->grass.enabled) {
        auto field = o->grass.buildField(*scene);
        grass = std::make_unique<grass::GrassRenderer>(library, field, o->grass.cullSettings());
        log::info(
            "grass: {} blade types, {} tiles of {} m, about {:.3g} blades in the field, patch {:.2f} MB",
            field->types().size(), static_cast<long long>(field->layout().tilesX) * field->layout().tilesZ,
            field->layout().tileSize, field->estimateBlades(),
            static_cast<double>(grass::patchBytes(field->patch().size(), field->types().size())) / 1e6);
        if (o->camera.cameraPos.empty()) {
          camera = grassCamera(*scene, *field, glm::radians(o->camera.fovDegrees), o->grass.windDirection);
          const float e = scene->exaggeration();
          log::info("grass: camera at {:.1f},{:.1f},{:.1f} looking at {:.1f},{:.1f},{:.1f} (--camera-pos, "
                    "--look-at)",
                    camera.position.x, camera.position.y / e, camera.position.z, camera.target.x,
                    camera.target.y / e, camera.target.z);
        }
      }
      std::unique_ptr<trees::ForestScene> forest;
      if (o->trees.enabled) {
        std::shared_ptr<trees::Forest> placed = o->trees.buildForest(*scene);
        forest = std::make_unique<trees::ForestScene>(library, placed, o->trees.wind);
        forest->setBark(o->trees.barkSources());
        o->trees.applyFoliage(*forest);
        o->trees.applyFarField(*forest, *scene);
        log::info("trees: {} trees, {} pieces, {} joints, {}", placed->trees.size(),
                  forest->renderer().instances().instances.size(), placed->jointCount,
                  o->trees.wind ? "in the wind (--no-trees-wind: rest pose)" : "rest pose");
        if (o->camera.cameraPos.empty() && !o->grass.enabled) {
          camera = forestCamera(*scene, *placed, glm::radians(o->camera.fovDegrees));
        }
      }
      std::unique_ptr<scene::GrassSimulation> simulation;
      if (o->simulation.enabled()) {
        simulation = std::make_unique<scene::GrassSimulation>(
            library, scene->field(), *grass, grass->fieldPointer(), o->simulation.settings());
        const glm::vec2 drop = ballDropPoint(scene->field(), grass->field(), camera);
        simulation->spawnBalls(drop, 1.5f, o->simulation.balls, o->simulation.seed, 0.5f);
        if (o->camera.cameraPos.empty()) {
          camera = ballCamera(*scene, drop, glm::radians(o->camera.fovDegrees));
        }
      }
      terrain::TerrainDrawOptions options = scene->drawOptions(camera, o->camera.fog);
      options.view = parseTerrainView(o->view);
      options.wireframe = o->wireframe;
      grass::GrassDrawOptions grassOptions;
      grassOptions.view = o->grass.grassView();
      grassOptions.wind = o->grass.wind();
      std::vector<Image> frames;
      Progress progress("render", static_cast<std::size_t>(frameCount));
      for (int f = 0; f < frameCount; ++f) {
        const double time = o->time + f / o->fps;
        if (simulation) {
          simulation->advance(time - o->time, grassOptions.wind);
        }
        target.begin(glm::vec4(environment.fogColor, 1.0f));
        drawTerrainWithGrass(*scene, grass.get(), camera, o->width, o->height, time, options, grassOptions);
        if (forest) {
          // Fixed steps from --time on (the first frame after the same warm-up): the same image for the same
          // --time, and enough steps per frame for any --fps.
          forest->advance(time, grassOptions.wind,
                          static_cast<int>(std::ceil(1.0 / (o->fps * trees::kForestWindStep))) + 1);
          trees::TreeDrawOptions treeOptions;
          treeOptions.view = o->trees.treeView();
          treeOptions.environment = options.environment;
          forest->draw(camera, o->width, o->height, time, o->trees.lod, treeOptions);
        }
        if (simulation) {
          simulation->drawBodies(camera, o->width, o->height, time, options.environment);
        }
        if (frameCount > 1) {
          frames.push_back(target.readColor());
        }
        progress.advance(1);
      }
      if (simulation) {
        const grass::SimStats& s = simulation->stats();
        log::info(
            "grass simulation: {} bodies, {} tiles ({} blades) simulated at the end, {} refused (pool full)",
            simulation->bodies(), s.activeTiles, s.simulatedBlades, s.refusedTiles);
      }
      if (!o->gif.empty()) {
        folding::writeGif(o->gif, frames, std::max(1, static_cast<int>(std::lround(100.0 / o->fps))));
        std::printf("%s\n", o->gif.c_str());
      }
      if (!frames.empty()) {
        saveImage(o->out, frames.back());
        std::printf("%s\n", o->out.c_str());
        return;
      }
    }
    saveImage(o->out, target.readColor());
    std::printf("%s\n", o->out.c_str());
  });
}

} // namespace sylva::app

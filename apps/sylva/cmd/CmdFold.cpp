// `sylva fold <sub>`: folding textures from a project file (docs/folding.md). synth writes the data textures,
// render writes PNG frames, GIF, sprite sheet or video, view previews live with sliders, export-shader writes
// the GLSL and its textures for a game, info describes a project. Every input error is one line naming the
// file and the JSON field, found before any output is written.
#include "cmd/CmdFoldFlow.hpp"
#include "Commands.hpp"
#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/media/Animation.hpp>
#include <sylva/media/Export.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/ProjectFile.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Session.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/folding/Templates.hpp>

#ifdef SYLVA_HAVE_FOLDING_GPU
#include <sylva/folding/gpu/FoldRenderer.hpp>
#include <sylva/folding/gpu/ShaderExport.hpp>
#include <sylva/folding_ui/Editor.hpp>
#include <sylva/folding_ui/Viewer.hpp>
#include <sylva/shader/Library.hpp>
#endif

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sylva::app {
namespace {

namespace fs = std::filesystem;
using namespace sylva::folding;
using namespace sylva::media;

constexpr const char* kFunctionNames[] = {"linear", "piecewise", "exponential", "sigmoid", "sine"};
/** Largest total size of the frames a render keeps in memory before writing, bytes. */
constexpr double kMaxFrameBytes = 4.0 * 1024.0 * 1024.0 * 1024.0;

std::optional<PositionFunction::Type> parseFunction(const std::string& name) {
  for (int i = 0; i < 5; ++i) {
    if (name == kFunctionNames[i]) {
      return static_cast<PositionFunction::Type>(i);
    }
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------------------
// synth

void registerFoldSynth(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "synth",
      "Synthesise the folding textures of a project: colour atlas, init and jump textures (16-bit PNG "
      "or EXR), folding.json, and the pictures vectors.png, t0.png and t1.png");
  struct Options {
    std::string project;
    std::string out;
    int arrowStep = 0;
  };
  auto o = std::make_shared<Options>();
  command->add_option("project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_option("-o,--out", o->out, "Output directory (created)")->required();
  command->add_option("--arrow-step", o->arrowStep, "Texels between arrows in vectors.png (0: automatic)")
      ->check(CLI::Range(0, 4096));
  command->callback([o] {
    const LoadedProject l = loadProjectFile(o->project);
    const auto start = std::chrono::steady_clock::now();
    SynthesisStats stats;
    const Textures textures = synthesizeLoaded(l, &stats);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const fs::path dir = o->out;
    saveTextures(dir, l.project, textures);
    const int step =
        o->arrowStep > 0 ? o->arrowStep : std::max(8, std::max(textures.width(), textures.height()) / 48);
    saveImage(dir / "vectors.png", vectorFieldPicture(textures, step));
    saveImage(dir / "t0.png", thresholdHeatMap(textures, 0));
    saveImage(dir / "t1.png", thresholdHeatMap(textures, 1));
    std::fputs(describeSynthesis(l, textures, stats, seconds).c_str(), stdout);
    std::printf("%s\n", dir.string().c_str());
  });
}

// ---------------------------------------------------------------------------------------------------------
// render

struct RenderOptions {
  ContextFlags context;
  std::string project;
  std::string out;
  int frames = 0;
  double fps = 25.0;
  double duration = 0.0;
  std::string gif;
  std::string mp4;
  std::string webm;
  std::string sprites;
  int columns = 0;
  std::string renderer = "cpu";
  std::string image;
  double speed = 1.0;
  double shift = 0.0;
  std::string function;
  std::string shaderDir;
};

/** Renders `count` frames at t = i / fps of image `index`, cropped to its atlas entry. */
std::vector<Image> renderFrames(const RenderOptions& o, const LoadedProject& l, const Textures& textures,
                                const std::vector<Profile>& profiles, int index, int count) {
  const AtlasEntry& entry = textures.atlas.entries[static_cast<std::size_t>(index)];
  if (o.renderer == "gl") {
#ifdef SYLVA_HAVE_FOLDING_GPU
    auto context = platform::createHeadlessContext(o.context.options());
    shader::Library library(o.shaderDir);
    folding::gpu::FoldRenderer renderer(library);
    renderer.upload(textures, profiles, l.project.jumpLayers);
    return folding::renderFrames(count, l.file,
                                 [&](int i) { return cropToEntry(renderer.render(i / o.fps), entry); });
#else
    fail("--renderer gl: this sylva was built without the folding GPU renderer");
#endif
  }
  return folding::renderFrames(count, l.file, [&](int i) {
    return cropToEntry(renderFrame(textures, profiles, l.project.jumpLayers, i / o.fps, workerCount()),
                       entry);
  });
}

void runRender(const RenderOptions& o) {
  // Everything that can be wrong with the options is found before any work.
  requireExtension("--gif", o.gif, ".gif");
  requireExtension("--mp4", o.mp4, ".mp4");
  requireExtension("--webm", o.webm, ".webm");
  requireExtension("--sprites", o.sprites, ".png");
  if ((!o.mp4.empty() || !o.webm.empty()) && !ffmpegAvailable()) {
    fail("ffmpeg not found on PATH: install it (apt install ffmpeg) or write --gif/--sprites/--frames "
         "instead");
  }
  std::optional<PositionFunction::Type> function;
  if (!o.function.empty()) {
    function = parseFunction(o.function);
  }
  const LoadedProject l = loadProjectFile(o.project);
  const int index = imageIndexOption(l.project, "--image", o.image);
  PlaybackOptions playback;
  playback.speed = o.speed;
  playback.shift = o.shift;
  playback.function = function;
  const std::vector<Profile> profiles = applyPlayback(l.project.profiles, playback);
  const LoopPeriod loop = loopPeriod(profiles);
  if (o.duration <= 0.0 && !loop.seamless) {
    std::string periods;
    for (const Profile& p : profiles) {
      periods += fmt::format("{}{} {:g} s", periods.empty() ? "" : ", ", p.id, p.periodS);
    }
    log::warn("{}: the profile periods ({}) have no common multiple within {} cycles or {:g} s, so the loop "
              "jumps at {:g} s: make them multiples of one period, or give --duration",
              o.project, periods, kMaxLoopCycles, kMaxLoopS, loop.seconds);
  }
  const double duration = o.duration > 0.0 ? o.duration : loop.seconds;
  const int count = o.frames > 0 ? o.frames : std::max(1, static_cast<int>(std::lround(duration * o.fps)));
  // The frames are the image's atlas crop, at most the whole image.
  const Image& shown = l.images.images[static_cast<std::size_t>(index)];
  const glm::ivec2 size(shown.width(), shown.height());
  if (static_cast<double>(count) * size.x * size.y * 4.0 > kMaxFrameBytes) {
    fail("--frames: {} frames of {}x{} need more than {:.0f} GiB in memory; render fewer or shorter", count,
         size.x, size.y, kMaxFrameBytes / (1024.0 * 1024.0 * 1024.0));
  }
  const bool defaultOutput = o.gif.empty() && o.mp4.empty() && o.webm.empty() && o.sprites.empty();
  const std::string pngDir = !o.out.empty() ? o.out : defaultOutput ? std::string("out/fold") : std::string();

  const Textures textures = synthesizeLoaded(l);
  const Rect shownRect = textures.atlas.entries[static_cast<std::size_t>(index)].atlasRect();
  const int columns = std::min(
      count, o.columns > 0 ? o.columns : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count)))));
  if (!o.sprites.empty() &&
      (static_cast<long long>(columns) * shownRect.width() > 65536 ||
       static_cast<long long>((count + columns - 1) / columns) * shownRect.height() > 65536)) {
    fail("--sprites {}: {} frames of {}x{} in {} columns make a sheet larger than 65536 pixels; change "
         "--columns "
         "or render fewer frames",
         o.sprites, count, shownRect.width(), shownRect.height(), columns);
  }
  const std::vector<Image> frames = renderFrames(o, l, textures, profiles, index, count);

  AnimationOutputs outputs;
  outputs.mp4 = o.mp4;
  outputs.webm = o.webm;
  outputs.sprites = o.sprites;
  outputs.columns = columns;
  outputs.gif = o.gif;
  outputs.pngDir = pngDir;
  outputs.fps = o.fps;
  for (const std::string& line : writeAnimation(outputs, frames, o.project)) {
    std::printf("%s\n", line.c_str());
  }
}

void registerFoldRender(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "render", "Render the animation of a project: PNG frames, animated GIF, sprite sheet (PNG + JSON), or "
                "MP4/WebM through the ffmpeg program");
  auto o = std::make_shared<RenderOptions>();
  command->add_option("project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_option("-o,--out,--png-dir", o->out,
                      "Directory for the PNG frames frame_NNNN.png (default out/fold when no other output is "
                      "named)");
  command->add_option("--frames", o->frames, "Number of frames (default: duration x fps)")
      ->check(CLI::Range(1, 100000));
  command->add_option("--fps", o->fps, "Frames per second")
      ->check(finiteRange(0.1, 1000.0))
      ->capture_default_str();
  command
      ->add_option(
          "--duration", o->duration,
          "Seconds to render (default: one seamless loop, the least common multiple of the profile periods)")
      ->check(finiteRange(1e-3, 3600.0));
  command->add_option("--gif", o->gif,
                      "Write an animated GIF (a palette per frame, error diffusion, loops forever)");
  command->add_option("--mp4", o->mp4, "Write an H.264 MP4 through ffmpeg");
  command->add_option("--webm", o->webm, "Write a VP9 WebM through ffmpeg");
  command->add_option("--sprites", o->sprites,
                      "Write a sprite sheet PNG and, beside it, a JSON of frame rectangles and times");
  command
      ->add_option("--columns", o->columns, "Sprite sheet columns (default: about the square root of frames)")
      ->check(CLI::Range(1, 100000));
  command->add_option("--renderer", o->renderer, "cpu (the reference) or gl (headless OpenGL)")
      ->check(CLI::IsMember({"cpu", "gl"}))
      ->capture_default_str();
  command->add_option("--image", o->image, "Id of the image to show (default: the project's canvas)");
  command->add_option("--speed", o->speed, "Playback speed (multiplies time)")
      ->check(finiteRange(0.01, 100.0))
      ->capture_default_str();
  command->add_option("--shift", o->shift, "Cycles added to every profile's shift")
      ->check(finiteRange(-1000.0, 1000.0))
      ->capture_default_str();
  command->add_option("--function", o->function, "Replace every profile's position function type")
      ->check(CLI::IsMember({"linear", "piecewise", "exponential", "sigmoid", "sine"}));
  command->add_option("--shader-dir", o->shaderDir, "gl: read shaders from this directory")
      ->check(CLI::ExistingDirectory);
  o->context.add(*command);
  command->callback([o] { runRender(*o); });
}

// ---------------------------------------------------------------------------------------------------------
// view

void registerFoldView(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "view", "Preview a project live in a window with sliders for speed, shift, position function and time "
              "(Space: pause; Tab: hide the panel; wheel or +/-: zoom, right/middle drag: pan, Home: fit, 1: "
              "one texel per pixel)");
#ifdef SYLVA_HAVE_FOLDING_GPU
  auto o = std::make_shared<folding_ui::ViewerOptions>();
  command->add_option("project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_option("--image", o->image, "Id of the image to show first (default: the project's canvas)");
  command->add_option("--shader-dir", o->shaderDir, "Read shaders from this directory")
      ->check(CLI::ExistingDirectory);
  addScriptedWindowOptions(*command, o->frames, o->screenshot, o->fixedStep);
  command->add_flag("--no-ui", o->noUi, "Start with the panel hidden");
  command->add_option("--zoom", o->zoom, "Zoom at start, screen pixels per image pixel (0: fit the window)")
      ->check(CLI::Range(0.0, 32.0));
  command->callback([o] { folding_ui::runViewer(*o); });
#else
  command->allow_extras();
  command->callback([] { fail("fold view: this sylva was built without the folding GPU renderer"); });
#endif
}

#ifdef SYLVA_HAVE_FOLDING_GPU
void registerFoldEdit(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "edit",
      "The folding-texture editor: draw motion zones and anchors on an image, shape the timing, watch "
      "the live preview, export (docs/folding-editor.md)");
  auto o = std::make_shared<folding_ui::EditorOptions>();
  command->add_option("inputs", o->inputs,
                      "A project file (.json) to open, or image files to start a new project from (none: the "
                      "start screen)");
  command->add_option("--project", o->project,
                      "Where a new project is saved (default: <first image>.fold.json next to it)");
  command->add_option("--width", o->width, "Window width")
      ->check(CLI::Range(640, 16384))
      ->capture_default_str();
  command->add_option("--height", o->height, "Window height")
      ->check(CLI::Range(480, 16384))
      ->capture_default_str();
  command->add_option("--zoom", o->zoom, "Canvas zoom at start (0: fit the image)")
      ->check(CLI::Range(0.0, 32.0));
  command
      ->add_option("--autosave", o->autosaveSeconds, "Seconds between autosaves of unsaved work (0: never)")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  command->add_option("--paused-at", o->pausedAt, "Start with the preview paused at this time (seconds)")
      ->check(CLI::Range(0.0, 1e6));
  command->add_flag("--no-recover", o->noRecover, "Ignore an autosave sidecar newer than the project file");
  command->add_option("--recent-file", o->recentFile,
                      "The recent-files list (default: $XDG_CONFIG_HOME/sylva/recent-folding.json)");
  command->add_option("--shader-dir", o->shaderDir, "Read shaders from this directory")
      ->check(CLI::ExistingDirectory);
  addScriptedWindowOptions(*command, o->frames, o->screenshot, o->fixedStep);
  command->callback([o] { folding_ui::runEditor(*o); });
}
#endif

// ---------------------------------------------------------------------------------------------------------
// export-shader

void registerExportShader(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "export-shader", "Write a self-contained GLSL fragment shader that plays the project, with its "
                       "textures and a README of the encoding, for use in a game engine");
  struct Options {
    ContextFlags context;
    std::string project;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  command->add_option("project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_option("-o,--out", o->out, "Output directory (created)")->required();
  command->callback([o] {
#ifdef SYLVA_HAVE_FOLDING_GPU
    const LoadedProject l = loadProjectFile(o->project);
    const Textures textures = synthesizeLoaded(l);
    const shader::Library library;
    const EncodedInfo info = folding::gpu::encodedInfo(l.project, textures);
    // The shader text is made (and checked against the project) before any file is written.
    (void)folding::gpu::exportedShaderSource(library, l.project, info);
    saveTextures(o->out, l.project, textures);
    folding::gpu::exportShader(o->out, library, l.project, info);
    std::printf("%s\n", o->out.c_str());
#else
    fail("fold export-shader: this sylva was built without the folding GPU renderer");
#endif
  });
}

void registerExportWeb(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "export-web",
      "Write one self-contained HTML file (WebGL 2, textures embedded) that plays the project's "
      "canvas image in a browser with the same equations");
  struct Options {
    std::string project;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  command->add_option("project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_option("-o,--out", o->out, "Output HTML file")->required();
  command->callback([o] {
#ifdef SYLVA_HAVE_FOLDING_GPU
    const LoadedProject l = loadProjectFile(o->project);
    const Textures textures = synthesizeLoaded(l);
    folding::gpu::writeWebPreview(o->out, shader::Library(), l.project, textures);
    std::printf("%s\n", o->out.c_str());
#else
    fail("fold export-web: this sylva was built without the folding GPU renderer");
#endif
  });
}

// ---------------------------------------------------------------------------------------------------------
// info

void registerFoldInfo(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "info", "Describe a project: images and their sizes, atlas layout, profiles, zones and their tools");
  struct Options {
    std::string project;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  command->add_option("project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_flag("--json", o->json, "Print JSON: the canonical project plus image sizes and the atlas");
  command->callback([o] {
    const LoadedProject l = loadProjectFile(o->project);
    const Atlas atlas = namingFile(l.file, [&] { return packAtlas(l.project, l.images); });
    if (o->json) {
      std::cout << describeProjectJson(l, atlas).dump(2) << "\n";
    } else {
      std::cout << describeProject(l, atlas);
    }
  });
}

} // namespace

// ---------------------------------------------------------------------------------------------------------
// template

void registerFoldTemplate(CLI::App& fold) {
  std::string names;
  for (MotionTemplate m : motionTemplates()) {
    names += (names.empty() ? "" : ", ") + std::string(motionTemplateName(m));
  }
  auto* command = fold.add_subcommand(
      "template", "Apply a motion template (" + names +
                      ") to one zone of a project: its tools, folding region, interpolation and a profile");
  struct Options {
    std::string project;
    std::string zone;
    std::string name;
    double strength = 0.0;
    std::vector<double> direction{0.0, 1.0};
    double period = 0.0;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  command->add_option("project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_option("--zone", o->zone, "Id of the zone to animate")->required();
  std::vector<std::string> choices;
  for (MotionTemplate m : motionTemplates()) {
    choices.emplace_back(motionTemplateName(m));
  }
  command->add_option("--template", o->name, "Template name")->required()->check(CLI::IsMember(choices));
  command
      ->add_option(
          "--strength", o->strength,
          "Largest motion in pixels (0: a fraction of the zone; blink: 0 and anything larger close the eye)")
      ->check(finiteRange(0.0, 1e4))
      ->capture_default_str();
  command
      ->add_option("--direction", o->direction,
                   "wave_swash: direction the water advances, X Y; flag_ripple: the way the wind blows along "
                   "the flag (its sign on the long axis; default from the left or top)")
      ->expected(2)
      ->check(finiteRange(-1e4, 1e4));
  command->add_option("--period", o->period, "Profile period in seconds (0: the template's default)")
      ->check(finiteRange(0.0, 1e6))
      ->capture_default_str();
  command->add_option("-o,--out", o->out, "Write the edited project here (default: overwrite the input)");
  command->callback([o] {
    const Project project = loadProject(o->project);
    const int zone = zoneIndexOption(project, o->project, o->zone);
    EditHistory history(project);
    TemplateParams params;
    params.strength = o->strength;
    params.direction = Vec2(o->direction[0], o->direction[1]);
    params.periodS = o->period;
    applyMotionTemplate(history, zone, *parseMotionTemplate(o->name), params);
    const std::filesystem::path out =
        o->out.empty() ? std::filesystem::path(o->project) : std::filesystem::path(o->out);
    // File names stay relative to the project's images: rewritten for a new location.
    const Project edited = o->out.empty() ? history.project() : rebasedProject(history.project(), out);
    saveProject(out, edited);
    std::printf("%s: zone '%s' now plays '%s'\n", out.string().c_str(), o->zone.c_str(), o->name.c_str());
  });
}

void registerFold(CLI::App& app) {
  auto* command = app.add_subcommand(
      "fold", "Folding textures: animate still images from a project file (docs/folding.md)");
  command->require_subcommand(1);
  registerFoldSynth(*command);
  registerFoldRender(*command);
  registerFoldView(*command);
  registerExportShader(*command);
  registerExportWeb(*command);
  registerFoldInfo(*command);
  registerFoldTemplate(*command);
  registerFoldFlow(*command);
#ifdef SYLVA_HAVE_FOLDING_GPU
  registerFoldEdit(*command);
#endif
}

} // namespace sylva::app

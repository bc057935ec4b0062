// `sylva fold <sub>`: folding textures from a project file (docs/folding.md). synth writes the data textures,
// render writes PNG frames, GIF, sprite sheet or video, view previews live with sliders, export-shader writes
// the GLSL and its textures for a game, info describes a project. Every input error is one line naming the
// file and the JSON field, found before any output is written.
#include "cmd/CmdFoldFlow.hpp"
#include "Commands.hpp"
#include "flags/SourceOptions.hpp"

#include <imgui.h>
#include <sylva/core/Error.hpp>
#include <sylva/ui/ImageCanvas.hpp>
#include <sylva/ui/WindowShell.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/media/Export.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Session.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/folding/Templates.hpp>

#ifdef SYLVA_HAVE_FOLDING_GPU
#include <sylva/folding/gpu/FoldRenderer.hpp>
#include <sylva/folding/gpu/ShaderExport.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/shader/Library.hpp>

#include "fold/FoldEdit.hpp"

#include <GLFW/glfw3.h>
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

const char* functionName(PositionFunction::Type type) {
  return kFunctionNames[static_cast<int>(type)];
}

std::optional<PositionFunction::Type> parseFunction(const std::string& name) {
  for (int i = 0; i < 5; ++i) {
    if (name == kFunctionNames[i]) {
      return static_cast<PositionFunction::Type>(i);
    }
  }
  return std::nullopt;
}

const char* loopName(LoopMode mode) {
  return mode == LoopMode::PingPong ? "ping-pong" : mode == LoopMode::Crossfade ? "crossfade" : "none";
}

const char* interpName(Interpolation::Type type) {
  return type == Interpolation::Type::Shepard           ? "shepard"
         : type == Interpolation::Type::ModifiedShepard ? "modified_shepard"
                                                        : "modified_shepard_random";
}

const char* foldingName(Folding::Type type) {
  return type == Folding::Type::Polygons ? "polygons"
         : type == Folding::Type::Mask   ? "mask"
         : type == Folding::Type::Object ? "object"
                                         : "none";
}

const char* toolName(const Tool& tool) {
  static constexpr const char* kNames[] = {"translate", "scale", "points",  "curve",
                                           "lasso",     "zero",  "fly_over"};
  return kNames[tool.index()];
}

/** A project with its images, loaded and validated (errors name the file and the field). */
struct Loaded {
  std::string where;
  Project project;
  ProjectImages images;
};

Loaded load(const std::string& file) {
  Loaded l;
  l.where = file;
  l.project = loadProject(file);
  l.images = loadProjectImages(l.project, l.where);
  return l;
}

/**
 * Runs `work`, prefixing the project file to errors that do not name it yet (the atlas packer reports
 * "zones[0].tools: ..." without knowing the file).
 */
template <typename F> auto withFileName(const Loaded& l, F&& work) {
  try {
    return work();
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.rfind(l.where, 0) == 0) {
      throw;
    }
    fail("{}: {}", l.where, message);
  }
}

/** Synthesises with a progress line; Ctrl-C cancels with the one-line error. */
Textures synthesizeWithProgress(const Loaded& l, SynthesisStats* stats = nullptr) {
  Progress progress("synthesis", std::max<std::size_t>(synthesisRows(l.project, l.images), 1));
  SynthesisStats own;
  SynthesisStats& s = stats ? *stats : own;
  Textures textures = withFileName(l, [&] { return synthesize(l.project, l.images, &progress, &s); });
  if (progress.cancelled()) {
    fail("{}: synthesis cancelled", l.where);
  }
  for (const std::string& warning : stillZoneWarnings(l.project, s)) {
    log::warn("{}: {}", l.where, warning);
  }
  return textures;
}

/** Index of image `id` (default: the canvas); throws naming the option and listing the images. */
int imageOption(const Project& project, const std::string& id) {
  if (id.empty()) {
    return project.canvasIndex();
  }
  const int index = project.imageIndex(id);
  if (index < 0) {
    std::string ids;
    for (const ImageEntry& e : project.images) {
      ids += (ids.empty() ? "" : ", ") + e.id;
    }
    fail("--image: no image '{}' in the project (images: {})", id, ids);
  }
  return index;
}

void requireExtensionIfGiven(const std::string& option, const std::string& path, const std::string& ext) {
  if (!path.empty() && lowerExtension(path) != ext) {
    fail("{} {}: expected a {} file", option, path, ext);
  }
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
    const Loaded l = load(o->project);
    const auto start = std::chrono::steady_clock::now();
    SynthesisStats stats;
    const Textures textures = synthesizeWithProgress(l, &stats);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const fs::path dir = o->out;
    saveTextures(dir, l.project, textures);
    const int step =
        o->arrowStep > 0 ? o->arrowStep : std::max(8, std::max(textures.width(), textures.height()) / 48);
    saveImage(dir / "vectors.png", vectorFieldPicture(textures, step));
    saveImage(dir / "t0.png", thresholdHeatMap(textures, 0));
    saveImage(dir / "t1.png", thresholdHeatMap(textures, 1));
    std::printf("%s: atlas %dx%d, %zu images, %zu zones, %zu jump layer%s%s\n", l.where.c_str(),
                textures.width(), textures.height(), l.project.images.size(), l.project.zones.size(),
                textures.jump.size(), textures.jump.size() == 1 ? "" : "s",
                textures.fold.empty() ? "" : ", extra fold intervals");
    std::printf("  %zu anchors, %zu zone texels, %zu folded, %zu with several intervals; jumpMax %.3f px; "
                "%.2f s\n",
                stats.anchors, stats.zonePixels, stats.foldedPixels, stats.multiInterval, textures.jumpMax(),
                seconds);
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
std::vector<Image> renderFrames(const RenderOptions& o, const Loaded& l, const Textures& textures,
                                const std::vector<Profile>& profiles, int index, int count) {
  const AtlasEntry& entry = textures.atlas.entries[static_cast<std::size_t>(index)];
  std::vector<Image> frames;
  frames.reserve(static_cast<std::size_t>(count));
  Progress progress("rendering frames", static_cast<std::size_t>(count));
  const auto check = [&] {
    if (progress.cancelled()) {
      fail("{}: rendering cancelled", l.where);
    }
  };
  if (o.renderer == "gl") {
#ifdef SYLVA_HAVE_FOLDING_GPU
    auto context = platform::createHeadlessContext(o.context.options());
    shader::Library library(o.shaderDir);
    folding::gpu::FoldRenderer renderer(library);
    renderer.upload(textures, profiles, l.project.jumpLayers);
    for (int i = 0; i < count; ++i) {
      check();
      frames.push_back(cropToEntry(renderer.render(i / o.fps), entry));
      progress.advance();
    }
#else
    fail("--renderer gl: this sylva was built without the folding GPU renderer");
#endif
  } else {
    for (int i = 0; i < count; ++i) {
      check();
      frames.push_back(cropToEntry(
          renderFrame(textures, profiles, l.project.jumpLayers, i / o.fps, workerCount()), entry));
      progress.advance();
    }
  }
  check();
  return frames;
}

void runRender(const RenderOptions& o) {
  // Everything that can be wrong with the options is found before any work.
  requireExtensionIfGiven("--gif", o.gif, ".gif");
  requireExtensionIfGiven("--mp4", o.mp4, ".mp4");
  requireExtensionIfGiven("--webm", o.webm, ".webm");
  requireExtensionIfGiven("--sprites", o.sprites, ".png");
  if ((!o.mp4.empty() || !o.webm.empty()) && !ffmpegAvailable()) {
    fail("ffmpeg not found on PATH: install it (apt install ffmpeg) or write --gif/--sprites/--frames "
         "instead");
  }
  std::optional<PositionFunction::Type> function;
  if (!o.function.empty()) {
    function = parseFunction(o.function);
  }
  const Loaded l = load(o.project);
  const int index = imageOption(l.project, o.image);
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

  const Textures textures = synthesizeWithProgress(l);
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

  // All outputs or none: a live Progress turns Ctrl-C into a request checked after each file (the handler
  // otherwise ends the process between two outputs, leaving the first), and a failure or a cancellation part
  // way removes every file this run wrote. Video first: it is the output most likely to fail (ffmpeg,
  // codecs), and then nothing else is written.
  const int digits = std::max(4, static_cast<int>(std::to_string(count - 1).size()));
  const std::size_t files = (o.mp4.empty() ? 0 : 1) + (o.webm.empty() ? 0 : 1) + (o.sprites.empty() ? 0 : 2) +
                            (o.gif.empty() ? 0 : 1) + (pngDir.empty() ? 0 : static_cast<std::size_t>(count));
  Progress writing("writing", std::max<std::size_t>(files, 1));
  std::vector<fs::path> written;
  std::error_code ec;
  const bool pngDirExisted = !pngDir.empty() && fs::exists(pngDir, ec);
  const auto wrote = [&](const fs::path& path) {
    written.push_back(path);
    writing.advance();
    if (writing.cancelled()) {
      fail("{}: cancelled; the outputs written so far were removed", o.project);
    }
  };
  std::vector<std::string> report;
  try {
    for (const std::string& video : {o.mp4, o.webm}) {
      if (!video.empty()) {
        writeVideo(video, frames, o.fps);
        wrote(video);
        report.push_back(video);
      }
    }
    if (!o.sprites.empty()) {
      const fs::path json = fs::path(o.sprites).replace_extension(".json");
      writeSpriteSheet(o.sprites, json, frames, columns, o.fps);
      wrote(json);
      wrote(o.sprites);
      report.push_back(o.sprites);
      report.push_back(json.string());
    }
    if (!o.gif.empty()) {
      const int delay = std::max(2, static_cast<int>(std::lround(100.0 / o.fps)));
      writeGif(o.gif, frames, delay, true);
      wrote(o.gif);
      report.push_back(fmt::format("{} ({} frames, {} cs each)", o.gif, count, delay));
    }
    if (!pngDir.empty()) {
      for (int i = 0; i < count; ++i) {
        const fs::path frame = fs::path(pngDir) / fmt::format("frame_{:0{}}.png", i, digits);
        saveImage(frame, frames[static_cast<std::size_t>(i)]);
        wrote(frame);
      }
      report.push_back(fmt::format("{} ({} frames)", pngDir, count));
    }
  } catch (...) {
    for (const fs::path& path : written) {
      fs::remove(path, ec);
    }
    if (!pngDir.empty() && !pngDirExisted && fs::is_empty(pngDir, ec)) {
      fs::remove(pngDir, ec);
    }
    throw;
  }
  for (const std::string& line : report) {
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

struct ViewOptions {
  std::string project;
  std::string image;
  std::string shaderDir;
  int frames = 0;
  std::string screenshot;
  double fixedStep = 0.0;
  bool noUi = false;
  double zoom = 0.0;
};

#ifdef SYLVA_HAVE_FOLDING_GPU
void runFoldViewer(const ViewOptions& o) {
  const Loaded l = load(o.project);
  int index = imageOption(l.project, o.image);
  const Textures textures = synthesizeWithProgress(l);
  const glm::ivec2 first = textures.atlas.entries[static_cast<std::size_t>(index)].atlasRect().max -
                           textures.atlas.entries[static_cast<std::size_t>(index)].atlasRect().min;
  // Open at the image's size: small images zoomed up to about 960×720 (room for the panel), large ones
  // shrunk to fit a common screen.
  const double grow = std::max(1.0, std::min(960.0 / first.x, 720.0 / first.y));
  const double fit = std::min({grow, 1600.0 / first.x, 1000.0 / first.y});
  ui::ShellOptions shellOptions;
  shellOptions.width = std::max(480, static_cast<int>(first.x * fit));
  shellOptions.height = std::max(360, static_cast<int>(first.y * fit));
  shellOptions.title = "Sylva fold: " + fs::path(o.project).filename().string();
  shellOptions.frames = o.frames;
  shellOptions.screenshot = o.screenshot;
  shellOptions.fixedStep = o.fixedStep;
  shellOptions.panelShown = !o.noUi;
  ui::WindowShell shell(shellOptions);
  shader::Library library(o.shaderDir);
  folding::gpu::FoldRenderer renderer(library);
  renderer.upload(textures, l.project.profiles, l.project.jumpLayers);

  float speed = 1.0f;
  float shift = 0.0f;
  int function = 0; // 0: as in the project, else kFunctionNames[function - 1]
  bool paused = false;
  double t = 0.0;
  const double period = loopPeriod(l.project.profiles).seconds;
  const auto updateProfiles = [&] {
    PlaybackOptions playback;
    playback.shift = shift; // speed scales the clock below, so changing it never jumps the phase
    if (function > 0) {
      playback.function = static_cast<PositionFunction::Type>(function - 1);
    }
    renderer.setProfiles(applyPlayback(l.project.profiles, playback));
  };
  // The frame is drawn at the image's size and shown on a canvas filling the window (wheel: zoom, right or
  // middle drag: pan, Home: fit, +/-: zoom, 1: one texel per pixel).
  ui::ImageCanvas canvas;
  canvas.fitMargin = 0.0;
  canvas.fitOnWholePixels = true;
  canvas.fitZoom = o.zoom;
  canvas.showGrid = false; // a preview: the panel turns the grid on
  ui::CanvasImage frameImage;
  shell.setKeyHandler([&](int key, int) {
    if (key == GLFW_KEY_SPACE) {
      paused = !paused;
    } else if (key == GLFW_KEY_HOME) {
      canvas.requestFit();
    } else if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) {
      canvas.zoomAtCentre(2.0);
    } else if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) {
      canvas.zoomAtCentre(0.5);
    } else if (key == GLFW_KEY_1) {
      canvas.actualSize();
    } else {
      return false;
    }
    return true;
  });
  shell.run([&](const ui::ShellFrame& f) {
    if (!paused) {
      t += f.dt * speed;
    }
    const AtlasEntry& entry = textures.atlas.entries[static_cast<std::size_t>(index)];
    const Rect region = entry.atlasRect();
    frameImage.bindForDraw({region.width(), region.height()});
    renderer.draw(t, region);
    gl::bindDefaultFramebuffer(f.size.x, f.size.y);
    gl::clear(glm::vec4(0.12f, 0.12f, 0.13f, 1.0f));
    shell.beginUi();
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(f.size.x), static_cast<float>(f.size.y)));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0.0f, 0.0f));
    ImGui::Begin("##frame", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoScrollWithMouse);
    ImGui::PopStyleVar();
    // draw() puts the region's first row at the top of the viewport, GL's last row: flipped on the way.
    canvas.drawPixelGrid(canvas.begin(frameImage.texture(), frameImage.size(), true));
    canvas.input();
    frameImage.showAt(canvas.view.zoom); // this frame's zoom: the texture is drawn when the frame ends
    ImGui::End();
    if (!shell.panelShown()) {
      shell.endUi();
      return;
    }
    shell.beginPanel(
        "Fold", fmt::format(", {}x{} at {:.0f}%", region.width(), region.height(), 100.0 * canvas.view.zoom));
    bool changed = false;
    ImGui::SliderFloat("speed", &speed, 0.0f, 4.0f, "%.2fx");
    changed |= ImGui::SliderFloat("shift (cycles)", &shift, 0.0f, 1.0f, "%.3f");
    const char* functions[] = {"as in the project", "linear", "piecewise", "exponential", "sigmoid", "sine"};
    changed |= ImGui::Combo("function", &function, functions, 6);
    float time = static_cast<float>(std::fmod(t, period));
    if (ImGui::SliderFloat("time (s)", &time, 0.0f, static_cast<float>(period), "%.3f")) {
      t = time;
      paused = true;
    }
    ImGui::Checkbox("pause (space)", &paused);
    ImGui::SameLine();
    ImGui::Checkbox("pixel grid", &canvas.showGrid);
    if (l.project.images.size() > 1) {
      std::vector<const char*> ids;
      for (const ImageEntry& e : l.project.images) {
        ids.push_back(e.id.c_str());
      }
      if (ImGui::Combo("image", &index, ids.data(), static_cast<int>(ids.size()))) {
        canvas.requestFit();
      }
    }
    if (changed) {
      updateProfiles();
    }
    ImGui::PopItemWidth();
    ImGui::End();
    shell.endUi();
  });
}
#endif

void registerFoldView(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "view", "Preview a project live in a window with sliders for speed, shift, position function and time "
              "(Space: pause; Tab: hide the panel; wheel or +/-: zoom, right/middle drag: pan, Home: fit, 1: "
              "one texel per pixel)");
  auto o = std::make_shared<ViewOptions>();
  command->add_option("project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_option("--image", o->image, "Id of the image to show first (default: the project's canvas)");
  command->add_option("--shader-dir", o->shaderDir, "Read shaders from this directory")
      ->check(CLI::ExistingDirectory);
  addScriptedWindowOptions(*command, o->frames, o->screenshot, o->fixedStep);
  command->add_flag("--no-ui", o->noUi, "Start with the panel hidden");
  command->add_option("--zoom", o->zoom, "Zoom at start, screen pixels per image pixel (0: fit the window)")
      ->check(CLI::Range(0.0, 32.0));
  command->callback([o] {
#ifdef SYLVA_HAVE_FOLDING_GPU
    runFoldViewer(*o);
#else
    fail("fold view: this sylva was built without the folding GPU renderer");
#endif
  });
}

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
    const Loaded l = load(o->project);
    const Textures textures = synthesizeWithProgress(l);
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
    const Loaded l = load(o->project);
    const Textures textures = synthesizeWithProgress(l);
    folding::gpu::writeWebPreview(o->out, shader::Library(), l.project, textures);
    std::printf("%s\n", o->out.c_str());
#else
    fail("fold export-web: this sylva was built without the folding GPU renderer");
#endif
  });
}

// ---------------------------------------------------------------------------------------------------------
// info

std::string vec(Vec2 v) {
  return fmt::format("({:g}, {:g})", v.x, v.y);
}

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
    const Loaded l = load(o->project);
    const Project& p = l.project;
    const Atlas atlas = withFileName(l, [&] { return packAtlas(p, l.images); });
    if (o->json) {
      nlohmann::json images = nlohmann::json::array();
      for (std::size_t i = 0; i < p.images.size(); ++i) {
        const AtlasEntry& e = atlas.entries[i];
        images.push_back({{"id", e.id},
                          {"size", {e.imageSize.x, e.imageSize.y}},
                          {"crop", {e.crop.min.x, e.crop.min.y, e.crop.max.x, e.crop.max.y}},
                          {"atlas_pos", {e.atlasPos.x, e.atlasPos.y}}});
      }
      const nlohmann::json json = {
          {"file", l.where},
          {"project", toJson(p)},
          {"atlas", {{"size", {atlas.color.width(), atlas.color.height()}}, {"images", images}}}};
      std::cout << json.dump(2) << "\n";
      return;
    }
    std::printf("%s: sylva-fold version %d, seed %llu\n", l.where.c_str(), kProjectVersion,
                static_cast<unsigned long long>(p.seed));
    std::printf("atlas: %dx%d, gutter %d px, canvas '%s'\n", atlas.color.width(), atlas.color.height(),
                p.gutter, p.images[static_cast<std::size_t>(p.canvasIndex())].id.c_str());
    std::printf("images:\n");
    for (std::size_t i = 0; i < p.images.size(); ++i) {
      const AtlasEntry& e = atlas.entries[i];
      std::printf("  %-12s %s  %dx%d, kept [%d,%d)-[%d,%d) at atlas (%d, %d)\n", e.id.c_str(),
                  p.images[i].file.string().c_str(), e.imageSize.x, e.imageSize.y, e.crop.min.x, e.crop.min.y,
                  e.crop.max.x, e.crop.max.y, e.atlasPos.x, e.atlasPos.y);
    }
    std::printf("profiles:\n");
    for (const Profile& pr : p.profiles) {
      std::printf("  %-12s %s, period %g s, shift %g, loop %s\n", pr.id.c_str(), functionName(pr.fn.type),
                  pr.periodS, pr.shift, loopName(pr.loop));
    }
    std::string layers;
    for (double b : p.jumpLayers) {
      layers += (layers.empty() ? "" : ", ") + fmt::format("{:g}", b);
    }
    std::printf("jump layers: %zu (breakpoints %s)\n", p.jumpLayers.size() - 1, layers.c_str());
    std::printf("zones:\n");
    for (const Zone& z : p.zones) {
      std::string tools;
      for (const Tool& t : z.tools) {
        tools += (tools.empty() ? "" : ", ") + std::string(toolName(t));
      }
      const std::vector<Vec2> outline = z.shape.outline();
      Vec2 lo(1e300);
      Vec2 hi(-1e300);
      for (const Vec2& v : outline) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
      }
      std::printf("  %-12s on '%s', %s %s-%s, profile '%s', layer %d, %s (R %g), tools: %s; folding: %s\n",
                  z.id.c_str(), z.image.c_str(), z.shape.type == Shape::Type::Rect ? "rect" : "polygon",
                  vec(lo).c_str(), vec(hi).c_str(), z.profile.c_str(), z.layer, interpName(z.interp.type),
                  z.interp.radius, tools.empty() ? "none" : tools.c_str(), foldingName(z.folding.type));
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
  command->add_option("--direction", o->direction, "wave_swash: direction the water advances, X Y")
      ->expected(2)
      ->check(finiteRange(-1e4, 1e4));
  command->add_option("--period", o->period, "Profile period in seconds (0: the template's default)")
      ->check(finiteRange(0.0, 1e6))
      ->capture_default_str();
  command->add_option("-o,--out", o->out, "Write the edited project here (default: overwrite the input)");
  command->callback([o] {
    const Project project = loadProject(o->project);
    const int zone = [&] {
      for (std::size_t z = 0; z < project.zones.size(); ++z) {
        if (project.zones[z].id == o->zone) {
          return static_cast<int>(z);
        }
      }
      fail("--zone: {} has no zone '{}'", o->project, o->zone);
    }();
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

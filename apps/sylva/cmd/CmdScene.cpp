// `sylva render SCENE.json`: stills and resumable, splittable, deterministic frame sequences of a scene file
// (docs/scenes.md "Rendering sequences").
#include "cmd/CmdScene.hpp"

#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/media/Export.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/scene/Sequence.hpp>

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace sylva::app {
namespace {

std::string shellQuote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

/** The range's frames as MP4 through ffmpeg (H.264, yuv420p); the frames must all be there. */
void encodeMp4(const std::filesystem::path& dir, const scene::FrameRange& range, double fps,
               const std::string& out) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) {
    fail("--mp4 {}: ffmpeg is not installed (apt install ffmpeg; scripts/setup-debian.sh installs it)", out);
  }
  // ffmpeg reads numbered files from a start number on; a list file also covers ranges with gaps (--frames
  // 0-9,20-29) in order.
  const std::filesystem::path list = dir / "frames.ffconcat";
  {
    std::FILE* f = std::fopen(list.c_str(), "w");
    if (f == nullptr) {
      fail("--mp4: cannot write {}", list.string());
    }
    std::fprintf(f, "ffconcat version 1.0\n");
    for (int frame : range.frames()) {
      std::fprintf(f, "file '%s'\nduration %.9f\n", scene::frameName(frame).c_str(), 1.0 / fps);
    }
    std::fclose(f);
  }
  const std::filesystem::path parent = std::filesystem::path(out).parent_path();
  if (!parent.empty()) {
    std::filesystem::create_directories(parent);
  }
  const std::string temporary = out + ".tmp.mp4";
  const std::string command = fmt::format(
      "ffmpeg -loglevel error -y -f concat -safe 0 -i {} -r {} -c:v libx264 -pix_fmt yuv420p -crf 20 "
      "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -movflags +faststart {}",
      shellQuote(list.string()), fps, shellQuote(temporary));
  const int rc = std::system(command.c_str());
  std::filesystem::remove(list);
  if (rc != 0) {
    std::filesystem::remove(temporary);
    fail("--mp4 {}: ffmpeg failed (exit {})", out, rc);
  }
  std::filesystem::rename(temporary, out);
}

} // namespace

void addSceneRenderOptions(CLI::App& command, SceneRenderOptions& o) {
  command
      .add_option(
          "--shard", o.shard,
          "With a scene file: render only shard i of n (i/n) of --frames, so independent runs split a "
          "range (frame k of the range goes to shard k mod n)")
      ->capture_default_str();
  command.add_option("--camera", o.camera,
                     "With a scene file: the camera to render (default: the file's output)");
  command.add_option("--mp4", o.mp4, "With a scene file: also encode the sequence as H.264 MP4 (ffmpeg)");
  command.add_flag("--overwrite", o.overwrite,
                   "With a scene file: render frames again even when a complete frame file exists");
}

void renderSceneFile(const SceneRenderOptions& o) {
  scene::SceneDesc desc = scene::loadScene(o.file);
  const int width = o.width > 0 ? o.width : desc.output.width;
  const int height = o.height > 0 ? o.height : desc.output.height;
  const std::string cameraName = o.camera.empty() ? desc.output.camera : o.camera;
  if (!desc.cameras.contains(cameraName)) {
    fail("--camera {}: {} has no such camera", cameraName, o.file);
  }
  const bool sequence = !o.frames.empty() || !o.gif.empty() || !o.mp4.empty();
  const scene::FrameRange range =
      o.frames.empty()
          ? scene::parseFrames(fmt::format("{}-{}", desc.output.firstFrame, desc.output.lastFrame))
          : scene::parseFrames(o.frames);
  const scene::Shard shard = scene::parseShard(o.shard);
  if (!sequence && shard.count > 1) {
    fail("--shard {}: needs a sequence (--frames A-B)", o.shard);
  }
  const std::vector<int> frames =
      sequence ? scene::framesOf(range, shard) : std::vector<int>{desc.output.firstFrame};
  const std::filesystem::path out =
      !o.out.empty() ? std::filesystem::path(o.out)
                     : std::filesystem::path("out") / (sequence ? desc.name : desc.name + ".png");
  // Outputs checked before the scene is built and drawn.
  if (!sequence) {
    checkOutputFile(out, "--out");
  }
  if (!o.gif.empty()) {
    checkOutputFile(o.gif, "--gif", "anim.gif");
  }
  if (!o.mp4.empty()) {
    checkOutputFile(o.mp4, "--mp4", "anim.mp4");
  }
  if (sequence) {
    if (std::filesystem::exists(out) && !std::filesystem::is_directory(out)) {
      fail("--out {}: a sequence needs a directory, and this is a file", out.string());
    }
    std::filesystem::create_directories(out);
    const int stale = scene::removeStaleTemporaries(out);
    if (stale > 0) {
      log::info("removed {} unfinished frame file(s) left by an interrupted run", stale);
    }
  }

  // Frames already complete are skipped (resumable); the simulation still steps through their times.
  std::vector<int> todo;
  for (int f : frames) {
    if (!sequence || o.overwrite || !scene::frameComplete(out / scene::frameName(f), width, height)) {
      todo.push_back(f);
    }
  }
  if (sequence && todo.size() < frames.size()) {
    // Said on stderr whatever the log level: a resumed run should say what it is not redoing.
    std::fprintf(stderr, "%zu of %zu frames already complete in %s: skipped\n", frames.size() - todo.size(),
                 frames.size(), out.c_str());
  }

  if (!todo.empty()) {
    auto context = platform::createHeadlessContext(o.context);
    shader::Library library(o.shaderDir);
    scene::SceneWorld world(library, desc);
    // Offline frames take the full path: each is then a pure function of (scene, frame), whatever was drawn
    // before (shards and resumed runs rely on it); the real-time paths keep far shadow cascades.
    scene::SceneDrawOptions draw = world.drawOptions();
    draw.fullQuality = true;
    world.setDrawOptions(draw);
    render::RenderTarget target(width, height);
    Progress progress(fmt::format("render {}", desc.name), todo.size());
    for (int f : todo) {
      if (progress.cancelled()) {
        fail("interrupted: {} of {} frames written; run the same command again to resume", progress.done(),
             todo.size());
      }
      world.advanceToFrame(f);
      const double time = world.frameTime(f);
      const render::Camera camera = world.camera(cameraName, time, target.aspect());
      target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      world.draw(camera, width, height, time, &target.depth(), nullptr);
      const Image image = target.readColor();
      if (sequence) {
        scene::writeFrameAtomically(out / scene::frameName(f), image);
      } else {
        if (!out.parent_path().empty()) {
          std::filesystem::create_directories(out.parent_path());
        }
        scene::writeFrameAtomically(out, image);
      }
      progress.advance(1);
    }
  }
  if (!sequence) {
    std::printf("%s\n", out.c_str());
    return;
  }
  std::printf("%s\n", out.c_str());
  if (o.gif.empty() && o.mp4.empty()) {
    return;
  }
  // Encoding needs the whole range (every shard done): say what is missing instead of a short video.
  int missing = 0;
  for (int f : range.frames()) {
    if (!scene::frameComplete(out / scene::frameName(f), width, height)) {
      ++missing;
    }
  }
  if (missing > 0) {
    log::warn("{} of {} frames of the range are not rendered yet (other shards?): not encoding; run again "
              "with the same --gif/--mp4 when they are",
              missing, range.count());
    return;
  }
  const double fps = desc.output.fps;
  if (!o.gif.empty()) {
    std::vector<Image> images;
    for (int f : range.frames()) {
      images.push_back(loadImage(out / scene::frameName(f)));
    }
    media::writeGif(o.gif, images, std::max(1, static_cast<int>(std::lround(100.0 / fps))));
    std::printf("%s\n", o.gif.c_str());
  }
  if (!o.mp4.empty()) {
    encodeMp4(out, range, fps, o.mp4);
    std::printf("%s\n", o.mp4.c_str());
  }
}

} // namespace sylva::app

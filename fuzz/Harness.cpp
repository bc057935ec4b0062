#include "Harness.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/folding/Flow.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/shader/Preprocessor.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/TerrainMaps.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace sylva::fuzz {

#ifdef SYLVA_FUZZ_HAVE_CLI
void runCliArguments(std::span<const std::uint8_t> bytes); // HarnessCli.cpp
#endif

namespace {

namespace fs = std::filesystem;

/** A private scratch folder for this process: loaders take paths, so inputs are written there first. */
const fs::path& scratch() {
  static const fs::path dir = [] {
    fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    fs::path d = base / ("sylva-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

fs::path writeInput(const std::string& name, std::span<const std::uint8_t> bytes) {
  const fs::path path = scratch() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

/** Runs `body`; a sylva::Error is the expected rejection, anything else escapes and is a finding. */
template <typename F> void expectCleanRejection(F&& body) {
  try {
    body();
  } catch (const Error&) {
  }
}

void heightFile(const char* name, std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput(name, bytes);
  // A field of 2^26 samples (256 MiB of floats) is plenty to exercise every loader; larger claims a file can
  // legitimately make (a sparse GeoTIFF) would only measure the machine's memory.
  terrain::LoadOptions options;
  options.maxSamples = std::size_t{1} << 26;
  expectCleanRejection([&] { (void)terrain::loadHeightField(path, options); });
}

void png(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("input.png", bytes);
  fs::remove(scratch() / "input.png.json");
  expectCleanRejection([&] {
    const Image image = loadImage(path);
    if (image.channels() <= 2) {
      (void)terrain::loadHeightField(path);
    }
  });
}

void exr(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("input.exr", bytes);
  expectCleanRejection([&] {
    const Image image = loadImage(path);
    if (image.channels() <= 2) {
      (void)terrain::loadHeightField(path);
    }
  });
}

void npy(std::span<const std::uint8_t> bytes) {
  heightFile("input.npy", bytes);
}
void npz(std::span<const std::uint8_t> bytes) {
  heightFile("input.npz", bytes);
}
void gdal(std::span<const std::uint8_t> bytes) {
  heightFile("input.tif", bytes);
}

/** Every Sylva JSON file: procedural spec, splat layers, and a height PNG's sidecar. */
void json(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("input.json", bytes);
  expectCleanRejection([&] { (void)terrain::proceduralSpecFromJson(loadJsonFile(path), path.string()); });
  expectCleanRejection([&] { (void)terrain::splatLayersFromJson(loadJsonFile(path), path.string()); });
  static const fs::path heights = [] {
    Image image(4, 4, 1, PixelType::U16);
    const fs::path p = scratch() / "sidecar.png";
    savePng(p, image);
    return p;
  }();
  writeInput("sidecar.png.json", bytes);
  expectCleanRejection([&] { (void)terrain::loadHeightField(heights); });
}

/**
 * Shader preprocessor: the input is split at NUL bytes into up to four files a.glsl, b.glsl, c.glsl, d.glsl
 * (so `#include "b.glsl"` and cycles are reachable), then a.glsl is preprocessed with two defines.
 */
void shader(std::span<const std::uint8_t> bytes) {
  const fs::path dir = scratch() / "shaders";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const char* names[] = {"a.glsl", "b.glsl", "c.glsl", "d.glsl"};
  std::size_t start = 0;
  for (std::size_t file = 0; file < 4; ++file) {
    std::size_t end = start;
    while (end < bytes.size() && bytes[end] != 0) {
      ++end;
    }
    if (start <= bytes.size()) {
      std::ofstream out(dir / names[file], std::ios::binary);
      out.write(reinterpret_cast<const char*>(bytes.data() + start),
                static_cast<std::streamsize>(end - start));
    }
    start = end + 1;
    if (start > bytes.size()) {
      break;
    }
  }
  const shader::Library library(dir);
  expectCleanRejection([&] { (void)shader::preprocess(library, "a.glsl", {{"SYLVA_A", "1"}, {"B", ""}}); });
}

/**
 * Folding projects: parsed, validated against two small images in the scratch folder ("img.png" 24×16 and
 * "obj.png" 6×4, also usable as masks of their own size), synthesised and rendered at one time. File names
 * with a directory part are skipped so the fuzzer cannot point the loader at arbitrary system files.
 */
void fold(std::span<const std::uint8_t> bytes) {
  static const bool images = [] {
    Image img(24, 16, 3, PixelType::U8);
    Image obj(6, 4, 4, PixelType::U8);
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 24; ++x) {
        img.set(x, y, 0, static_cast<float>(x) / 24.0f);
        img.set(x, y, 1, static_cast<float>(y) / 16.0f);
        if (x < 6 && y < 4) {
          obj.set(x, y, 3, (x + y) % 2 ? 1.0f : 0.0f);
        }
      }
    }
    savePng(scratch() / "img.png", img);
    savePng(scratch() / "obj.png", obj);
    return true;
  }();
  (void)images;
  const fs::path path = writeInput("project.json", bytes);
  expectCleanRejection([&] {
    const folding::Project project = folding::loadProject(path);
    for (const folding::ImageEntry& image : project.images) {
      if (image.file.has_parent_path()) {
        return;
      }
    }
    for (const folding::Zone& zone : project.zones) {
      if (zone.freezeMask.has_parent_path() || zone.folding.mask.has_parent_path()) {
        return;
      }
    }
    const folding::ProjectImages loaded = folding::loadProjectImages(project, path.string());
    const folding::Textures textures = folding::synthesize(project, loaded);
    (void)folding::renderFrame(textures, project.profiles, project.jumpLayers, 0.37);
  });
}

/** Frames of `clip` through both optical flows when there are two small ones. */
void flowOfFirstFrames(const folding::VideoClip& clip) {
  if (clip.frames.size() >= 2 && clip.size.x <= 128 && clip.size.y <= 128) {
    for (const folding::FlowMethod method : {folding::FlowMethod::Dis, folding::FlowMethod::Farneback}) {
      (void)folding::flowPicture(folding::computeFlow(clip.frames[0], clip.frames[1], method));
    }
  }
}

/**
 * Reference videos as image sequences (`seq%04d.png`, what OpenCV's own image-sequence reader opens; the
 * decoder follows the content, the extension is only a name): the bytes as two frames, then both optical
 * flows of the two small frames. The part of loadVideo CI fuzzes.
 */
void flow(std::span<const std::uint8_t> bytes) {
  const fs::path first = writeInput("seq0000.png", bytes);
  writeInput("seq0001.png", bytes);
  expectCleanRejection(
      [&] { flowOfFirstFrames(folding::loadVideo(first.parent_path() / "seq%04d.png", 3)); });
}

/**
 * Reference videos in containers: the bytes as a file FFmpeg probes (any container it recognises), at most 3
 * frames. Not in the CI run (scripts/fuzz.sh `all`): OpenCV 4.6's FFmpeg capture over-reads a heap buffer on
 * files whose header and frames disagree on the frame size (docs/folding.md, "Known issue"), which this
 * target finds within a minute; run it by name.
 */
void flowFfmpeg(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("input.avi", bytes);
  expectCleanRejection([&] { flowOfFirstFrames(folding::loadVideo(path, 3)); });
}

} // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> kTargets = {
      {"png", "PNG images, 8/16-bit, and PNG height maps (loadImage, loadHeightField)", png},
      {"exr", "OpenEXR images and EXR height maps", exr},
      {"npy", "NumPy .npy height arrays", npy},
      {"npz", "NumPy .npz archives (zip of .npy, with dx/dy/extent scalars)", npz},
      {"gdal", "rasters opened through GDAL (GeoTIFF and every format GDAL identifies)", gdal},
      {"json", "Sylva JSON files: procedural spec, splat layers, height-map sidecar", json},
      {"shader", "the shader preprocessor's #include, #pragma once, #version and #line handling", shader},
      {"fold", "folding projects: parsing, validation against images, synthesis and one CPU frame", fold},
      {"flow", "reference videos as image sequences for motion from video, and their optical flow", flow},
      {"flow_ffmpeg",
       "reference videos in containers (FFmpeg through OpenCV); not in CI, see docs/testing.md", flowFfmpeg},
#ifdef SYLVA_FUZZ_HAVE_CLI
      {"cli", "the sylva command line's option parsing and validation (commands not run)", runCliArguments},
#endif
  };
  return kTargets;
}

void runTarget(std::string_view name, std::span<const std::uint8_t> bytes) {
  for (const Target& target : targets()) {
    if (target.name == name) {
      target.run(bytes);
      return;
    }
  }
  throw std::invalid_argument("unknown fuzz target " + std::string(name));
}

} // namespace sylva::fuzz

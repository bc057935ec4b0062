#include "Harness.hpp"

#include <sylva/blades/BladeModel.hpp>
#include <sylva/capture/Depth.hpp>
#include <sylva/capture/Fakenect.hpp>
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/farm/Farm.hpp>
#include <sylva/folding/Flow.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/scene/CameraPath.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/scene/Sequence.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/shader/Preprocessor.hpp>
#include <sylva/terrain/HeightRaster.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/TerrainMaps.hpp>
#include <sylva/terrain/TilePyramid.hpp>
#include <sylva/trees/Foliage.hpp>
#include <sylva/trees/Import.hpp>
#include <sylva/trees/Skeleton.hpp>
#include <sylva/trees/Species.hpp>
#include <sylva/trees/Tree.hpp>
#include <sylva/texsynth/TileSetIo.hpp>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <system_error>

/**
 * LeakSanitizer's built-in suppressions for every harness binary (libFuzzer targets and the ASan replay).
 * Assimp 5.2's OBJ reader leaks the meshes it has built when it rejects a later object ("OBJ: vertex index
 * out of range"; fuzz/regressions/piece_import), an allocation inside libassimp that sylva cannot free. Only
 * allocations made inside libassimp are ignored; our own code is never suppressed.
 */
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libassimp.so\n";
}

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
  // The out-of-core path (tile pyramids): the same file opened window by window, a few windows read.
  const fs::path path = scratch() / "input.tif";
  expectCleanRejection([&] {
    const auto raster = terrain::HeightRaster::open(path);
    if (static_cast<double>(raster->width()) * raster->height() > double(1 << 26)) {
      return; // a claim that large would only measure the machine's memory (as in heightFile)
    }
    std::vector<float> window(64 * 64);
    const int w = std::min(64, raster->width());
    const int h = std::min(64, raster->height());
    raster->read(0, 0, w, h, window.data());
    raster->read(raster->width() - w, raster->height() - h, w, h, window.data());
  });
}

/**
 * Tile pyramids: the first byte chooses what the rest is — a tile file (decoded alone, then read through a
 * small pyramid in place of its tile 0/0/0) or the pyramid's `pyramid.json` — then the pyramid is opened and
 * queried at every level.
 */
void tilePyramid(std::span<const std::uint8_t> bytes) {
  static const fs::path good = [] {
    const fs::path dir = scratch() / "pyramid-good";
    terrain::HeightField field(40, 33, 2.0f, 3.0f);
    for (int j = 0; j < field.height(); ++j) {
      for (int i = 0; i < field.width(); ++i) {
        field.at(i, j) = static_cast<float>((i * 7 + j * 13) % 29);
      }
    }
    terrain::buildPyramid(*terrain::HeightRaster::fromField(field), dir, {.tileSize = 16});
    return dir;
  }();
  const fs::path dir = scratch() / "pyramid";
  // libFuzzer's timer signals can interrupt the kernel copy (EINTR, seen once in CI's smoke run): retry it.
  for (int attempt = 0;; ++attempt) {
    fs::remove_all(dir);
    std::error_code error;
    fs::copy(good, dir, fs::copy_options::recursive, error);
    if (!error) {
      break;
    }
    if (error != std::errc::interrupted || attempt >= 8) {
      throw fs::filesystem_error("cannot copy the fuzz pyramid", good, dir, error);
    }
  }
  const bool asTile = !bytes.empty() && (bytes[0] & 1) == 0;
  const auto rest = bytes.empty() ? bytes : bytes.subspan(1);
  if (asTile) {
    expectCleanRejection([&] { (void)terrain::decodeTile(rest.data(), rest.size(), "input.tile"); });
    std::ofstream(terrain::tilePath(dir, {0, 0, 0}), std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(rest.data()), static_cast<std::streamsize>(rest.size()));
  } else {
    std::ofstream(dir / "pyramid.json", std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(rest.data()), static_cast<std::streamsize>(rest.size()));
  }
  expectCleanRejection([&] {
    const auto pyramid = terrain::TilePyramid::open(dir, 4096);
    for (int level = 0; level < pyramid->info().levels; ++level) {
      for (const float x : {0.0f, 17.5f, 1.0e9f}) {
        (void)pyramid->heightAt(x, 0.5f * x, level);
      }
    }
  });
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
 * Reference videos in containers: the bytes as a file FFmpeg's libraries probe (any container they
 * recognise), at most 3 frames and their flow. Under OpenCV 4.6's FFmpeg capture this target found, within a
 * minute, a heap over-read on files whose header and frames disagree on the frame size; loadVideo now decodes
 * containers through libavformat/libavcodec itself and converts each frame at its decoded size.
 */
void flowFfmpeg(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("input.avi", bytes);
  expectCleanRejection([&] { flowOfFirstFrames(folding::loadVideo(path, 3)); });
}

/**
 * Blade-model files: loaded and validated; what loads must also survive the helpers and a round trip through
 * toJson (a valid file that its own writer cannot express again would be a finding).
 */
void bladeModels(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("blades.json", bytes);
  blades::BladeModelFile file;
  try {
    file = blades::loadBladeModels(path);
  } catch (const Error&) {
    return;
  }
  for (const blades::BladeModel& blade : file.blades) {
    (void)blade.length();
    (void)blade.maxWidth();
    (void)blade.lodForKnots(16);
  }
  (void)blades::parseBladeModels(blades::toJson(file), path.string()); // throws (a finding) if not
}

/** Depth inputs: the bytes as a file both depth loaders open (16-bit depth PNG, 8-bit Middlebury disparity).
 */
void depthPng(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("depth.png", bytes);
  expectCleanRejection([&] {
    const capture::DepthFrame frame = capture::loadDepthPng(path);
    const auto [lo, hi] = capture::depthRange(frame);
    (void)capture::depthPreview(frame, lo, hi + 1.0f);
  });
  expectCleanRejection([&] { (void)capture::loadMiddlebury(path); });
}

/**
 * fakenect recordings and frame files. The first byte chooses: even, the rest is decoded directly as a depth
 * PGM and as an RGB PPM (small sizes reach the pixel loops); odd, the rest is a recording: INDEX.txt up to
 * the first NUL byte, then a 2-byte little-endian length L, L bytes of the file the first INDEX line names
 * and the remaining bytes as the file the second line names (plain names only), then every depth frame is
 * read.
 */
void fakenect(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) {
    return;
  }
  const std::span<const std::byte> rest = std::as_bytes(bytes.subspan(1));
  if (bytes[0] % 2 == 0) {
    expectCleanRejection(
        [&] { (void)capture::depthFromKinectRaw(capture::decodeFakenectDepth(rest, "d.pgm")); });
    expectCleanRejection([&] { (void)capture::decodeFakenectRgb(rest, "r.ppm"); });
    return;
  }
  const fs::path dir = scratch() / "fakenect";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::size_t pos = 1;
  while (pos < bytes.size() && bytes[pos] != 0) {
    ++pos;
  }
  const std::string index(reinterpret_cast<const char*>(bytes.data()) + 1, pos - 1);
  std::ofstream(dir / "INDEX.txt", std::ios::binary)
      .write(index.data(), static_cast<std::streamsize>(index.size()));
  std::span<const std::uint8_t> files =
      pos + 1 <= bytes.size() ? bytes.subspan(pos + 1) : bytes.subspan(0, 0);
  std::size_t firstSize = 0;
  if (files.size() >= 2) {
    firstSize = std::min<std::size_t>(files[0] | (std::size_t{files[1]} << 8), files.size() - 2);
    files = files.subspan(2);
  }
  // The first two INDEX lines name the files; anything with a directory part is left out.
  std::vector<std::string> names;
  std::size_t start = 0;
  while (names.size() < 2 && start < index.size()) {
    std::size_t end = index.find('\n', start);
    end = end == std::string::npos ? index.size() : end;
    std::string name = index.substr(start, end - start);
    if (!name.empty() && name.back() == '\r') {
      name.pop_back();
    }
    start = end + 1;
    if (name.empty()) {
      continue;
    }
    const bool plain = name.size() < 200 &&
                       name.find_first_of(std::string("/\\\0", 3)) == std::string::npos && name != "." &&
                       name != ".." && name != "INDEX.txt";
    names.push_back(plain ? name : std::string());
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::span<const std::uint8_t> file =
        i == 0 ? files.subspan(0, firstSize) : files.subspan(firstSize);
    if (!names[i].empty()) {
      std::ofstream(dir / names[i], std::ios::binary)
          .write(reinterpret_cast<const char*>(file.data()), static_cast<std::streamsize>(file.size()));
    }
  }
  expectCleanRejection([&] {
    const capture::FakenectRecording recording = capture::FakenectRecording::open(dir);
    for (std::size_t i = 0; i < std::min<std::size_t>(recording.depthFrameCount(), 8); ++i) {
      expectCleanRejection([&] { (void)recording.depthFrame(i); });
    }
  });
}

/**
 * Tree and species JSON: the bytes parsed as JSON (syntax errors are the json target's business) and read as
 * a tree (treeFromJson against the built-in pieces) and as a species (speciesFromJson). What loads must also
 * survive its helpers and load again from its own toJson; a species that loads grows a tree (at most 300
 * pieces, to stay fast) that must validate.
 */
void treeJson(std::span<const std::uint8_t> bytes) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(bytes.begin(), bytes.end());
  } catch (const nlohmann::json::exception&) {
    return;
  }
  static const trees::PieceSet pieces = trees::standardPieces();
  std::optional<trees::TreeTopology> tree;
  try {
    tree = trees::treeFromJson(json, pieces, "tree.json");
  } catch (const Error&) {
  }
  if (tree) {
    (void)trees::treeStats(pieces, *tree);
    std::vector<glm::mat4> frames;
    const std::vector<glm::vec2> pose = trees::randomPose(*tree, trees::Species{}, 3);
    trees::jointFrames(pieces, *tree, glm::mat4(1.0f), pose, frames);
    (void)trees::treeFromJson(trees::toJson(*tree, pieces), pieces, "tree.json"); // throws (a finding) if not
  }
  std::optional<trees::Species> species;
  try {
    species = trees::speciesFromJson(json, "species.json");
  } catch (const Error&) {
  }
  if (species) {
    (void)trees::speciesFromJson(trees::toJson(*species), "species.json"); // throws (a finding) if not
    species->maxPieces = std::min(species->maxPieces, 300);
    const trees::TreeTopology grown = trees::generateTree(pieces, *species, 1);
    trees::validate(grown, pieces, "generated");
  }
}

/**
 * Artist pieces: the bytes as an OBJ file through importPiece (Assimp's OBJ reader, then rim finding, fitting
 * and every interlocking check), at most 4,096 quads; a piece that imports is written out as OBJ and glTF.
 * Assimp's OBJ reader clears a read buffer of several megabytes per file, which bounds this target at about
 * 100 inputs/s under ASan.
 */
void pieceImport(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("piece.obj", bytes);
  trees::ImportOptions options;
  options.maxQuads = 4096;
  expectCleanRejection([&] {
    const trees::Piece piece = trees::importPiece(path, options);
    trees::exportPieceObj(piece, scratch() / "out.obj");
    trees::exportPieceGltf(piece, scratch() / "out.gltf");
  });
}

/**
 * Leaf clouds for the foliage impostors: the bytes as an OBJ file through loadLeafCloud (Assimp's OBJ reader,
 * triangulation, node walk, normalisation into the unit sphere), at most 4,096 triangles; a cloud that loads
 * must validate.
 */
void leafModel(std::span<const std::uint8_t> bytes) {
  const fs::path path = writeInput("leaves.obj", bytes);
  expectCleanRejection([&] {
    const trees::LeafCloud cloud = trees::loadLeafCloud(path, 4096);
    trees::validate(cloud, "leaves.obj"); // throws (a finding) if the loader let a bad cloud through
  });
}

/**
 * farm.json (the render farm's manifest, `sylva farm status` reads it) and Slurm's `scontrol -o show job`
 * lines: strict parsing with one-line errors; a manifest that loads writes its scripts, splits its units over
 * its tasks exactly once each, and survives its own round trip.
 */
void farmManifest(std::span<const std::uint8_t> bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  for (const farm::TaskState& t : farm::parseJobLines(text)) {
    if (t.state.empty() || t.job.empty()) {
      throw std::logic_error("scontrol lines: a record without a job or a state");
    }
  }
  if (bytes.size() <= 4096) {
    expectCleanRejection([&] { (void)farm::parseArrayList(text); });
  }
  std::optional<farm::Farm> loaded;
  expectCleanRejection([&] { loaded = farm::parseFarm(text, "/nonexistent-sylva-fuzz/farm/farm.json"); });
  if (!loaded) {
    return;
  }
  const farm::Farm& f = *loaded;
  (void)farm::taskScriptText(f);
  (void)farm::encodeScriptText(f);
  const int units = f.unitCount();
  if (units <= 20000) {
    int total = 0;
    for (int task = 0; task < f.tasks; ++task) {
      total += static_cast<int>(f.unitsOf(task).size());
    }
    if (total != units) {
      throw std::logic_error("farm.json: the tasks' units do not add up to the farm's");
    }
  }
  const std::string again = farm::manifestText(f);
  if (farm::manifestText(farm::parseFarm(again, "round trip")) != again) {
    throw std::logic_error("farm.json: the manifest changes in a round trip");
  }
}

/**
 * tileset.json (texsynth): strict parsing of the description of a tile set; one that loads must survive its
 * own toJson (its atlas grid recomputed from the tile count) and load again with the same classes.
 */
void texsynthTileset(std::span<const std::uint8_t> bytes) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(bytes.begin(), bytes.end());
  } catch (const nlohmann::json::exception&) {
    return;
  }
  std::optional<texsynth::TileSetDescription> description;
  try {
    description = texsynth::tileSetFromJson(json, "tileset.json");
  } catch (const Error&) {
  }
  if (description) {
    texsynth::TileSet set = description->set;
    set.tiles.resize(static_cast<std::size_t>(description->tileTotal())); // toJson needs only their count
    const texsynth::TileSetDescription again =
        texsynth::tileSetFromJson(texsynth::toJson(set), "tileset.json"); // throws (a finding) if not
    if (again.set.classes != description->set.classes || again.set.colours != description->set.colours ||
        again.tileTotal() != description->tileTotal()) {
      throw std::logic_error("tileset.json: the round trip changed the tile set");
    }
  }
}

/**
 * Scene files (data/scenes, docs/scenes.md): strict parsing through parseScene with a fake path whose
 * directory does not exist, so referenced files are "file not found" (a clean rejection) and nothing is
 * written; a scene that parses has every camera evaluated. The same bytes also go through the --frames and
 * --shard parsers.
 */
void sceneFile(std::span<const std::uint8_t> bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  std::optional<scene::SceneDesc> desc;
  std::string strictError;
  try {
    desc = scene::parseScene(text, "/nonexistent-sylva-fuzz/scene.json");
  } catch (const Error& e) {
    strictError = e.what();
  }
  // `sylva scene check`'s reader goes on past errors: it must agree with the strict one on whether the file
  // is valid, its first error must be the strict reader's, and every message must be one line.
  scene::SceneFileErrors all;
  try {
    (void)scene::parseSceneAll(text, "/nonexistent-sylva-fuzz/scene.json", all);
  } catch (const Error& e) {
    all.messages.insert(all.messages.begin(), e.what());
  }
  if (all.messages.empty() != strictError.empty() ||
      (!strictError.empty() && all.messages.front() != strictError)) {
    throw std::logic_error("scene.json: parseSceneAll disagrees with parseScene: '" + strictError + "' vs '" +
                           (all.messages.empty() ? std::string() : all.messages.front()) + "'");
  }
  for (const std::string& m : all.messages) {
    if (m.find('\n') != std::string::npos) {
      throw std::logic_error("scene.json: a multi-line message: " + m);
    }
  }
  if (desc) {
    const scene::GroundHeight flat = [](float, float) { return 0.0f; };
    for (const auto& [name, camera] : desc->cameras) {
      const std::vector<scene::WorldCameraKey> keys = scene::resolveKeys(camera, flat);
      const double first = keys.front().time;
      const double last = keys.back().time;
      for (double t : {first - 1.0, first, 0.5 * (first + last), last, last + 1.0}) {
        const scene::CameraSample s = scene::evaluate(keys, t, camera.loop);
        if (!std::isfinite(s.position.x + s.position.y + s.position.z + s.fov)) {
          throw std::logic_error("scene.json: camera '" + name + "' evaluates to a non-finite value");
        }
      }
    }
    (void)desc->sun.direction();
  }
  if (bytes.size() <= 4096) {
    expectCleanRejection([&] {
      const scene::FrameRange range = scene::parseFrames(text);
      if (range.count() <= 10000) {
        (void)scene::framesOf(range, scene::parseShard("1/3"));
      }
    });
    expectCleanRejection([&] { (void)scene::parseShard(text); });
  }
}

} // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> kTargets = {
      {"png", "PNG images, 8/16-bit, and PNG height maps (loadImage, loadHeightField)", png},
      {"exr", "OpenEXR images and EXR height maps", exr},
      {"npy", "NumPy .npy height arrays", npy},
      {"npz", "NumPy .npz archives (zip of .npy, with dx/dy/extent scalars)", npz},
      {"gdal", "rasters opened through GDAL (GeoTIFF and every format GDAL identifies), whole and by windows",
       gdal},
      {"tile_pyramid", "tile pyramids: tile files and pyramid.json, opened and queried", tilePyramid},
      {"json", "Sylva JSON files: procedural spec, splat layers, height-map sidecar", json},
      {"shader", "the shader preprocessor's #include, #pragma once, #version and #line handling", shader},
      {"fold", "folding projects: parsing, validation against images, synthesis and one CPU frame", fold},
      {"flow", "reference videos as image sequences for motion from video, and their optical flow", flow},
      {"flow_ffmpeg", "reference videos in containers (AVI, MP4, …) through FFmpeg's libraries", flowFfmpeg},
      {"blade_models", "blade-model files (capture): parsing, validation and a round trip", bladeModels},
      {"depth_png", "depth inputs: 16-bit depth PNGs and 8-bit Middlebury disparity maps", depthPng},
      {"fakenect", "fakenect recordings: INDEX.txt, depth PGM and RGB PPM frame files", fakenect},
      {"tree_json", "tree and species JSON: loading, helpers, round trips, growing a tree", treeJson},
      {"piece_import", "artist tree pieces as OBJ through Assimp: rims, fitting, interlocking checks",
       pieceImport},
      {"leaf_model", "leaf clouds for foliage impostors as OBJ through Assimp: triangles, UVs, normalisation",
       leafModel},
      {"texsynth_tileset", "tile-set descriptions (tileset.json, texsynth): strict parsing and a round trip",
       texsynthTileset},
      {"scene_file", "scene files (data/scenes): strict parsing, camera paths, --frames and --shard",
       sceneFile},
      {"farm_manifest",
       "the render farm's farm.json and scontrol's job lines: strict parsing, scripts, round trip",
       farmManifest},
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

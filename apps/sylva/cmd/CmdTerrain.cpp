// `sylva terrain <sub>`: turns a DEM file or a procedural seed into height maps, normal maps and splat maps,
// and answers questions about it (info, query). Every subcommand reads its heights through SourceOptions
// below.
#include "Commands.hpp"
#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/terrain/FieldSummary.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/Quadtree.hpp>
#include <sylva/terrain/TerrainMaps.hpp>
#include <sylva/terrain/TilePyramid.hpp>
#include <sylva/scene/Sequence.hpp>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sylva::app {
namespace {

/** Throws unless `path` ends in one of `allowed` (lower-case, with the dot); names the option. */
void requireExtension(const std::string& option, const std::string& path,
                      const std::vector<std::string>& allowed) {
  const std::string ext = lowerExtension(path);
  if (std::find(allowed.begin(), allowed.end(), ext) == allowed.end()) {
    std::string list;
    for (const std::string& a : allowed) {
      list += (list.empty() ? "" : ", ") + a;
    }
    fail("{} {}: unsupported extension '{}' (use {})", option, path, ext, list);
  }
}

/**
 * Where the heights come from: a DEM file (--dem) or a procedural spec (--seed and/or --spec, with --type,
 * --size, --spacing, --height-scale). Shared by every terrain subcommand; check() enforces exactly one source
 * and rejects options that do not apply to it.
 */
std::string summary(const terrain::HeightField& field, const terrain::HeightFieldInfo& info) {
  return fmt::format("{}x{} samples, spacing {:g} x {:g} m, heights {:.3f} .. {:.3f} m, {} absent",
                     field.width(), field.height(), field.spacingX(), field.spacingZ(), info.minHeight,
                     info.maxHeight, info.absentCount);
}

std::string vec3(const glm::vec3& v, int decimals) {
  return fmt::format("({:.{}f}, {:.{}f}, {:.{}f})", v.x, decimals, v.y, decimals, v.z, decimals);
}

/** Path of splat page `page` of `count`: `out` itself for one page, else `<stem>_<page><ext>` beside it. */
std::filesystem::path pagePath(const std::filesystem::path& out, int page, int count) {
  if (count == 1) {
    return out;
  }
  std::filesystem::path result = out;
  result.replace_filename(fmt::format("{}_{}{}", out.stem().string(), page, out.extension().string()));
  return result;
}

/** An F32 image in the output's storage: raw floats for .exr, 8/16-bit for .png. */
Image forOutput(const std::string& path, const Image& image, int bits) {
  if (lowerExtension(path) == ".exr") {
    return image;
  }
  return image.converted(bits == 8 ? PixelType::U8 : PixelType::U16);
}

void registerHeightmap(CLI::App& terrainCommand) {
  auto* command = terrainCommand.add_subcommand(
      "heightmap",
      "Write a height map: .png (16-bit, normalised min..max, with a .json sidecar holding metres and "
      "spacing), "
      ".exr (float metres, with sidecar), .npy (float32 metres) or .tif (GeoTIFF, float32 metres)");
  struct Options {
    SourceOptions source;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  o->source.add(*command);
  command->add_option("-o,--out", o->out, "Output file (.png, .exr, .npy, .tif)")->required();
  command->callback([o] {
    o->source.check();
    requireExtension("-o", o->out, {".png", ".exr", ".npy", ".tif", ".tiff"});
    const terrain::HeightField field = o->source.load();
    terrain::saveHeightField(o->out, field);
    std::printf("%s\n", o->out.c_str());
    const std::string ext = lowerExtension(o->out);
    if (ext == ".png" || ext == ".exr") {
      std::printf("%s.json\n", o->out.c_str());
    }
    std::printf("%s\n", summary(field, terrain::heightFieldInfo(field)).c_str());
  });
}

void registerNormals(CLI::App& terrainCommand) {
  auto* command = terrainCommand.add_subcommand(
      "normals",
      "Write the CPU Sobel normal map (world space, y up): .png stores (n + 1) / 2, i.e. xyz remapped "
      "from [-1, 1] to [0, 1] as RGB; .exr stores the raw unit vectors as float RGB");
  struct Options {
    SourceOptions source;
    std::string out;
    std::string border = "clamp";
    float borderHeight = 0.0f;
    int bits = 16;
  };
  auto o = std::make_shared<Options>();
  o->source.add(*command);
  command->add_option("-o,--out", o->out, "Output image (.png or .exr)")->required();
  command
      ->add_option("--border", o->border,
                   "Neighbours outside the grid: clamp (edge sample) or constant (--border-height metres)")
      ->check(CLI::IsMember({"clamp", "constant"}))
      ->capture_default_str();
  command
      ->add_option("--border-height", o->borderHeight, "Height of outside neighbours with --border constant")
      ->check(finiteRange(-kMaxHeightScale, kMaxHeightScale))
      ->capture_default_str();
  command->add_option("--bits", o->bits, "PNG bit depth (8 or 16)")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  command->callback([o] {
    o->source.check();
    requireExtension("-o", o->out, {".png", ".exr"});
    const terrain::HeightField field = o->source.load();
    terrain::SobelOptions options;
    options.border = o->border == "constant" ? terrain::BorderMode::Constant : terrain::BorderMode::Clamp;
    options.constantHeight = o->borderHeight;
    Image normals = terrain::sobelNormalMap(field, options);
    if (lowerExtension(o->out) == ".png") {
      for (float& v : normals.values<float>()) {
        v = v * 0.5f + 0.5f;
      }
    }
    saveImage(o->out, forOutput(o->out, normals, o->bits));
    std::printf("%s\n", o->out.c_str());
    std::printf("%dx%d normals (%s), border %s, from %s\n", normals.width(), normals.height(),
                lowerExtension(o->out) == ".png" ? "xyz remapped to [0, 1]" : "raw xyz", o->border.c_str(),
                summary(field, terrain::heightFieldInfo(field)).c_str());
  });
}

void registerSplat(CLI::App& terrainCommand) {
  auto* command = terrainCommand.add_subcommand(
      "splat",
      "Write splat (blend) weights by height and slope as RGBA pages, layer 4k + c in channel c of page "
      "k: one page is written to -o itself, several to <stem>_0<ext>, <stem>_1<ext>, ...");
  struct Options {
    SourceOptions source;
    std::string out;
    std::string layers;
    std::string writeDefaults;
    int bits = 8;
  };
  auto o = std::make_shared<Options>();
  o->source.add(*command);
  auto* outOption = command->add_option("-o,--out", o->out, "Output image (.png or .exr)");
  auto* layersOption = command->add_option(
      "--layers", o->layers, "Layer rules JSON (default: sand/grass/snow/rock fitted to the height range)");
  auto* writeOption = command->add_option("--write-default-layers", o->writeDefaults,
                                          "Write the default rules for this terrain's height range to this "
                                          "JSON file, to edit and pass to --layers");
  layersOption->excludes(writeOption);
  command->add_option("--bits", o->bits, "PNG bit depth (8 or 16)")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  command->callback([o, outOption, writeOption] {
    o->source.check();
    if (outOption->count() == 0 && writeOption->count() == 0) {
      fail("-o: required (or --write-default-layers FILE)");
    }
    if (outOption->count() > 0) {
      requireExtension("-o", o->out, {".png", ".exr"});
    }
    if (writeOption->count() > 0) {
      requireExtension("--write-default-layers", o->writeDefaults, {".json"});
    }
    std::vector<terrain::SplatLayer> layers;
    if (!o->layers.empty()) {
      layers = terrain::loadSplatLayers(o->layers); // before any work: a bad rules file writes nothing
    }
    const terrain::HeightField field = o->source.load();
    const terrain::HeightFieldInfo info = terrain::heightFieldInfo(field);
    if (layers.empty()) {
      layers = terrain::defaultSplatLayers(info.minHeight, info.maxHeight);
    }
    if (writeOption->count() > 0) {
      terrain::saveSplatLayers(o->writeDefaults, layers);
      std::printf("%s\n", o->writeDefaults.c_str());
    }
    if (outOption->count() == 0) {
      return;
    }
    const Image normals = terrain::sobelNormalMap(field);
    const std::vector<Image> pages = terrain::splatMap(field, normals, layers);
    std::vector<Image> outputs;
    outputs.reserve(pages.size());
    for (const Image& page : pages) {
      outputs.push_back(forOutput(o->out, page, o->bits));
    }
    const int count = static_cast<int>(pages.size());
    for (int k = 0; k < count; ++k) {
      const std::filesystem::path path = pagePath(o->out, k, count);
      saveImage(path, outputs[static_cast<std::size_t>(k)]);
      std::printf("%s\n", path.string().c_str());
    }
    std::string names;
    for (const terrain::SplatLayer& layer : layers) {
      names += (names.empty() ? "" : ", ") + layer.name;
    }
    std::printf("%zu layers on %d page%s (%s), %dx%d\n", layers.size(), count, count == 1 ? "" : "s",
                names.c_str(), field.width(), field.height());
  });
}

void registerTerrainInfo(CLI::App& terrainCommand) {
  auto* command = terrainCommand.add_subcommand(
      "info",
      "Print size, spacing, extent, height range, absent samples and the default 16-root quadtree layout");
  struct Options {
    SourceOptions source;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  o->source.add(*command);
  command->add_flag("--json", o->json, "Print JSON instead of text");
  command->callback([o] {
    terrain::LoadReport report;
    const terrain::HeightField field = o->source.load(&report);
    if (o->json) {
      std::printf("%s\n",
                  terrain::describeHeightFieldJson(field, report, o->source.describe()).dump(2).c_str());
    } else {
      std::fputs(terrain::describeHeightField(field, report, o->source.describe()).c_str(), stdout);
    }
  });
}

void registerQuery(CLI::App& terrainCommand) {
  auto* command = terrainCommand.add_subcommand(
      "query",
      "Print the height and normal at world (x, z) metres (--at), or the first hit of a ray (--ray); "
      "sample (i, j) is at x = i * spacingX, z = j * spacingZ, y up");
  struct Options {
    SourceOptions source;
    std::string at;
    std::string ray;
    bool bicubic = false;
    float maxDistance = 0.0f;
  };
  auto o = std::make_shared<Options>();
  o->source.add(*command);
  auto* atOption = command->add_option("--at", o->at, "World position X,Z in metres");
  auto* rayOption =
      command->add_option("--ray", o->ray, "Ray OX,OY,OZ,DX,DY,DZ: origin in metres, direction");
  command->add_flag("--bicubic", o->bicubic, "Catmull-Rom interpolation instead of bilinear");
  auto* maxOption = command
                        ->add_option("--max-distance", o->maxDistance,
                                     "Longest ray, metres (default: far enough to cross the whole terrain)")
                        ->check(finiteRange(0.0, 1.0e12));
  command->callback([o, atOption, rayOption, maxOption] {
    o->source.check();
    if (atOption->count() == 0 && rayOption->count() == 0) {
      fail("--at X,Z or --ray OX,OY,OZ,DX,DY,DZ: give at least one");
    }
    std::optional<std::vector<float>> at;
    std::optional<std::vector<float>> ray;
    if (atOption->count() > 0) {
      at = parseNumbers("--at", o->at, 2, "X,Z");
    }
    if (rayOption->count() > 0) {
      ray = parseNumbers("--ray", o->ray, 6, "OX,OY,OZ,DX,DY,DZ");
      if ((*ray)[3] == 0.0f && (*ray)[4] == 0.0f && (*ray)[5] == 0.0f) {
        fail("--ray: direction ({}, {}, {}) is zero", (*ray)[3], (*ray)[4], (*ray)[5]);
      }
    }
    const terrain::HeightField field = o->source.load();
    const terrain::Interpolation interpolation =
        o->bicubic ? terrain::Interpolation::Bicubic : terrain::Interpolation::Bilinear;
    if (at) {
      const float x = (*at)[0];
      const float z = (*at)[1];
      const float h = terrain::heightAt(field, x, z, interpolation);
      const bool outside = x < 0.0f || z < 0.0f || x > field.extentX() || z > field.extentZ();
      const char* note = outside ? " (outside the footprint: edge heights continue)" : "";
      if (std::isnan(h)) {
        std::printf("at (%g, %g) m: height absent (nodata)%s\n", static_cast<double>(x),
                    static_cast<double>(z), note);
      } else {
        const glm::vec3 n = terrain::normalAt(field, x, z, interpolation);
        std::printf("at (%g, %g) m: height %.3f m, normal %s%s\n", static_cast<double>(x),
                    static_cast<double>(z), static_cast<double>(h), vec3(n, 4).c_str(), note);
      }
    }
    if (ray) {
      const glm::vec3 origin((*ray)[0], (*ray)[1], (*ray)[2]);
      const glm::vec3 dir((*ray)[3], (*ray)[4], (*ray)[5]);
      float maxDistance = o->maxDistance;
      if (maxOption->count() == 0) {
        // Any hit lies inside the box footprint × height range: within |origin − centre| + half its diagonal.
        const terrain::HeightFieldInfo info = terrain::heightFieldInfo(field);
        const glm::vec3 lo(0.0f, info.minHeight, 0.0f);
        const glm::vec3 hi(field.extentX(), info.maxHeight, field.extentZ());
        maxDistance = glm::length(origin - 0.5f * (lo + hi)) + 0.5f * glm::length(hi - lo) + 1.0f;
      }
      const std::optional<terrain::RayHit> hit =
          terrain::raycast(field, origin, dir, maxDistance, interpolation);
      if (hit) {
        std::printf("hit at %s m, distance %.3f m, normal %s\n", vec3(hit->position, 3).c_str(),
                    static_cast<double>(hit->distance), vec3(hit->normal, 4).c_str());
      } else {
        std::printf("miss\n");
      }
    }
  });
}

void registerPyramid(CLI::App& terrainCommand) {
  auto* command = terrainCommand.add_subcommand(
      "pyramid",
      "Cut a DEM into a tile pyramid (docs/terrain-data.md): compressed tiles of (T+1)^2 heights at every "
      "level of detail, with height ranges and geometric errors, built tile by tile in bounded memory on all "
      "cores; resumes an interrupted build; --shard splits level 0 across Slurm array tasks");
  struct Options {
    std::string dem;
    std::string out;
    int tileSize = 256;
    std::string shard;
    float pngScale = 100.0f;
    float spacing = 0.0f;
    std::string npzArray;
    bool geographic = false;
    bool flipY = false;
  };
  auto o = std::make_shared<Options>();
  command
      ->add_option("dem", o->dem,
                   "The DEM: any GDAL raster (GeoTIFF, ...; read window by window, so it may be larger "
                   "than memory), or .png/.exr/.npy/.npz (loaded whole)")
      ->required();
  command->add_option("-o,--out", o->out, "The pyramid's folder (created; an unfinished build there resumes)")
      ->required();
  command
      ->add_option("--tile-size", o->tileSize,
                   fmt::format("Samples per tile edge T (a tile holds (T+1)^2 heights), {}..{}",
                               terrain::kMinTileSize, terrain::kMaxTileSize))
      ->default_val(256)
      ->check(CLI::Range(terrain::kMinTileSize, terrain::kMaxTileSize));
  command->add_option(
      "--shard", o->shard,
      "i/n: build only level 0's tiles k with k mod n = i (counted from 0), for one task of a "
      "job array; a last run without --shard builds the coarser levels and reuses them");
  command->add_option("--spacing", o->spacing, "Metres between samples, overriding the file's coordinates")
      ->check(finiteRange(kMinSpacing, kMaxSpacing));
  command->add_flag("--geographic", o->geographic,
                    "Read the file's coordinates as longitude/latitude degrees");
  command->add_flag("--flip-y", o->flipY, "Reverse the rows (for files that are wrong about north)");
  command->add_option("--png-scale", o->pngScale, "Metres of PNG value 1.0 (PNG without sidecar)")
      ->check(finiteRange(1e-6, kMaxHeightScale));
  command->add_option("--npz-array", o->npzArray, "Array inside an .npz (default: the first 2D array)");
  command->callback([o] {
    scene::Shard shard;
    if (!o->shard.empty()) {
      shard = scene::parseShard(o->shard);
    }
    const std::filesystem::path out = o->out;
    std::error_code ec;
    if (std::filesystem::exists(out, ec) && !std::filesystem::is_directory(out, ec)) {
      fail("-o {}: exists and is not a folder", out.string());
    }
    terrain::LoadOptions load;
    load.heightScale = o->pngScale;
    load.spacing = o->spacing;
    load.npzArray = o->npzArray;
    load.horizontal = o->geographic ? terrain::HorizontalUnits::Degrees : terrain::HorizontalUnits::Auto;
    load.flipY = o->flipY;
    const auto start = std::chrono::steady_clock::now();
    const auto raster = terrain::HeightRaster::open(o->dem, load);
    const terrain::PyramidInfo plan = terrain::PyramidInfo::plan(
        raster->width(), raster->height(), raster->spacingX(), raster->spacingZ(), o->tileSize);
    std::printf("%s: %dx%d samples at %g x %g m; %d levels of %dx%d tiles (T = %d), %llu tiles in all\n",
                o->dem.c_str(), raster->width(), raster->height(), static_cast<double>(raster->spacingX()),
                static_cast<double>(raster->spacingZ()), plan.levels, plan.level(0).tilesX,
                plan.level(0).tilesY, o->tileSize, static_cast<unsigned long long>(plan.tiles));
    std::fflush(stdout);
    std::optional<Progress> progress;
    terrain::PyramidOptions options;
    options.tileSize = o->tileSize;
    options.shardIndex = shard.index;
    options.shardCount = shard.count;
    options.source = o->dem;
    options.onTile = [&progress](std::size_t, std::size_t) {
      if (!progress) {
        return;
      }
      if (progress->cancelled()) {
        fail("pyramid: cancelled (finished tiles are kept; run again to resume)");
      }
      progress->advance();
    };
    {
      const terrain::PyramidLevel base = plan.level(0);
      const std::size_t baseTiles =
          static_cast<std::size_t>(base.tilesX) * static_cast<std::size_t>(base.tilesY);
      const std::size_t mine = (baseTiles + shard.count - 1 - shard.index) / shard.count;
      progress.emplace("pyramid tiles", shard.count > 1 ? mine : static_cast<std::size_t>(plan.tiles));
    }
    const terrain::PyramidBuild build = terrain::buildPyramid(*raster, out, options);
    progress.reset();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (shard.count > 1) {
      std::printf(
          "shard %d/%d: level 0 tiles: %zu written, %zu kept (%.1f MB) in %.1f s; run without --shard "
          "to finish\n",
          shard.index, shard.count, build.written, build.kept,
          static_cast<double>(build.writtenBytes) / 1.0e6, seconds);
      return;
    }
    const double raw = static_cast<double>(build.info.tiles) * static_cast<double>(o->tileSize + 1) *
                       static_cast<double>(o->tileSize + 1) * 4.0;
    std::printf(
        "%s: %zu tiles written, %zu kept; %.2f MB on disk (%.2fx smaller than raw floats), heights "
        "%.3f .. %.3f m, in %.1f s\n",
        out.string().c_str(), build.written, build.kept, static_cast<double>(build.info.bytes) / 1.0e6,
        raw / std::max(1.0, static_cast<double>(build.info.bytes)), static_cast<double>(build.info.minHeight),
        static_cast<double>(build.info.maxHeight), seconds);
  });
}

} // namespace

void registerTerrain(CLI::App& app) {
  auto* command = app.add_subcommand(
      "terrain",
      "Terrain tools: height, normal and splat maps from a DEM or a seed; info; height queries; tile "
      "pyramids");
  command->require_subcommand(1);
  registerHeightmap(*command);
  registerNormals(*command);
  registerSplat(*command);
  registerTerrainInfo(*command);
  registerQuery(*command);
  registerPyramid(*command);
}

} // namespace sylva::app

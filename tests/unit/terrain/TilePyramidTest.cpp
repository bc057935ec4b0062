#include <sylva/terrain/TilePyramid.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>

#include "TempDir.hpp"
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace sylva::terrain {
namespace {

using test::errorOf;
using test::kNaN;
using test::sameBits;

/** A rough procedural field of w × h samples with an absent patch (NaN), spacing 2 × 3 m. */
HeightField roughField(int w, int h, std::uint64_t seed = 3) {
  ProceduralSpec spec;
  spec.seed = seed;
  spec.type = ProceduralSpec::Type::Ridged;
  spec.frequency = 1.0f / 64.0f;
  spec.heightScale = 300.0f;
  HeightField field = generate(spec, 0.0, 0.0, w, h, 2.0f);
  field.setSpacing(2.0f, 3.0f);
  for (int j = h / 3; j < h / 3 + 7; ++j) {
    for (int i = w / 2; i < w / 2 + 5; ++i) {
      field.at(i, j) = kNaN;
    }
  }
  return field;
}

std::vector<std::uint8_t> fileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/** Level `level`'s samples of `field` by the documented rule: sample i of level L + 1 is min(2i, w_L − 1). */
HeightField decimated(const HeightField& field, int level) {
  HeightField current = field;
  for (int l = 0; l < level; ++l) {
    HeightField next((current.width() - 1 + 1) / 2 + 1, (current.height() - 1 + 1) / 2 + 1);
    for (int j = 0; j < next.height(); ++j) {
      for (int i = 0; i < next.width(); ++i) {
        next.at(i, j) =
            current.at(std::min(2 * i, current.width() - 1), std::min(2 * j, current.height() - 1));
      }
    }
    current = std::move(next);
  }
  return current;
}

TEST(TilePyramid, PlanCountsLevelsUntilOneTileHoldsAll) {
  const PyramidInfo a = PyramidInfo::plan(257, 257, 1.0f, 1.0f, 256);
  EXPECT_EQ(a.levels, 1);
  EXPECT_EQ(a.tiles, 1u);
  const PyramidInfo b = PyramidInfo::plan(258, 100, 1.0f, 1.0f, 256);
  EXPECT_EQ(b.levels, 2);
  EXPECT_EQ(b.level(0).tilesX, 2);
  EXPECT_EQ(b.level(1).width, 130);
  const PyramidInfo world = PyramidInfo::plan((1 << 20) + 1, (1 << 20) + 1, 1.0f, 1.0f, 256);
  EXPECT_EQ(world.levels, 13);
  EXPECT_EQ(world.level(0).tilesX, 4096);
  EXPECT_EQ(world.level(12).width, 257);
  EXPECT_NE(errorOf([] { (void)PyramidInfo::plan(100, 100, 1.0f, 1.0f, 8); }).find("tile size 8"),
            std::string::npos);
  // A raster that size in tiles of 16 would need gigabytes of tile summaries: refused before any read.
  struct Huge final : HeightRaster {
    Huge() : HeightRaster(kMaxRasterSide, kMaxRasterSide, 1.0f, 1.0f) {}
    void read(int, int, int, int, float*) const override { ADD_FAILURE() << "read"; }
  };
  test::TempDir dir;
  EXPECT_NE(errorOf([&] {
              (void)buildPyramid(Huge(), dir / "huge", {.tileSize = 16});
            }).find("use a larger --tile-size"),
            std::string::npos);
}

TEST(TilePyramid, TileCodecIsLosslessAndRejectsEveryDamage) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> height(-500.0f, 4000.0f);
  TileData tile;
  tile.key = {3, 7, 2};
  tile.size = 32;
  tile.heights.resize(33 * 33);
  for (float& h : tile.heights) {
    h = height(rng);
  }
  tile.heights[40] = kNaN;
  tile.heights[41] = -0.0f;
  tile.summary = {-500.0f, 4000.0f, 1.5f};
  const std::vector<std::uint8_t> bytes = encodeTile(tile);
  const TileData back = decodeTile(bytes.data(), bytes.size(), "t.tile");
  EXPECT_EQ(back.key, tile.key);
  EXPECT_EQ(back.size, 32);
  EXPECT_EQ(back.summary.error, 1.5f);
  for (std::size_t k = 0; k < tile.heights.size(); ++k) {
    ASSERT_TRUE(sameBits(back.heights[k], tile.heights[k])) << k;
  }
  // Every single-byte change and every truncation is refused with one line naming the file.
  for (std::size_t at = 0; at < bytes.size(); at += 7) {
    std::vector<std::uint8_t> damaged = bytes;
    damaged[at] ^= 0x5a;
    const std::string message = errorOf([&] { (void)decodeTile(damaged.data(), damaged.size(), "t.tile"); });
    ASSERT_EQ(message.rfind("t.tile: ", 0), 0u) << "byte " << at << ": " << message;
    ASSERT_EQ(message.find('\n'), std::string::npos);
  }
  for (const std::size_t keep : {std::size_t{0}, std::size_t{20}, std::size_t{48}, bytes.size() - 1}) {
    EXPECT_EQ(errorOf([&] { (void)decodeTile(bytes.data(), keep, "t.tile"); }).rfind("t.tile: ", 0), 0u);
  }
  // Smooth heights pack well: the predictor's point.
  TileData smooth = tile;
  for (int b = 0; b <= 32; ++b) {
    for (int a = 0; a <= 32; ++a) {
      smooth.heights[static_cast<std::size_t>(b) * 33 + a] = 100.0f + 0.25f * static_cast<float>(a + b);
    }
  }
  smooth.summary = {100.0f, 116.0f, 0.0f};
  EXPECT_LT(encodeTile(smooth).size(), 33u * 33u * 4u / 4u);
}

TEST(TilePyramid, LevelsAreTheDecimatedFieldAndLevelZeroQueriesEqualHeightAt) {
  test::TempDir dir;
  const HeightField field = roughField(301, 190);
  const PyramidBuild build = buildPyramid(*HeightRaster::fromField(field), dir.path(), {.tileSize = 32});
  EXPECT_EQ(build.info.levels, 5);
  EXPECT_EQ(build.written, build.info.tiles);
  const auto pyramid = TilePyramid::open(dir.path());
  const PyramidInfo& info = pyramid->info();
  EXPECT_TRUE(info.complete);
  const HeightFieldInfo range = heightFieldInfo(field);
  EXPECT_EQ(info.minHeight, range.minHeight);
  EXPECT_EQ(info.maxHeight, range.maxHeight);
  for (int level = 0; level < info.levels; ++level) {
    const HeightField expected = decimated(field, level);
    const PyramidLevel l = info.level(level);
    ASSERT_EQ(l.width, expected.width());
    ASSERT_EQ(l.height, expected.height());
    for (int ty = 0; ty < l.tilesY; ++ty) {
      for (int tx = 0; tx < l.tilesX; ++tx) {
        const auto tile = pyramid->tile({level, tx, ty});
        for (int b = 0; b <= 32; ++b) {
          for (int a = 0; a <= 32; ++a) {
            const int i = tx * 32 + a;
            const int j = ty * 32 + b;
            const float want = i < l.width && j < l.height ? expected.at(i, j) : kNaN;
            ASSERT_TRUE(sameBits(tile->at(a, b), want)) << "level " << level << " sample " << i << "," << j
                                                        << ": " << tile->at(a, b) << " vs " << want;
          }
        }
      }
    }
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> x(-10.0f, field.extentX() + 10.0f);
  std::uniform_real_distribution<float> z(-10.0f, field.extentZ() + 10.0f);
  for (int k = 0; k < 4000; ++k) {
    const float px = k < 300 ? static_cast<float>(k) * 2.0f : x(rng); // sample positions and tile borders too
    const float pz = k < 300 ? static_cast<float>(k % 190) * 3.0f : z(rng);
    const float want = heightAt(field, px, pz, Interpolation::Bilinear);
    ASSERT_TRUE(sameBits(pyramid->heightAt(px, pz), want)) << px << "," << pz;
  }
}

TEST(TilePyramid, RangesAndErrorsBoundEveryFinerSample) {
  test::TempDir dir;
  const HeightField field = roughField(200, 170, 9);
  buildPyramid(*HeightRaster::fromField(field), dir.path(), {.tileSize = 16});
  const auto pyramid = TilePyramid::open(dir.path());
  const PyramidInfo& info = pyramid->info();
  double tightest = 1e30;
  for (int level = 1; level < info.levels; ++level) {
    const PyramidLevel l = info.level(level);
    const double step = std::ldexp(1.0, level);
    for (int ty = 0; ty < l.tilesY; ++ty) {
      for (int tx = 0; tx < l.tilesX; ++tx) {
        const TileSummary& s = pyramid->summary({level, tx, ty});
        EXPECT_EQ(s.error, pyramid->tile({level, tx, ty})->summary.error);
        double worst = 0.0;
        // Every level-0 sample in the tile's footprint: inside the range, and within `error` of the level's
        // bilinear surface (evaluated by the pyramid's own query at that level).
        const int i0 = static_cast<int>(tx * 16 * step);
        const int j0 = static_cast<int>(ty * 16 * step);
        for (int j = j0; j <= std::min(field.height() - 1, static_cast<int>(j0 + 16 * step)); ++j) {
          for (int i = i0; i <= std::min(field.width() - 1, static_cast<int>(i0 + 16 * step)); ++i) {
            const float h = field.at(i, j);
            if (std::isnan(h)) {
              continue;
            }
            EXPECT_GE(h, s.minHeight);
            EXPECT_LE(h, s.maxHeight);
            const float surface =
                pyramid->heightAt(static_cast<float>(i) * 2.0f, static_cast<float>(j) * 3.0f, level);
            if (!std::isnan(surface)) {
              worst = std::max(worst, std::abs(static_cast<double>(surface) - h));
            }
          }
        }
        ASSERT_LE(worst, static_cast<double>(s.error) * (1.0 + 1e-6) + 1e-4)
            << "level " << level << " tile " << tx << "," << ty;
        if (worst > 0.0) {
          tightest = std::min(tightest, s.error / worst);
        }
      }
    }
  }
  EXPECT_LT(tightest, 1.5) << "the hierarchical bound should be tight somewhere";
}

TEST(TilePyramid, ShardsAndResumedBuildsWriteTheSameTiles) {
  test::TempDir dir;
  const auto raster = HeightRaster::fromField(roughField(150, 120, 4));
  const PyramidBuild whole = buildPyramid(*raster, dir / "whole", {.tileSize = 16});
  for (int shard = 0; shard < 3; ++shard) {
    const PyramidBuild part =
        buildPyramid(*raster, dir / "sharded", {.tileSize = 16, .shardIndex = shard, .shardCount = 3});
    EXPECT_FALSE(part.info.complete);
    EXPECT_EQ(part.kept, 0u);
  }
  EXPECT_NE(errorOf([&] { (void)TilePyramid::open(dir / "sharded"); }).find("'complete' is false"),
            std::string::npos);
  const PyramidBuild finish = buildPyramid(*raster, dir / "sharded", {.tileSize = 16});
  const PyramidLevel base = whole.info.level(0);
  EXPECT_EQ(finish.kept, static_cast<std::size_t>(base.tilesX * base.tilesY));
  EXPECT_EQ(finish.written, whole.written - finish.kept);

  // Damage one tile and delete another: a rerun rewrites exactly those two.
  const std::filesystem::path damaged = tilePath(dir / "sharded", {0, 2, 1});
  std::vector<std::uint8_t> bytes = fileBytes(damaged);
  bytes[bytes.size() / 2] ^= 1;
  std::ofstream(damaged, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  std::filesystem::remove(tilePath(dir / "sharded", {1, 0, 0}));
  const PyramidBuild again = buildPyramid(*raster, dir / "sharded", {.tileSize = 16});
  EXPECT_EQ(again.written, 2u);

  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir / "whole")) {
    if (entry.is_regular_file()) {
      const auto relative = std::filesystem::relative(entry.path(), dir / "whole");
      EXPECT_EQ(fileBytes(entry.path()), fileBytes(dir / "sharded" / relative)) << relative;
    }
  }
}

TEST(TilePyramid, RefusesAnotherSourcesFolderAndBadShards) {
  test::TempDir dir;
  buildPyramid(*HeightRaster::fromField(roughField(100, 90)), dir.path(), {.tileSize = 16});
  const std::string other = errorOf(
      [&] { buildPyramid(*HeightRaster::fromField(roughField(101, 90)), dir.path(), {.tileSize = 16}); });
  EXPECT_NE(other.find("pyramid.json: holds a pyramid of 100x90"), std::string::npos) << other;
  EXPECT_NE(errorOf([&] {
              buildPyramid(*HeightRaster::fromField(roughField(100, 90)), dir / "x",
                           {.tileSize = 16, .shardIndex = 2, .shardCount = 2});
            }).find("shards count from 0"),
            std::string::npos);
  HeightField empty(40, 40, 1.0f, 1.0f, kNaN);
  EXPECT_NE(errorOf([&] {
              buildPyramid(*HeightRaster::fromField(empty), dir / "empty", {.tileSize = 16});
            }).find("all 40x40 samples are absent"),
            std::string::npos);
}

TEST(TilePyramid, CacheStaysWithinItsBudget) {
  test::TempDir dir;
  const HeightField field = roughField(400, 400, 6);
  buildPyramid(*HeightRaster::fromField(field), dir.path(), {.tileSize = 32});
  const std::size_t tileBytes = 33 * 33 * sizeof(float);
  const auto pyramid = TilePyramid::open(dir.path(), 3 * tileBytes);
  std::size_t peak = 0;
  for (int j = 0; j < field.height(); j += 7) {
    for (int i = 0; i < field.width(); i += 5) {
      const float h = pyramid->heightAt(static_cast<float>(i) * 2.0f, static_cast<float>(j) * 3.0f);
      ASSERT_TRUE(sameBits(h, field.at(i, j)));
      peak = std::max(peak, pyramid->cachedBytes());
    }
  }
  EXPECT_LE(peak, 3 * tileBytes);
  EXPECT_GT(pyramid->tilesRead(), 13u * 13u) << "a small cache reads tiles again";
}

TEST(TilePyramid, PyramidJsonErrorsNameTheField) {
  test::TempDir dir;
  buildPyramid(*HeightRaster::fromField(roughField(60, 60)), dir.path(), {.tileSize = 16});
  const std::filesystem::path json = dir / "pyramid.json";
  const std::string good = readTextFile(json);
  const auto expectField = [&](const std::string& from, const std::string& to, const std::string& field) {
    std::string text = good;
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    writeTextFile(json, text);
    const std::string message = errorOf([&] { (void)TilePyramid::open(dir.path()); });
    EXPECT_NE(message.find("pyramid.json"), std::string::npos) << message;
    EXPECT_NE(message.find(field), std::string::npos) << message;
  };
  expectField("\"levels\": 3", "\"levels\": 4", "'levels'");
  expectField("\"tileSize\": 16", "\"tileSize\": 1", "'tileSize'");
  expectField("\"width\": 60", "\"width\": \"60\"", "'width'");
  expectField("\"format\": \"sylva-pyramid\"", "\"format\": \"x\"", "'format'");
  writeTextFile(json, good);
  std::filesystem::remove(dir / "1" / "index.bin");
  EXPECT_NE(errorOf([&] { (void)TilePyramid::open(dir.path()); }).find("index.bin"), std::string::npos);
  EXPECT_NE(errorOf([&] { (void)TilePyramid::open(dir / "nothing"); }).find("not a folder"),
            std::string::npos);
}

/** A float32 GeoTIFF written south-up (positive row step) with nodata, scale and offset. */
void writeSouthUpGeoTiff(const std::filesystem::path& path, const HeightField& field) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  char* options[] = {const_cast<char*>("TILED=YES"), const_cast<char*>("BLOCKXSIZE=32"),
                     const_cast<char*>("BLOCKYSIZE=32"), nullptr};
  std::unique_ptr<GDALDataset> ds(
      driver->Create(path.string().c_str(), field.width(), field.height(), 1, GDT_Float32, options));
  ASSERT_NE(ds, nullptr);
  double gt[6] = {0.0, 2.0, 0.0, 0.0, 0.0, 3.0};
  ds->SetGeoTransform(gt);
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetNoDataValue(-9999.0);
  band->SetScale(0.5);
  band->SetOffset(10.0);
  std::vector<float> values(field.samples().size());
  for (int y = 0; y < field.height(); ++y) {
    for (int x = 0; x < field.width(); ++x) {
      const float h = field.at(x, field.height() - 1 - y);
      values[static_cast<std::size_t>(y) * field.width() + x] = std::isnan(h) ? -9999.0f : (h - 10.0f) * 2.0f;
    }
  }
  ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, field.width(), field.height(), values.data(), field.width(),
                           field.height(), GDT_Float32, 0, 0, nullptr),
            CE_None);
}

TEST(TilePyramid, GdalWindowsEqualTheLoadedField) {
  test::TempDir dir;
  writeSouthUpGeoTiff(dir / "dem.tif", roughField(150, 97, 8));
  for (const bool flip : {false, true}) {
    LoadOptions options;
    options.flipY = flip;
    const HeightField loaded = loadHeightField(dir / "dem.tif", options);
    LoadReport report;
    const auto raster = HeightRaster::open(dir / "dem.tif", options, &report);
    EXPECT_EQ(raster->width(), loaded.width());
    EXPECT_EQ(raster->spacingX(), loaded.spacingX());
    EXPECT_EQ(raster->spacingZ(), loaded.spacingZ());
    EXPECT_NE(report.orientation.find("south-up"), std::string::npos) << report.orientation;
    for (const auto& [i0, j0, w, h] : {std::array{0, 0, 150, 97}, std::array{33, 5, 40, 61},
                                       std::array{149, 96, 1, 1}, std::array{70, 30, 17, 9}}) {
      std::vector<float> window(static_cast<std::size_t>(w) * h);
      raster->read(i0, j0, w, h, window.data());
      for (int b = 0; b < h; ++b) {
        for (int a = 0; a < w; ++a) {
          ASSERT_TRUE(sameBits(window[static_cast<std::size_t>(b) * w + a], loaded.at(i0 + a, j0 + b)))
              << "flip " << flip << " at " << i0 + a << "," << j0 + b;
        }
      }
    }
    EXPECT_NE(errorOf([&] {
                std::vector<float> out(4);
                raster->read(149, 0, 2, 2, out.data());
              }).find("outside"),
              std::string::npos);
    // The pyramid of the file equals the pyramid of the loaded field, byte for byte.
    const std::string tag = flip ? "flip" : "plain";
    buildPyramid(*raster, dir / (tag + "-file"), {.tileSize = 32});
    buildPyramid(*HeightRaster::fromField(loaded), dir / (tag + "-field"), {.tileSize = 32});
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir / (tag + "-file"))) {
      if (entry.is_regular_file() && entry.path().extension() != ".json") {
        const auto relative = std::filesystem::relative(entry.path(), dir / (tag + "-file"));
        EXPECT_EQ(fileBytes(entry.path()), fileBytes(dir / (tag + "-field") / relative)) << relative;
      }
    }
  }
}

} // namespace
} // namespace sylva::terrain

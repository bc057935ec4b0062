// `sylva terrain pyramid`: a GeoTIFF larger than the process's memory limit (`ulimit -v`) becomes a tile
// pyramid whose samples are the file's; the same file cannot be loaded whole under that limit (so the test
// can fail). Also: shards and resume through the real command, one-line errors.
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/terrain/TilePyramid.hpp>

#include "CliRun.hpp"
#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <gdal_priv.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace sylva::test {
namespace {

/** The analytic surface the big file holds, metres: smooth hills plus a finer ripple. */
float surface(int i, int j) {
  const double x = i;
  const double z = j;
  return static_cast<float>(600.0 + 300.0 * std::sin(x / 700.0) * std::cos(z / 900.0) +
                            25.0 * std::sin(x / 37.0 + z / 53.0));
}

/**
 * A float32 GeoTIFF of side × side samples (tiled 256², DEFLATE with the floating-point predictor), 30 m
 * spacing in a projected CRS, written band by band so the test itself stays small in memory.
 */
void writeBigGeoTiff(const std::filesystem::path& path, int side) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  char* options[] = {const_cast<char*>("TILED=YES"),        const_cast<char*>("COMPRESS=DEFLATE"),
                     const_cast<char*>("PREDICTOR=3"),      const_cast<char*>("ZLEVEL=1"),
                     const_cast<char*>("BIGTIFF=IF_SAFER"), nullptr};
  std::unique_ptr<GDALDataset> ds(driver->Create(path.string().c_str(), side, side, 1, GDT_Float32, options));
  ASSERT_NE(ds, nullptr);
  double gt[6] = {500000.0, 30.0, 0.0, 5000000.0, 0.0, -30.0};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(32633);
  ds->SetSpatialRef(&srs);
  std::vector<float> band(static_cast<std::size_t>(side) * 256);
  for (int y0 = 0; y0 < side; y0 += 256) {
    const int rows = std::min(256, side - y0);
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < side; ++x) {
        band[static_cast<std::size_t>(y) * side + x] = surface(x, y0 + y);
      }
    }
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, y0, side, rows, band.data(), side, rows,
                                             GDT_Float32, 0, 0, nullptr),
              CE_None);
  }
}

/**
 * `sylva args` under `ulimit -v kib` with two workers, llvmpipe rasterising on the calling thread and two
 * malloc arenas (each thread's arena and stack reserve address space, which `ulimit -v` counts).
 */
RunResult runLimited(const TempDir& dir, long kib, const std::string& args) {
  return runProgram("/bin/sh", dir.path(),
                    "-c " + quote(fmt::format("ulimit -v {} && SYLVA_THREADS=2 LP_NUM_THREADS=0 "
                                              "MALLOC_ARENA_MAX=2 exec {} {}",
                                              kib, quote(SYLVA_EXE), args)));
}

TEST(CliPyramid, DemLargerThanTheMemoryLimitBecomesAPyramid) {
  TempDir dir;
  // CI: 13,501² floats = 729 MB under a 704,000 KiB (721 MB) limit; full: 16,385² = 1.07 GB under 1 GiB. The
  // process itself takes about 350 MB of address space (shared libraries; llvmpipe more once it renders).
  const bool full = fullMode();
  const int side = full ? 16385 : 13501;
  const long limitKib = full ? 1048576 : 704000;
  ASSERT_GT(static_cast<double>(side) * side * 4.0, limitKib * 1024.0) << "the DEM must exceed the limit";
  writeBigGeoTiff(dir / "big.tif", side);

  // Loaded whole, the file does not fit: the limit is real.
  const RunResult whole = runLimited(dir, limitKib, "terrain info --dem " + at(dir, "big.tif"));
  EXPECT_NE(whole.status, 0) << whole.out << whole.err;
  EXPECT_NE(whole.err.find("out of memory"), std::string::npos) << whole.err;

  const RunResult built =
      runLimited(dir, limitKib, "terrain pyramid " + at(dir, "big.tif") + " -o " + at(dir, "pyr"));
  ASSERT_EQ(built.status, 0) << built.out << built.err;
  std::printf("%s", built.out.c_str()); // the timing and size line, for docs/terrain-data.md
  EXPECT_NE(built.out.find(fmt::format("{}x{} samples at 30 x 30 m", side, side)), std::string::npos)
      << built.out;

  // And it renders under the same limit, streamed within small budgets.
  const RunResult drawn = runLimited(dir, limitKib,
                                     "render --pyramid " + at(dir, "pyr") +
                                         " --gpu-budget 18 --ram-budget 60 --width 320 --height 180 "
                                         "-o " +
                                         at(dir, "view.png"));
  ASSERT_EQ(drawn.status, 0) << drawn.out << drawn.err;
  const Image view = loadImage(dir / "view.png");
  int ground = 0; // pixels not of the clear colour (the top-left corner is sky)
  for (int y = 0; y < view.height(); ++y) {
    for (int x = 0; x < view.width(); ++x) {
      bool differs = false;
      for (int c = 0; c < 3; ++c) {
        differs = differs || std::abs(view.get(x, y, c) - view.get(0, 0, c)) > 0.02f;
      }
      ground += differs ? 1 : 0;
    }
  }
  EXPECT_GT(ground, view.width() * view.height() / 5) << "the DEM covers a good part of the view";

  const auto pyramid = terrain::TilePyramid::open(dir / "pyr", std::size_t{64} << 20);
  const terrain::PyramidInfo& info = pyramid->info();
  EXPECT_EQ(info.width, side);
  EXPECT_EQ(info.levels, full ? 7 : 7);
  EXPECT_EQ(info.spacingX, 30.0f);
  std::mt19937 rng(2);
  std::uniform_int_distribution<int> sample(0, side - 1);
  for (int k = 0; k < 2000; ++k) {
    const int i = k < 4 ? (k & 1) * (side - 1) : sample(rng);
    const int j = k < 4 ? (k >> 1) * (side - 1) : sample(rng);
    ASSERT_EQ(pyramid->heightAt(static_cast<float>(i) * 30.0f, static_cast<float>(j) * 30.0f), surface(i, j))
        << i << "," << j;
  }
  // The coarsest level is every 64th sample of the file.
  const int top = info.levels - 1;
  const int step = 1 << top;
  for (int j = 0; j < side; j += 37 * step) {
    for (int i = 0; i < side; i += 41 * step) {
      ASSERT_EQ(pyramid->heightAt(static_cast<float>(i) * 30.0f, static_cast<float>(j) * 30.0f, top),
                surface(i, j));
    }
  }
}

TEST(CliPyramid, ShardsThenAFinishingRunEqualOneRun) {
  TempDir dir;
  writeBigGeoTiff(dir / "dem.tif", 700);
  const RunResult one =
      runSylva(dir, "terrain pyramid " + at(dir, "dem.tif") + " -o " + at(dir, "one") + " --tile-size 64");
  ASSERT_EQ(one.status, 0) << one.err;
  for (int shard = 0; shard < 4; ++shard) {
    const RunResult part = runSylva(dir, "terrain pyramid " + at(dir, "dem.tif") + " -o " + at(dir, "four") +
                                             fmt::format(" --tile-size 64 --shard {}/4", shard));
    ASSERT_EQ(part.status, 0) << part.err;
    EXPECT_NE(part.out.find("run without --shard to finish"), std::string::npos) << part.out;
  }
  const RunResult finish =
      runSylva(dir, "terrain pyramid " + at(dir, "dem.tif") + " -o " + at(dir, "four") + " --tile-size 64");
  ASSERT_EQ(finish.status, 0) << finish.err;
  EXPECT_NE(finish.out.find("121 kept"), std::string::npos) << finish.out; // 11 x 11 level-0 tiles
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir / "one")) {
    if (entry.is_regular_file() && entry.path().extension() != ".json") {
      const auto relative = std::filesystem::relative(entry.path(), dir / "one");
      EXPECT_EQ(readAll(entry.path()), readAll(dir / "four" / relative)) << relative;
    }
  }
}

TEST(CliPyramid, BadInputsGiveOneLineErrors) {
  TempDir dir;
  writeBigGeoTiff(dir / "dem.tif", 100);
  writeTextFile(dir / "file", "x");
  const auto expectError = [&](const std::string& args, const std::string& text) {
    const RunResult r = runSylva(dir, args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.err.find(text), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  };
  expectError("terrain pyramid " + at(dir, "missing.tif") + " -o " + at(dir, "p"),
              "missing.tif: file not found");
  expectError("terrain pyramid " + at(dir, "dem.tif") + " -o " + at(dir, "file"),
              "exists and is not a folder");
  expectError("terrain pyramid " + at(dir, "dem.tif") + " -o " + at(dir, "p") + " --shard 4/4", "--shard");
  expectError("terrain pyramid " + at(dir, "dem.tif") + " -o " + at(dir, "p") + " --tile-size 8",
              "--tile-size");
  const RunResult ok =
      runSylva(dir, "terrain pyramid " + at(dir, "dem.tif") + " -o " + at(dir, "p") + " --tile-size 32");
  ASSERT_EQ(ok.status, 0) << ok.err;
  expectError("terrain pyramid " + at(dir, "dem.tif") + " -o " + at(dir, "p") + " --tile-size 64",
              "holds a pyramid of 100x100 samples at 30 x 30 m in tiles of 32");
}

} // namespace
} // namespace sylva::test

// `sylva render` on real-world shaped terrains: framing from the real extent, camera options, exaggeration,
// sea level and water, limits checked before work, and the one-line errors of bad camera options. They
// render, so they need a GL context (label gl). Also `sylva view --grass` in its scripted mode (needs a
// display).
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Image.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/HeightSources.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace sylva {
namespace {

using test::runSylva;

namespace fs = std::filesystem;
using test::quote;

/** Fraction of pixels that are not the sky (the clear colour, linear (0.62, 0.72, 0.85) stored as 8 bits). */
double terrainFraction(const Image& image) {
  std::size_t terrain = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const float d = std::abs(image.get(x, y, 0) - 0.62f) + std::abs(image.get(x, y, 1) - 0.72f) +
                      std::abs(image.get(x, y, 2) - 0.85f);
      terrain += d > 0.03f ? 1 : 0;
    }
  }
  return static_cast<double>(terrain) / (static_cast<double>(image.width()) * image.height());
}

/** Fraction of the image's rows that hold terrain, from the first to the last. */
double rowSpan(const Image& image) {
  int first = image.height();
  int last = -1;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const float d = std::abs(image.get(x, y, 0) - 0.62f) + std::abs(image.get(x, y, 1) - 0.72f) +
                      std::abs(image.get(x, y, 2) - 0.85f);
      if (d > 0.03f) {
        first = std::min(first, y);
        last = std::max(last, y);
      }
    }
  }
  return last < first ? 0.0 : static_cast<double>(last - first + 1) / image.height();
}

/** Pixels whose blue clearly dominates red and green: water (terrain layers are never this blue). */
std::size_t waterPixels(const Image& image) {
  std::size_t count = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const float r = image.get(x, y, 0);
      const float g = image.get(x, y, 1);
      const float b = image.get(x, y, 2);
      const bool sky = std::abs(r - 0.62f) + std::abs(g - 0.72f) + std::abs(b - 0.85f) < 0.03f;
      // Dark and blue: not sky, not snow (bright), not grass or sand (red/green dominate).
      count += !sky && b > r + 0.12f && b > g + 0.05f && r + g + b < 1.6f ? 1 : 0;
    }
  }
  return count;
}

/** A w×h DEM saved as .npy: a Gaussian hill of `relief` metres on a slope from −base (west) to +base (east).
 */
fs::path writeDem(const test::TempDir& dir, const std::string& name, int w, int h, float relief, float base) {
  terrain::HeightField field(w, h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const float u = static_cast<float>(i) / static_cast<float>(w - 1) - 0.6f;
      const float v = static_cast<float>(j) / static_cast<float>(h - 1) - 0.5f;
      field.at(i, j) = relief * std::exp(-8.0f * (u * u + v * v)) +
                       base * (2.0f * static_cast<float>(i) / static_cast<float>(w - 1) - 1.0f);
    }
  }
  const fs::path path = dir / name;
  terrain::saveHeightField(path, field);
  return path;
}

bool same(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() != b.channels()) {
    return false;
  }
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      for (int c = 0; c < a.channels(); ++c) {
        if (a.get(x, y, c) != b.get(x, y, c)) {
          return false;
        }
      }
    }
  }
  return true;
}

Image render(const test::TempDir& dir, const std::string& args, const std::string& name) {
  const fs::path out = dir / name;
  const test::RunResult r =
      runSylva(dir, "render " + args + " --width 160 --height 90 -o " + quote(out.string()));
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  if (const char* dump = std::getenv("SYLVA_DUMP"); dump != nullptr && r.status == 0) {
    fs::copy_file(out, fs::path(dump) / name, fs::copy_options::overwrite_existing); // to look at failures
  }
  return r.status == 0 ? loadImage(out) : Image(1, 1, 3, PixelType::F32);
}

TEST(CliRender, FramingShowsTheWholeTerrainWhateverItsShape) {
  const test::TempDir dir;
  // Relief far larger than the extent (a mis-read or tiny DEM), and a continent (extent far beyond relief).
  const fs::path tall = writeDem(dir, "tall.npy", 40, 30, 3000.0f, 0.0f);
  const fs::path wide = writeDem(dir, "wide.npy", 200, 100, 2000.0f, 0.0f);
  for (const std::string view : {"south-west", "north"}) {
    // Relief 8 times the extent: the mountain must reach from near the bottom of the image to near the top.
    EXPECT_GT(
        rowSpan(render(dir, "--dem " + quote(tall.string()) + " --spacing 10 --view-from " + view, "t.png")),
        0.8)
        << view;
  }
  for (const std::string view : {"south-west", "north", "top"}) {
    EXPECT_GT(terrainFraction(render(
                  dir, "--dem " + quote(wide.string()) + " --spacing 50000 --view-from " + view, "w.png")),
              0.15)
        << view;
  }
}

TEST(CliRender, CameraOptionsMoveTheView) {
  const test::TempDir dir;
  const std::string source = "--seed 5 --size 129 --spacing 8";
  const Image framed = render(dir, source, "a.png");
  const Image again = render(dir, source, "b.png");
  EXPECT_TRUE(same(framed, again)) << "same options, same image";
  const auto differs = [&](const std::string& extra) {
    const Image other = render(dir, source + " " + extra, "c.png");
    return !same(framed, other);
  };
  EXPECT_TRUE(differs("--view-from north"));
  EXPECT_TRUE(differs("--fov 25"));
  EXPECT_TRUE(differs("--camera-pos 0,600,1024 --look-at 512,0,512"));
  EXPECT_TRUE(differs("--exaggeration 3"));
  EXPECT_TRUE(differs("--fog 0"));
  // A close look from the ground still sees terrain (clip planes follow the camera).
  EXPECT_GT(terrainFraction(render(dir, source + " --camera-pos 500,420,500 --look-at 700,300,700", "g.png")),
            0.3);
}

TEST(CliRender, SeaLevelDrawsWaterOnlyWhenThereIsSea) {
  const test::TempDir dir;
  // A coast: the west dips to -200 m, the hill rises to 300 m.
  const fs::path coast = writeDem(dir, "coast.npy", 120, 90, 300.0f, 200.0f);
  const std::string source = "--dem " + quote(coast.string()) + " --spacing 20 --view-from top --fog 0";
  EXPECT_GT(waterPixels(render(dir, source, "auto.png")), 300u) << "auto: heights below 0 m get a sea";
  EXPECT_EQ(waterPixels(render(dir, source + " --sea-level none", "none.png")), 0u);
  const std::size_t low = waterPixels(render(dir, source + " --sea-level -30", "low.png"));
  const std::size_t high = waterPixels(render(dir, source + " --sea-level 40", "high.png"));
  EXPECT_GT(high, low) << "a higher sea covers more";
  // Inland terrain (all heights above 0 m) has no sea unless asked for.
  const fs::path hill = writeDem(dir, "hill.npy", 60, 60, 300.0f, 0.0f);
  EXPECT_EQ(waterPixels(render(dir, "--dem " + quote(hill.string()) + " --spacing 20 --view-from top --fog 0",
                               "h.png")),
            0u);
}

TEST(CliRender, BadCameraOptionsAndLimitsFailBeforeWork) {
  const test::TempDir dir;
  const fs::path out = dir / "never.png";
  for (const std::string& args :
       {std::string("--camera-pos 1,2"), std::string("--look-at a,b,c"), std::string("--view-from up"),
        std::string("--fov 0"), std::string("--fog 2"), std::string("--sea-level deep"),
        std::string("--exaggeration 0"), std::string("--camera-pos 1,2,3 --look-at 1,2,3"),
        std::string("--size 32768"), std::string("--seed 18446744073709551616")}) {
    const test::RunResult r =
        runSylva(dir, "render --seed 1 --size 65 " + args + " -o " + quote(out.string()));
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  // A directory as the output or as the DEM is named as such.
  fs::create_directories(dir / "folder.png");
  test::RunResult r = runSylva(dir, "render --seed 1 --size 65 -o " + quote((dir / "folder.png").string()));
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
  r = runSylva(dir, "render --dem " + quote(dir.path().string()) + " -o " + quote(out.string()));
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
}

using test::displayRequired;
using test::haveDisplay;

// `sylva view --grass` in its scripted mode: the viewer builds the field, starts at the ground-level grass
// camera and draws blades (with the grass panel open) until the screenshot. Needs a window: skipped without a
// display unless SYLVA_REQUIRE_DISPLAY=1 (CI runs it under xvfb-run).
TEST(CliView, GrassScreenshotShowsBlades) {
  if (!haveDisplay()) {
    if (displayRequired()) {
      FAIL() << "no display and SYLVA_REQUIRE_DISPLAY=1 (run under xvfb-run)";
    }
    GTEST_SKIP() << "no display (set DISPLAY or run under xvfb-run); view --grass test skipped";
  }
  const test::TempDir dir;
  const fs::path shot = dir / "grass.png";
  const test::RunResult r = runSylva(
      dir, "view --grass --size 129 --spacing 4 --width 640 --height 360 --frames 3 --fixed-step 0.1 "
           "--screenshot " +
               quote(shot.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(shot.string()), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(shot));
  const Image image = loadImage(shot);
  ASSERT_GE(image.width(), 640);
  ASSERT_GE(image.height(), 360);
  if (const char* dump = std::getenv("SYLVA_DUMP"); dump != nullptr) {
    fs::copy_file(shot, fs::path(dump) / "view-grass.png", fs::copy_options::overwrite_existing);
  }
  // The lower half of the right quarter (the panel covers the left ~450 px): the eye is 1.7 m above dense
  // grass, so blades (green clearly above red and blue) fill most of it.
  std::size_t green = 0;
  std::size_t total = 0;
  for (int y = image.height() / 2; y < image.height(); ++y) {
    for (int x = image.width() * 3 / 4; x < image.width(); ++x) {
      const float red = image.get(x, y, 0);
      const float g = image.get(x, y, 1);
      const float blue = image.get(x, y, 2);
      green += g > red + 0.05f && g > blue + 0.05f ? 1 : 0;
      ++total;
    }
  }
  EXPECT_GT(static_cast<double>(green) / static_cast<double>(total), 0.6) << green << " of " << total;
}

/**
 * Pixels of the balls' red checker squares (linear (0.75, 0.12, 0.08), strongly red in the sRGB screenshot):
 * nothing else in the viewer (terrain, grass, sky, the ImGui panel) is this red.
 */
std::size_t ballPixels(const Image& image) {
  std::size_t count = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      count += image.get(x, y, 0) > 0.5f && image.get(x, y, 1) < 0.3f && image.get(x, y, 2) < 0.3f ? 1 : 0;
    }
  }
  return count;
}

// `sylva view --grass --physics balls` in its scripted mode: the viewer drops the balls as `sylva render`
// does, starts at the camera watching them, steps the simulation with the fixed step and draws them; without
// --physics no ball is drawn (the check can fail). --no-ui: at 640 px the panel covers the balls (they roll
// past left of the centre) and its translucency greys them. Needs a display, like the test above.
TEST(CliView, PhysicsBallsShowInTheViewer) {
  if (!haveDisplay()) {
    if (displayRequired()) {
      FAIL() << "no display and SYLVA_REQUIRE_DISPLAY=1 (run under xvfb-run)";
    }
    GTEST_SKIP() << "no display (set DISPLAY or run under xvfb-run); view --physics test skipped";
  }
  const test::TempDir dir;
  const auto shoot = [&](const std::string& extra, int frames, const std::string& name) {
    const fs::path shot = dir / name;
    const test::RunResult r = runSylva(
        dir, "view --grass --no-ui " + extra + " --size 129 --spacing 4 --width 640 --height 360 --frames " +
                 std::to_string(frames) + " --fixed-step 0.05 --screenshot " + quote(shot.string()));
    EXPECT_EQ(r.status, 0) << extra << "\n" << r.err;
    if (r.status != 0 || !fs::exists(shot)) {
      ADD_FAILURE() << extra << ": no screenshot";
      return Image(1, 1, 3, PixelType::F32);
    }
    if (const char* dump = std::getenv("SYLVA_DUMP"); dump != nullptr) {
      fs::copy_file(shot, fs::path(dump) / ("view-" + name), fs::copy_options::overwrite_existing);
    }
    return loadImage(shot);
  };
  // 40 steps let the balls roll into the camera's view; the control needs no steps (without --physics there
  // is nothing to step) and its grass camera's frames cost about 1 s each on llvmpipe.
  const std::size_t balls = ballPixels(shoot("--physics balls --balls 4", 40, "balls.png"));
  EXPECT_GT(balls, 30u) << "the balls' red checker squares";
  const std::size_t none = ballPixels(shoot("", 2, "none.png"));
  EXPECT_EQ(none, 0u) << "no balls without --physics";
}

} // namespace
} // namespace sylva

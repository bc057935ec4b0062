// `sylva render --trees` and `sylva view --trees`: the forest on a small procedural terrain, swaying in the
// wind of --wind-*; the same --time gives the same file, trees are drawn (bark pixels, and the image differs
// from one without them), --frames steps the wind, bad species fail with one line and no output. They render,
// so they need a GL context (label gl); the viewer test also needs a display (skipped without one unless
// SYLVA_REQUIRE_DISPLAY=1; CI runs it under xvfb-run).
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Image.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace sylva {
namespace {

namespace fs = std::filesystem;
using test::quote;
using test::runSylva;

/** A small terrain (129 samples, 4 m apart) and a small image: a few seconds on llvmpipe. */
const std::string kScene = "--size 129 --spacing 4 --width 320 --height 180 ";

/**
 * Bark pixels in columns [x0, width): red clearly above blue, at least green, and not bright (brown). Where
 * the forest camera looks the small terrain is grass (green above red) below its snow (white; the forest
 * stops at the snow line), the sky is blue and the ImGui panel grey-blue, so nothing else is this colour.
 */
std::size_t barkPixels(const Image& image, int x0 = 0) {
  std::size_t count = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = x0; x < image.width(); ++x) {
      const float r = image.get(x, y, 0);
      const float g = image.get(x, y, 1);
      const float b = image.get(x, y, 2);
      count += r > b + 0.05f && r >= g && r + g + b < 2.35f ? 1 : 0;
    }
  }
  return count;
}

/** Pixels whose channels differ by more than 2/255 between two images of the same size. */
std::size_t differentPixels(const Image& a, const Image& b) {
  std::size_t count = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      bool differs = false;
      for (int c = 0; c < 3; ++c) {
        differs = differs || std::abs(a.get(x, y, c) - b.get(x, y, c)) > 2.5f / 255.0f;
      }
      count += differs ? 1 : 0;
    }
  }
  return count;
}

/** Runs `sylva render <args> -o dir/name`, expecting success and the path on stdout; returns the path. */
fs::path render(const test::TempDir& dir, const std::string& args, const std::string& name) {
  const fs::path out = dir / name;
  const test::RunResult r = runSylva(dir, "render " + kScene + args + " -o " + quote(out.string()));
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  EXPECT_NE(r.out.find(out.string()), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out)) << args;
  if (const char* dump = std::getenv("SYLVA_DUMP"); dump != nullptr && fs::exists(out)) {
    fs::copy_file(out, fs::path(dump) / ("trees-" + name), fs::copy_options::overwrite_existing);
  }
  return out;
}

// The springs start from rest a fixed warm-up before --time and step at 60 Hz: the same --time gives the same
// bytes; another --time moves the trees (a strong wind so the bend shows at 320 × 180); without wind the
// trees stand still at any time.
TEST(CliTreesRender, SameTimeGivesTheSameImage) {
  const test::TempDir dir;
  const std::string wind = "--trees --wind-speed 10 --wind-gusts 1 ";
  const fs::path a = render(dir, wind + "--time 2.5", "a.png");
  const fs::path b = render(dir, wind + "--time 2.5", "b.png");
  ASSERT_FALSE(test::readAll(a).empty());
  EXPECT_EQ(test::readAll(a), test::readAll(b)) << "same --time, different files";
  const fs::path later = render(dir, wind + "--time 4", "later.png");
  const std::size_t moved = differentPixels(loadImage(a), loadImage(later));
  std::printf("pixels moved by the wind from 2.5 s to 4 s: %zu\n", moved);
  EXPECT_GT(moved, 10u) << "the wind moved nothing in 1.5 s";
  const fs::path still1 = render(dir, "--trees --no-trees-wind --wind-speed 10 --time 2.5", "still1.png");
  const fs::path still2 = render(dir, "--trees --trees-wind=false --wind-speed 10 --time 4", "still2.png");
  EXPECT_EQ(test::readAll(still1), test::readAll(still2)) << "rest pose: no time dependence";
  EXPECT_GT(differentPixels(loadImage(a), loadImage(still1)), 10u) << "the wind bent nothing";
}

// Far trees sway too (issue 30): with every tree an impostor (far field from 1 m; one species, one bake), the
// wind moves the image between two times; without wind the impostors stand still.
TEST(CliTreesRender, ImpostorsSwayInTheWind) {
  const test::TempDir dir;
  const std::string far = "--trees --trees-species almond --trees-far 1 --trees-far-band 1 --wind-speed 10 ";
  const Image a = loadImage(render(dir, far + "--time 2.5", "far-a.png"));
  const Image b = loadImage(render(dir, far + "--time 4", "far-b.png"));
  const std::size_t moved = differentPixels(a, b);
  std::printf("impostor pixels moved by the wind from 2.5 s to 4 s: %zu\n", moved);
  EXPECT_GT(moved, 10u) << "the far trees stood still in a 10 m/s wind";
  const Image still1 = loadImage(render(dir, far + "--no-trees-wind --time 2.5", "far-still1.png"));
  const Image still2 = loadImage(render(dir, far + "--no-trees-wind --time 4", "far-still2.png"));
  EXPECT_EQ(differentPixels(still1, still2), 0u) << "no wind: no time dependence";
}

// The forest camera looks at a tree near the terrain's centre: bark pixels fill part of the image, and the
// image differs from the same render without --trees and from the same camera with no piece in range.
TEST(CliTreesRender, TreesAreVisible) {
  const test::TempDir dir;
  const Image trees = loadImage(render(dir, "--trees --time 1", "trees.png"));
  const Image none = loadImage(render(dir, "--time 1", "none.png"));
  const Image empty = loadImage(render(dir, "--trees --trees-distance 0.001 --time 1", "empty.png"));
  const std::size_t total =
      static_cast<std::size_t>(trees.width()) * static_cast<std::size_t>(trees.height());
  std::printf("bark pixels %zu of %zu; differing from no --trees %zu, from no tree drawn %zu\n",
              barkPixels(trees), total, differentPixels(trees, none), differentPixels(trees, empty));
  EXPECT_GT(barkPixels(trees), total / 400) << "bark: the tree the forest camera looks at";
  EXPECT_EQ(barkPixels(empty), 0u) << "nothing else is bark-coloured";
  EXPECT_GT(differentPixels(trees, none), total / 100) << "the same render without --trees";
  EXPECT_GT(differentPixels(trees, empty), total / 400) << "the same camera with no tree drawn";
}

// The bark tile-id debug view is a picture like the others: opaque (it once wrote the trees at alpha 1/255,
// invisible in an image viewer), with the ids in colour where the trees are.
TEST(CliTreesRender, SpeciesSheetDrawsEachSpeciesAtOneScale) {
  // `sylva tree sheet`: an apple tree and a poplar side by side, at one scale: two person markers (dark
  // columns reaching 1.75 m) stand on the ground strip, sky above both crowns, and the poplar (18 m) stands
  // far taller than the apple tree (4–5 m, leaves included). Bad input: one line, no file.
  const test::TempDir dir;
  const fs::path out = dir.path() / "sheet.png";
  const test::RunResult run =
      runSylva(dir, "tree sheet --species apple,lombardy-poplar --height 240 -o " + quote(out.string()));
  ASSERT_EQ(run.status, 0) << run.err;
  const Image image = loadImage(out);
  EXPECT_EQ(image.height(), 240);
  EXPECT_GT(image.width(), image.height() / 2);
  // The sky is kept in its clear colour: the first row, and the ground strip the last.
  const float skyBlue = image.get(0, 0, 2);
  EXPECT_GT(skyBlue, image.get(0, 0, 0));
  // Markers: columns whose pixels are near-black from the ground up.
  int markerColumns = 0;
  // The ground strip: brown (red above blue) up from the last row, at the left edge (sky above it).
  int groundRow = image.height() - 1;
  while (groundRow > 0 && image.get(0, groundRow - 1, 2) < image.get(0, groundRow - 1, 0)) {
    --groundRow;
  }
  EXPECT_LT(groundRow, image.height() - 2);
  EXPECT_GT(groundRow, image.height() * 3 / 4);
  for (int x = 0; x < image.width(); ++x) {
    const int y = groundRow - 2;
    markerColumns +=
        image.get(x, y, 0) < 0.2f && image.get(x, y, 1) < 0.2f && image.get(x, y, 2) < 0.2f ? 1 : 0;
  }
  EXPECT_GE(markerColumns, 2) << "two 0.45 m wide markers";
  // Each tree's highest non-sky pixel: the poplar (right half) reaches higher than the birch (left half).
  auto top = [&](int x0, int x1) {
    for (int y = 0; y < image.height(); ++y) {
      for (int x = x0; x < x1; ++x) {
        if (std::abs(image.get(x, y, 2) - skyBlue) > 0.05f) {
          return y;
        }
      }
    }
    return image.height();
  };
  const int poplarTop = top(image.width() / 2, image.width());
  const int appleTop = top(0, image.width() / 2);
  EXPECT_GT(poplarTop, 0) << "sky above the tallest crown";
  EXPECT_LT(poplarTop, groundRow - 5 * (groundRow - appleTop) / 2)
      << "the poplar: over 2.5x the apple's height";
  const fs::path bad = dir.path() / "bad.png";
  const test::RunResult unknown = runSylva(dir, "tree sheet --species bonsai -o " + quote(bad.string()));
  EXPECT_NE(unknown.status, 0);
  EXPECT_NE(unknown.err.find("unknown species 'bonsai'"), std::string::npos) << unknown.err;
  EXPECT_FALSE(fs::exists(bad));
  const test::RunResult jpeg = runSylva(dir, "tree sheet -o " + quote((dir.path() / "x.jpg").string()));
  EXPECT_NE(jpeg.status, 0);
  EXPECT_NE(jpeg.err.find("a species sheet is a .png file"), std::string::npos) << jpeg.err;
}

TEST(CliTreesRender, TheTileIdViewIsOpaque) {
  const test::TempDir dir;
  const Image tiles = loadImage(render(dir, "--trees --trees-view tiles --time 1", "tiles.png"));
  const Image shaded = loadImage(render(dir, "--trees --time 1", "shaded.png"));
  ASSERT_EQ(tiles.channels(), 4);
  std::size_t translucent = 0;
  for (int y = 0; y < tiles.height(); ++y) {
    for (int x = 0; x < tiles.width(); ++x) {
      translucent += tiles.get(x, y, 3) < 1.0f ? 1 : 0;
    }
  }
  EXPECT_EQ(translucent, 0u);
  const std::size_t total =
      static_cast<std::size_t>(tiles.width()) * static_cast<std::size_t>(tiles.height());
  EXPECT_GT(differentPixels(tiles, shaded), total / 400) << "the trees show their ids";
}

// --frames steps the wind between frames (at 30 frames/s, two 60 Hz steps each) and writes the last frame,
// and --gif all of them.
TEST(CliTreesRender, SeveralFramesRun) {
  const test::TempDir dir;
  const fs::path gif = dir / "trees.gif";
  const fs::path last = render(dir, "--trees --time 1 --frames 3 --gif " + quote(gif.string()), "last.png");
  EXPECT_GT(barkPixels(loadImage(last)), 0u);
  EXPECT_TRUE(fs::exists(gif));
  EXPECT_GT(fs::file_size(gif), 100u);
}

// Bad input: one line naming the option, a non-zero exit, no output file; checked before any GL work.
TEST(CliTreesRender, BadInputFailsWithOneLineAndNoOutput) {
  const test::TempDir dir;
  const fs::path out = dir / "bad.png";
  struct Case {
    std::string args;
    std::string names;
  };
  for (const Case& c :
       {Case{"--trees --trees-species nosuch", "--trees-species"},
        Case{"--trees --trees-species almond,nosuch", "--trees-species"},
        Case{"--trees --trees-wind=maybe", "--trees-wind"},
        Case{"--trees --trees-view nosuch", "--trees-view"}, Case{"--trees --wind-speed -1", "--wind-speed"},
        Case{"--trees --trees-bark-photos /nonexistent", "--trees-bark-photos"}}) {
    const test::RunResult r = runSylva(dir, "render " + kScene + c.args + " -o " + quote(out.string()));
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_EQ(test::lineCount(r.err), 1u) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  // The viewer checks the same options before it opens a window (so this needs no display).
  const test::RunResult r = runSylva(dir, "view --frames 1 --trees --trees-species nosuch");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(test::lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("--trees-species"), std::string::npos) << r.err;
  const test::RunResult demo = runSylva(dir, "view --frames 1 --trees --scene demo");
  EXPECT_EQ(demo.status, 2) << demo.err;
  EXPECT_EQ(test::lineCount(demo.err), 1u) << demo.err;
}

// Data the program brings (the fetched bark photos, the oak leaf) is found in the data folder, not the
// working directory: the same render from the repository and from elsewhere gives the same bytes (it once
// differed in 23,508 pixels: photo bark in one, procedural in the other). Bad output paths fail before work.
TEST(CliTreesRender, TheWorkingDirectoryChangesNothing) {
  const test::TempDir dir;
  const std::string args = "render " + kScene + "--trees --time 1 -o ";
  const fs::path fromRepo = dir / "repo.png";
  const fs::path fromElsewhere = dir / "elsewhere.png";
  const test::RunResult a = test::runSylvaFrom(SYLVA_SOURCE_DIR, dir, args + quote(fromRepo.string()));
  ASSERT_EQ(a.status, 0) << a.err;
  const test::RunResult b = test::runSylvaFrom(dir.path(), dir, args + quote(fromElsewhere.string()));
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_EQ(test::readAll(fromRepo), test::readAll(fromElsewhere));
  // -o a directory, or under a file: refused at once with one line, nothing written.
  for (const std::string& out : {dir.path().string(), (fromRepo / "x.png").string()}) {
    const test::RunResult r = runSylva(dir, "render " + kScene + "--trees -o " + quote(out));
    EXPECT_EQ(r.status, 2) << out;
    EXPECT_EQ(test::lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("--out " + out), std::string::npos) << r.err;
  }
}

using test::displayRequired;
using test::haveDisplay;

// `sylva view --trees` in its scripted mode: the viewer builds the forest, starts at the forest camera,
// steps the wind with the fixed step and draws the trees (with the Trees panel open, reading the visible
// counts) until the screenshot. Needs a window: skipped without a display unless SYLVA_REQUIRE_DISPLAY=1.
TEST(CliView, TreesScreenshotShowsTrees) {
  if (!haveDisplay()) {
    if (displayRequired()) {
      FAIL() << "no display and SYLVA_REQUIRE_DISPLAY=1 (run under xvfb-run)";
    }
    GTEST_SKIP() << "no display (set DISPLAY or run under xvfb-run); view --trees test skipped";
  }
  const test::TempDir dir;
  const fs::path shot = dir / "trees.png";
  const test::RunResult r = runSylva(
      dir, "view --trees --size 129 --spacing 4 --width 1280 --height 720 --frames 3 --fixed-step 0.1 "
           "--screenshot " +
               quote(shot.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(shot.string()), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(shot));
  const Image image = loadImage(shot);
  ASSERT_GE(image.width(), 1280);
  ASSERT_GE(image.height(), 720);
  if (const char* dump = std::getenv("SYLVA_DUMP"); dump != nullptr) {
    fs::copy_file(shot, fs::path(dump) / "view-trees.png", fs::copy_options::overwrite_existing);
  }
  // Right of the panel (it covers the left ~450 px): the tree the camera looks at stands in the middle.
  const std::size_t bark = barkPixels(image, image.width() * 2 / 5);
  std::printf("bark pixels right of the panel: %zu\n", bark);
  EXPECT_GT(bark, 400u) << "bark pixels of the tree in the middle";
}

} // namespace
} // namespace sylva

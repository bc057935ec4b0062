// `sylva texsynth` as a user runs it: quilt a photo into a PNG, build the bark tile set and a Wang set with a
// preview, same seed same bytes, and bad inputs that fail with one line naming the file or option and leave
// no output behind.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/texsynth/Procedural.hpp>
#include <sylva/texsynth/TileSet.hpp>
#include <sylva/texsynth/TileSetIo.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace sylva {
namespace {

namespace fs = std::filesystem;
using test::at;
using test::lineCount;
using test::runSylva;
using testing::HasSubstr;

/** A procedural bark photo pair written as PNGs (colour and OpenGL-style normal map). */
void writePhoto(const test::TempDir& dir, int size) {
  const texsynth::Texture bark = texsynth::proceduralBark(size, 5);
  saveImage(dir / "bark.png", texsynth::colourImage(bark));
  saveImage(dir / "bark-normal.png", texsynth::normalImage(bark, texsynth::NormalGreen::Up));
}

TEST(TexsynthCli, QuiltWritesAPngOfTheRequestedSize) {
  const test::TempDir dir;
  writePhoto(dir, 128);
  const std::string args = "texsynth quilt --in " + at(dir, "bark.png") + " --normal " +
                           at(dir, "bark-normal.png") + " --size 200x150 --block 32 --seed 4 --normal-out " +
                           at(dir, "n.png") + " --out ";
  const test::RunResult r = runSylva(dir, args + at(dir, "q.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("200x150"));
  const Image image = loadImage(dir / "q.png");
  EXPECT_EQ(image.width(), 200);
  EXPECT_EQ(image.height(), 150);
  EXPECT_EQ(loadImage(dir / "n.png").width(), 200);
  ASSERT_EQ(runSylva(dir, args + at(dir, "q2.png")).status, 0);
  EXPECT_EQ(test::readAll(dir / "q.png"), test::readAll(dir / "q2.png")) << "same seed, same bytes";
}

TEST(TexsynthCli, TilesBuildsTheBarkSet) {
  const test::TempDir dir;
  writePhoto(dir, 160);
  const test::RunResult r =
      runSylva(dir, "texsynth tiles --in " + at(dir, "bark.png") + " --normal " + at(dir, "bark-normal.png") +
                        " --out " + at(dir, "set") + " --tile 32 --variants 3 --seed 2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("9 tiles"));
  const texsynth::TileSet set = texsynth::loadTileSet(dir / "set");
  ASSERT_EQ(set.classes.size(), 3u);
  EXPECT_EQ(set.tiles.size(), 9u);
  EXPECT_EQ(set.channels, 6);
  EXPECT_TRUE(set.colours.at(0).symmetric);
  const std::vector<float> line = texsynth::edgeLine(set.tiles[0], texsynth::kEdgeBottom);
  for (const texsynth::Texture& tile : set.tiles) {
    for (int edge = 0; edge < 4; ++edge) {
      const std::vector<float> other = texsynth::edgeLine(tile, edge);
      for (std::size_t i = 0; i < line.size(); i += 6) {
        ASSERT_EQ(line[i], other[i]) << "edge " << edge;
      }
    }
  }
}

TEST(TexsynthCli, WangBuildsACompleteSetAndAPreview) {
  const test::TempDir dir;
  const test::RunResult r = runSylva(dir, "texsynth wang --in procedural --out " + at(dir, "wang") +
                                              " --colours 2 --tile 32 --preview 5x4 --seed 8");
  ASSERT_EQ(r.status, 0) << r.err;
  const texsynth::TileSet set = texsynth::loadTileSet(dir / "wang");
  EXPECT_EQ(set.classes.size(), 16u);
  const Image preview = loadImage(dir / "wang" / "preview.png");
  EXPECT_EQ(preview.width(), 5 * 32);
  EXPECT_EQ(preview.height(), 4 * 32);
}

TEST(TexsynthCli, PhotoTooSmallFailsAndLeavesNothing) {
  const test::TempDir dir;
  writePhoto(dir, 64);
  const test::RunResult r = runSylva(dir, "texsynth tiles --in " + at(dir, "bark.png") + " --out " +
                                              at(dir, "set") + " --tile 128");
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_THAT(r.err, HasSubstr("bark.png"));
  EXPECT_THAT(r.err, HasSubstr("smaller than the 128x128 tile"));
  EXPECT_FALSE(fs::exists(dir / "set"));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir.path())) {
    ++entries;
  }
  EXPECT_EQ(entries, 2u) << "only the photos";
}

TEST(TexsynthCli, BadOptionsAndFilesAreOneLineErrors) {
  const test::TempDir dir;
  writePhoto(dir, 64);
  writeTextFile(dir / "broken.jpg", "not a jpeg");
  const auto expectError = [&](const std::string& args, const std::string& message) {
    const test::RunResult r = runSylva(dir, args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_THAT(r.err, HasSubstr(message)) << args;
  };
  expectError("texsynth quilt --in " + at(dir, "broken.jpg") + " --out " + at(dir, "q.png"), "broken.jpg");
  expectError("texsynth quilt --in " + at(dir, "missing.png") + " --out " + at(dir, "q.png"), "missing.png");
  expectError("texsynth quilt --in " + at(dir, "bark.png") + " --out " + at(dir, "q.png") + " --size 10by10",
              "--size");
  expectError("texsynth quilt --in " + at(dir, "bark.png") + " --out " + at(dir, "q.png") + " --block 100",
              "bark.png: the image is 64x64, smaller than the 100x100 block");
  expectError("texsynth quilt --in " + at(dir, "bark.png") + " --out " + at(dir, "q.png") +
                  " --tolerance nan",
              "--tolerance");
  expectError("texsynth wang --in " + at(dir, "bark.png") + " --out " + at(dir, "w") + " --colours 4",
              "--colours");
  expectError("texsynth tiles --in " + at(dir, "bark.png") + " --out " + at(dir, "t") +
                  " --tile 32 --band 10 --overlap 8",
              "band");
  expectError("texsynth tiles --in " + at(dir, "bark.png") + " --normal " + at(dir, "broken.jpg") +
                  " --out " + at(dir, "t") + " --tile 32",
              "broken.jpg");
  EXPECT_FALSE(fs::exists(dir / "q.png"));
  EXPECT_FALSE(fs::exists(dir / "w"));
  EXPECT_FALSE(fs::exists(dir / "t"));
}

} // namespace
} // namespace sylva

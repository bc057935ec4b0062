// The shipped examples (data/folding/): their procedural inputs match the generators, and each project
// synthesises and animates as intended.
#include <sylva/core/Image.hpp>
#include <sylva/folding/Examples.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Synthesis.hpp>

#include "ExternalData.hpp"
#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

namespace sylva::folding {
namespace {

namespace fs = std::filesystem;

/** SYLVA_UPDATE_EXAMPLES=1 rewrites the committed example images from their generators. */
bool updating() {
  const char* env = std::getenv("SYLVA_UPDATE_EXAMPLES");
  return env != nullptr && std::string(env) == "1";
}

void expectCommitted(const std::string& name, const Image& generated) {
  const fs::path path = test::sourcePath("data/folding/" + name);
  if (updating()) {
    saveImage(path, generated);
  }
  ASSERT_TRUE(fs::exists(path)) << path << " is missing (SYLVA_UPDATE_EXAMPLES=1 writes it)";
  EXPECT_EQ(loadImage(path), generated) << path << " no longer matches its generator";
}

TEST(FoldingExamples, CommittedImagesMatchTheirGenerators) {
  expectCommitted("beach.png", beachImage(480, 288, 7));
  expectCommitted("meadow.png", meadowImage(360, 200, 7));
  expectCommitted("bird.png", birdImage(48, 28));
}

struct Example {
  Project project;
  ProjectImages images;
  Textures textures;
};

Example load(const std::string& name) {
  Example e;
  const fs::path path = test::sourcePath("data/folding/" + name);
  e.project = loadProject(path);
  e.images = loadProjectImages(e.project, path.string());
  e.textures = synthesize(e.project, e.images);
  return e;
}

/** Pixels of the canvas (columns below `columns`) that differ from the input by more than 8/255. */
std::size_t changed(const Example& e, const Image& frame, int columns = 1 << 30) {
  const AtlasEntry& canvas = e.textures.atlas.entries[static_cast<std::size_t>(e.project.canvasIndex())];
  const Image a = cropToEntry(frame, canvas);
  const Image b = cropToEntry(e.textures.atlas.color, canvas);
  const auto* p = reinterpret_cast<const std::uint8_t*>(a.data());
  const auto* q = reinterpret_cast<const std::uint8_t*>(b.data());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.byteSize(); i += 4) {
    if (static_cast<int>((i / 4) % static_cast<std::size_t>(a.width())) >= columns) {
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      if (std::abs(int(p[i + c]) - int(q[i + c])) > 8) {
        ++n;
        break;
      }
    }
  }
  return n;
}

/** Shared properties: nothing outside the zones moves, the loop closes, the mid-cycle frame has moved. */
void checkAnimation(const Example& e, double midTime, std::size_t minChanged) {
  const Textures& tex = e.textures;
  const double period = e.project.profiles[0].periodS;
  const Image first = renderFrame(tex, e.project.profiles, e.project.jumpLayers, 0.0, 2);
  const Image seam = renderFrame(tex, e.project.profiles, e.project.jumpLayers, period, 2);
  const Image mid = renderFrame(tex, e.project.profiles, e.project.jumpLayers, midTime, 2);
  const auto* a = reinterpret_cast<const std::uint8_t*>(first.data());
  const auto* b = reinterpret_cast<const std::uint8_t*>(seam.data());
  int seamDiff = 0;
  for (std::size_t i = 0; i < first.byteSize(); ++i) {
    seamDiff = std::max(seamDiff, std::abs(int(a[i]) - int(b[i])));
  }
  EXPECT_LE(seamDiff, 1) << "frame(T) must equal frame(0)";
  const std::span<const float> init = tex.init.values<float>();
  const auto* m = reinterpret_cast<const std::uint8_t*>(mid.data());
  const auto* c = reinterpret_cast<const std::uint8_t*>(tex.atlas.color.data());
  for (std::size_t i = 0; i < init.size() / 4; ++i) {
    if (init[i * 4 + 3] < 0.0f) {
      ASSERT_EQ(std::memcmp(m + i * 4, c + i * 4, 4), 0) << "a still texel changed";
    }
  }
  EXPECT_GE(changed(e, mid), minChanged);
  if (const char* out = std::getenv("SYLVA_EXAMPLE_OUT")) {
    const fs::path dir(out);
    const std::string stem = e.project.images[0].id;
    saveImage(dir / (stem + "-mid.png"), mid);
    saveImage(dir / (stem + "-vectors.png"), vectorFieldPicture(tex, 12));
    saveImage(dir / (stem + "-t0.png"), thresholdHeatMap(tex, 0));
  }
}

TEST(FoldingExamples, BeachSwashCoversTheSandAndWithdraws) {
  const Example e = load("beach.json");
  checkAnimation(e, 1.6, 4000);
  // The swash covers the wet sand at its height and uncovers it at the end of the backwash. The wave front
  // runs along the shore (phase gradient), so compare the left 100 columns: φ ≈ 0.4..0.52 at t = 1.6 s
  // (p ≥ 0.87), φ ≈ 0.93..1.05 at t = 3.7 s (p ≤ 0.14).
  const Image high = renderFrame(e.textures, e.project.profiles, e.project.jumpLayers, 1.6, 2);
  const Image low = renderFrame(e.textures, e.project.profiles, e.project.jumpLayers, 3.7, 2);
  EXPECT_GT(changed(e, high, 100), 3 * changed(e, low, 100) + 100);
}

TEST(FoldingExamples, BirdFliesOverTheMeadow) {
  const Example e = load("flyover.json");
  checkAnimation(e, 2.5, 300);
  const AtlasEntry& bird = e.textures.atlas.entries[1];
  const AtlasEntry& meadow = e.textures.atlas.entries[0];
  EXPECT_EQ(bird.origin() - meadow.origin(), glm::ivec2(-52, 64));
  // At s = 0.5 the bird's top-left is at from + (to − from)/2 = (156, 44): its eye region is dark/white
  // there.
  const Image frame =
      cropToEntry(renderFrame(e.textures, e.project.profiles, e.project.jumpLayers, 2.5), meadow);
  const Image birdImg = e.images.images[1];
  int same = 0;
  int opaque = 0;
  for (int y = 0; y < birdImg.height(); ++y) {
    for (int x = 0; x < birdImg.width(); ++x) {
      if (birdImg.get(x, y, 3) < 1.0f) {
        continue;
      }
      ++opaque;
      same += std::abs(frame.get(156 + x, 44 + y, 0) - birdImg.get(x, y, 0)) < 0.02f;
    }
  }
  EXPECT_GT(same, opaque * 9 / 10) << "the bird must be drawn whole where it is at mid-flight";
}

TEST(FoldingExamples, SquintingCat) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("chelsea.png"));
  const Example e = load("cat.json");
  checkAnimation(e, 1.6, 800);
}

} // namespace
} // namespace sylva::folding

// Crack-freedom, proven by rendering. For each crack method and base tessellation level 1..32, the Jacksboro
// DEM (real relief, 403x344 samples, ~75x93 m spacing) is drawn from 200 seeded camera poses (SYLVA_FULL=1;
// CI draws the first 50 of them, 3,200 frames over both methods and 32 levels). Each frame draws the surface,
// then skirts under every interior patch edge inside a GL_SAMPLES_PASSED query: surface ∪ skirts is the
// terrain's footprint, and a skirt sample passes the depth test only where the background would show through
// the surface. Zero samples in every frame = no crack pixel. With crack removal disabled the same check must
// find cracks, so it is known to work. The same holds with geomorphing on (TerrainCracksGeomorph) and with
// screen-space-error LOD (TerrainCracksErrorLod).
#include <sylva/core/Random.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/gpu/TerrainRenderer.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"
#include "TempDir.hpp"

#include <fmt/format.h>

#include <functional>
#include <memory>
#include <string>

namespace sylva::terrain {
namespace {

constexpr int kFullPoses = 200;
constexpr int kCiPoses = 50;
const int kPoses = test::fullMode() ? kFullPoses : kCiPoses;
constexpr int kWidth = 192;
constexpr int kHeight = 120;

/** Camera pose `index`: inside the terrain's footprint, above its highest point, looking down at random. */
render::Camera crackPose(const HeightField& field, float maxHeight, int index) {
  Rng rng(0x5EED0000ULL + static_cast<std::uint64_t>(index));
  const float span = std::max(field.extentX(), field.extentZ());
  render::Camera camera;
  camera.position = {rng.uniform(0.02f, 0.98f) * field.extentX(),
                     maxHeight + rng.uniform(20.0f, 0.12f * span),
                     rng.uniform(0.02f, 0.98f) * field.extentZ()};
  const float yaw = rng.uniform(0.0f, 6.2831853f);
  const float pitch = rng.uniform(-1.45f, -0.12f);
  camera.target = camera.position + glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                              std::cos(pitch) * std::cos(yaw));
  camera.nearPlane = 1.0f;
  camera.farPlane = 3.0f * span;
  return camera;
}

/** Loads the DEM once per process and renders crack checks for a method and level. */
class CrackRig {
public:
  explicit CrackRig(const shader::Library& library)
      : mField(loadHeightField(test::externalData("jacksboro_fault_dem.npz"))),
        mMax(heightFieldInfo(mField).maxHeight), mTarget(kWidth, kHeight),
        mRenderer(library, mField, defaultSplatLayers(heightFieldInfo(mField).minHeight, mMax)) {}

  /** Crack samples of pose `index` with `method` at base level `tess`. */
  /** With `lodError` > 0: screen-space-error LOD at that many pixels of this target's height. */
  std::int64_t cracks(CrackMethod method, int tess, int index, bool geomorph = false, float lodError = 0.0f) {
    const render::Camera camera = crackPose(mField, mMax, index);
    QuadtreeConfig config = QuadtreeConfig::forRootCount(16, mField.extentX(), mField.extentZ());
    config.maxDepth = 5;
    config.patchTessLevel = tess;
    config.method = method;
    config.lodErrorPixels = lodError;
    config.pixelsPerRadian = QuadtreeConfig::pixelsPerRadianFor(static_cast<float>(kHeight), camera.fovY);
    if (!mQuadtree || !mQuadtree->canSetConfig(config)) {
      mQuadtree = std::make_unique<Quadtree>(config, mField);
    } else {
      mQuadtree->setConfig(config);
    }
    const Frustum frustum = camera.frustum(mTarget.aspect());
    mQuadtree->select(camera.position, &frustum, mSelection);
    mTarget.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    TerrainDrawOptions options;
    options.skirts = true;
    options.geomorph = geomorph;
    mRenderer.draw(mSelection, camera, kWidth, kHeight, 0.0, nullptr, options);
    mLevelChanges = 0;
    for (const SelectedNode& n : mSelection.nodes) {
      mLevelChanges += std::popcount(n.edgeFlags);
    }
    return mRenderer.lastCrackSamples();
  }
  int lastLevelChanges() const { return mLevelChanges; }
  render::RenderTarget& target() { return mTarget; }

private:
  HeightField mField;
  float mMax;
  render::RenderTarget mTarget;
  TerrainRenderer mRenderer;
  std::unique_ptr<Quadtree> mQuadtree;
  QuadtreeSelection mSelection;
  int mLevelChanges = 0;
};

struct CrackCase {
  CrackMethod method;
  int tess;
};

/** Readable CTest names ("ours, level 7") instead of the struct's raw bytes. */
void PrintTo(const CrackCase& c, std::ostream* os) {
  *os << crackMethodName(c.method) << ", level " << c.tess;
}

class TerrainCracks : public test::GlTest, public ::testing::WithParamInterface<CrackCase> {};

/**
 * Draws `poses` crack checks with `c`'s method and level (geomorph and screen-space-error LOD as
 * `geomorph(pose)` and `lodError` say) and fails at the first frame with a crack pixel, saving it as
 * golden-out/<prefix>_….png; the poses must exercise stitching (more doubled edges than poses).
 */
void expectNoCracks(const shader::Library& library, const CrackCase& c, int poses, const char* prefix,
                    const std::function<bool(int)>& geomorph, float lodError,
                    const std::function<void(const std::string&, const std::string&)>& record) {
  CrackRig rig(library);
  long long levelChanges = 0;
  for (int pose = 0; pose < poses; ++pose) {
    const bool morph = geomorph(pose);
    const std::int64_t cracks = rig.cracks(c.method, c.tess, pose, morph, lodError);
    levelChanges += rig.lastLevelChanges();
    if (cracks != 0) {
      saveImage(std::filesystem::path(SYLVA_BINARY_DIR) / "golden-out" /
                    fmt::format("{}_{}_t{}_pose{}.png", prefix, crackMethodName(c.method), c.tess, pose),
                rig.target().readColor());
    }
    EXPECT_EQ(cracks, 0) << "pose " << pose << (morph ? " (geomorph)" : "") << ": " << cracks
                         << " crack pixels (image in golden-out/)";
  }
  // The poses must actually exercise stitching, or zero cracks would prove nothing.
  EXPECT_GT(levelChanges, poses);
  record("doubled_edges", std::to_string(levelChanges));
}

std::string caseName(const ::testing::TestParamInfo<CrackCase>& info) {
  return fmt::format("{}_t{:02}", info.param.method == CrackMethod::PaperSearch ? "paper" : "ours",
                     info.param.tess);
}

TEST_P(TerrainCracks, NoBackgroundThroughTheSurfaceOnJacksboro) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  expectNoCracks(
      shaders(), GetParam(), kPoses, "crack", [](int) { return false; }, 0.0f,
      [](const std::string& k, const std::string& v) { ::testing::Test::RecordProperty(k, v); });
}

std::vector<CrackCase> allCases() {
  std::vector<CrackCase> cases;
  for (CrackMethod method : {CrackMethod::PaperSearch, CrackMethod::RestrictedLevelMap}) {
    for (int tess = 1; tess <= kMaxPatchTessLevel; ++tess) {
      cases.push_back({method, tess});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(BothMethodsAllLevels, TerrainCracks, ::testing::ValuesIn(allCases()), caseName);

// The same proof with geomorphing on: morphed heights are a function of a vertex's lattice xz and the camera,
// so shared edge vertices stay bit-identical (skirt tops use the same height). CI: the "ours" method at seven
// levels over 20 poses; SYLVA_FULL=1: both methods, every level, all 200 poses.
constexpr int kCiGeomorphPoses = 20;
const int kGeomorphPoses = test::fullMode() ? kFullPoses : kCiGeomorphPoses;

class TerrainCracksGeomorph : public TerrainCracks {};

TEST_P(TerrainCracksGeomorph, NoBackgroundThroughTheMorphedSurfaceOnJacksboro) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  expectNoCracks(
      shaders(), GetParam(), kGeomorphPoses, "crack_geomorph", [](int) { return true; }, 0.0f,
      [](const std::string& k, const std::string& v) { ::testing::Test::RecordProperty(k, v); });
}

std::vector<CrackCase> geomorphCases() {
  if (test::fullMode()) {
    return allCases();
  }
  std::vector<CrackCase> cases;
  for (int tess : {1, 2, 3, 5, 8, 16, 32}) {
    cases.push_back({CrackMethod::RestrictedLevelMap, tess});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Geomorph, TerrainCracksGeomorph, ::testing::ValuesIn(geomorphCases()), caseName);

// The same proof with screen-space-error LOD (levels chosen by each node's geometric error projected into
// the 120-pixel-high target, τ = 0.5 px, plus the distance floor that keeps the selection restricted); the
// geomorph option is set on every other pose and must change nothing (error LOD draws unmorphed). CI: both
// methods at seven levels over 20 poses; SYLVA_FULL=1: both methods, every level, all 200 poses.
class TerrainCracksErrorLod : public TerrainCracks {};

TEST_P(TerrainCracksErrorLod, NoBackgroundThroughTheSurfaceWithScreenErrorLod) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  expectNoCracks(
      shaders(), GetParam(), kGeomorphPoses, "crack_error_lod", [](int pose) { return pose % 2 == 1; }, 0.5f,
      [](const std::string& k, const std::string& v) { ::testing::Test::RecordProperty(k, v); });
}

std::vector<CrackCase> errorLodCases() {
  if (test::fullMode()) {
    return allCases();
  }
  std::vector<CrackCase> cases;
  for (CrackMethod method : {CrackMethod::PaperSearch, CrackMethod::RestrictedLevelMap}) {
    for (int tess : {1, 2, 3, 5, 8, 16, 32}) {
      cases.push_back({method, tess});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(ErrorLod, TerrainCracksErrorLod, ::testing::ValuesIn(errorLodCases()), caseName);

using TerrainCrackCheck = test::GlTest;

// Without stitching, T-junctions must show up as crack pixels at every level: the check is not vacuous.
TEST_F(TerrainCrackCheck, FindsCracksWhenStitchingIsDisabled) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  CrackRig rig(shaders());
  for (int tess = 1; tess <= kMaxPatchTessLevel; ++tess) {
    std::int64_t found = 0;
    int pose = 0;
    for (; pose < kPoses && found == 0; ++pose) {
      found = rig.cracks(CrackMethod::None, tess, pose);
    }
    EXPECT_GT(found, 0) << "no crack found at level " << tess << " in " << kPoses << " poses";
    RecordProperty(fmt::format("level{:02}_first_pose_with_cracks", tess), pose - 1);
    RecordProperty(fmt::format("level{:02}_crack_samples", tess), std::to_string(found));
  }
}

// The geomorph crack check is not vacuous either: without stitching it finds the T-junctions.
TEST_F(TerrainCrackCheck, FindsCracksWithGeomorphWhenStitchingIsDisabled) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  CrackRig rig(shaders());
  for (int tess : {1, 4, 16}) {
    std::int64_t found = 0;
    for (int pose = 0; pose < kPoses && found == 0; ++pose) {
      found = rig.cracks(CrackMethod::None, tess, pose, true);
    }
    EXPECT_GT(found, 0) << "no crack found at level " << tess << " with geomorphing";
  }
}

} // namespace
} // namespace sylva::terrain

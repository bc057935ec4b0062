// From captured blades to blade models: tracking blades through a swaying synthetic recording (including a
// frame that loses a blade), blade models (levels, blade space, normals, widths, option errors, motion frame
// counts, file round trip) and a fakenect recording of the sequence extracting like the frames themselves.
#include <sylva/blades/BladeModel.hpp>
#include <sylva/capture/Extract.hpp>
#include <sylva/capture/Fakenect.hpp>
#include <sylva/capture/Pipeline.hpp>
#include <sylva/capture/Synthetic.hpp>
#include <sylva/core/Error.hpp>

#include "TempDir.hpp"

#include <glm/geometric.hpp>
#include "CaptureTestUtil.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace sylva::capture {
namespace {

using testutil::contains;
using testutil::errorOf;

constexpr int kSwayFrames = 20;
constexpr double kSwayFps = 30.0;

/** The swaying five-blade sequence and its captures, made once for the tests that share it. */
struct Sway {
  std::vector<SyntheticFrame> frames;
  std::vector<ExtractResult> results;
};

const Sway& sway() {
  static const Sway s = [] {
    Sway out;
    const SyntheticScene scene = makeCluster(BladeShape::SlimGrass, 5, 0.3f, 0.0f, 51);
    out.frames = swaySequence(scene, kSwayFrames, kSwayFps, 0.25f, 0.8);
    for (const SyntheticFrame& f : out.frames) {
      out.results.push_back(extractBlades(f.frame));
    }
    return out;
  }();
  return s;
}

/** Index of the true blade whose tip (pixels) is nearest `tipPx`, and that distance. */
std::pair<int, float> nearestTrueTip(const SyntheticTruth& truth, const glm::vec2& tipPx) {
  int best = -1;
  float bestDistance = std::numeric_limits<float>::max();
  for (std::size_t b = 0; b < truth.centrelinePx.size(); ++b) {
    const float d = glm::length(truth.centrelinePx[b].back() - tipPx);
    if (d < bestDistance) {
      bestDistance = d;
      best = static_cast<int>(b);
    }
  }
  return {best, bestDistance};
}

/** Distance (pixels) from `p` to the nearest sample of a true centreline. */
float distanceToLine(const std::vector<glm::vec2>& line, const glm::vec2& p) {
  float best = std::numeric_limits<float>::max();
  for (const glm::vec2& q : line) {
    best = std::min(best, glm::length(q - p));
  }
  return best;
}

/** The blade of `result` with exactly these knots, or null. */
const CapturedBlade* capturedBlade(const ExtractResult& result, const std::vector<glm::vec3>& knots) {
  const auto it = std::find_if(result.blades.begin(), result.blades.end(),
                               [&](const CapturedBlade& b) { return b.knots == knots; });
  return it == result.blades.end() ? nullptr : &*it;
}

float lineLength(const std::vector<glm::vec3>& line) {
  float length = 0.0f;
  for (std::size_t i = 1; i < line.size(); ++i) {
    length += glm::length(line[i] - line[i - 1]);
  }
  return length;
}

TEST(TrackBlades, FollowsEverySwayingBladeThroughTheSequence) {
  const Sway& s = sway();
  for (const ExtractResult& r : s.results) {
    ASSERT_EQ(r.blades.size(), 5u);
  }
  const std::vector<TrackedBlade> tracks = trackBlades(s.results);
  ASSERT_EQ(tracks.size(), 5u);
  // True tips are tens of pixels apart, so the nearest one names the blade unambiguously.
  float closestTrueTips = std::numeric_limits<float>::max();
  for (const SyntheticFrame& f : s.frames) {
    for (std::size_t a = 0; a < f.truth.centrelinePx.size(); ++a) {
      for (std::size_t b = a + 1; b < f.truth.centrelinePx.size(); ++b) {
        closestTrueTips = std::min(
            closestTrueTips, glm::length(f.truth.centrelinePx[a].back() - f.truth.centrelinePx[b].back()));
      }
    }
  }
  std::set<int> followed;
  float worst = 0.0f;
  float worstOffLine = 0.0f;
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    const TrackedBlade& track = tracks[t];
    EXPECT_EQ(track.missingFrames, 0);
    ASSERT_EQ(track.motion.size(), static_cast<std::size_t>(kSwayFrames));
    EXPECT_EQ(track.reference.knots, s.results[0].blades[t].knots);
    const int blade = nearestTrueTip(s.frames[0].truth, track.reference.skeletonPx.back()).first;
    followed.insert(blade);
    float travel = 0.0f;
    for (std::size_t f = 0; f < track.motion.size(); ++f) {
      // Every frame of the track is one of that frame's captured blades...
      const CapturedBlade* captured = capturedBlade(s.results[f], track.motion[f]);
      ASSERT_NE(captured, nullptr) << "track " << t << " frame " << f;
      // ...whose tip is the same true blade's throughout.
      const glm::vec2 tip = captured->skeletonPx.back();
      const auto [nearest, distance] = nearestTrueTip(s.frames[f].truth, tip);
      EXPECT_EQ(nearest, blade) << "track " << t << " frame " << f;
      worst = std::max(worst, distance);
      worstOffLine = std::max(worstOffLine, distanceToLine(s.frames[f].truth.centrelinePx[nearest], tip));
      travel = std::max(travel, glm::length(tip - track.reference.skeletonPx.back()));
    }
    // The tips really move (tracking is not the identity on a still scene).
    EXPECT_GT(travel, 10.0f) << "track " << t;
  }
  EXPECT_EQ(followed.size(), 5u);
  // Thin tips lose their last pixels to noise and dropouts, so a captured tip lies short of the true tip, but
  // on the true blade's centreline, and far nearer to its own true tip than true tips are to each other.
  EXPECT_LT(worst, 0.4f * closestTrueTips);
  EXPECT_LT(worstOffLine, 3.0f);
  std::printf(
      "tracked tips: within %.1f px of the true tips (%.2f px off the centreline); true tips at least "
      "%.1f px apart\n",
      worst, worstOffLine, closestTrueTips);
}

TEST(TrackBlades, ABladeMissingFromOneFrameHoldsItsKnots) {
  const Sway& s = sway();
  const std::vector<TrackedBlade> full = trackBlades(s.results);
  ASSERT_EQ(full.size(), 5u);
  // Frame 10 without one of its blades (the one track 2 took there).
  constexpr std::size_t kFrame = 10;
  std::vector<ExtractResult> results = s.results;
  std::vector<CapturedBlade>& blades = results[kFrame].blades;
  const auto dropped = std::find_if(blades.begin(), blades.end(), [&](const CapturedBlade& b) {
    return b.knots == full[2].motion[kFrame];
  });
  ASSERT_NE(dropped, blades.end());
  blades.erase(dropped);
  ASSERT_EQ(blades.size(), 4u);

  const std::vector<TrackedBlade> tracks = trackBlades(results);
  ASSERT_EQ(tracks.size(), 5u);
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    ASSERT_EQ(tracks[t].motion.size(), static_cast<std::size_t>(kSwayFrames));
    EXPECT_EQ(tracks[t].missingFrames, t == 2 ? 1 : 0) << "track " << t;
    for (std::size_t f = 0; f < tracks[t].motion.size(); ++f) {
      if (t == 2 && f == kFrame) {
        // Held from the frame before, then found again.
        EXPECT_EQ(tracks[t].motion[f], tracks[t].motion[f - 1]);
        EXPECT_NE(tracks[t].motion[f], full[t].motion[f]);
      } else {
        EXPECT_EQ(tracks[t].motion[f], full[t].motion[f]) << "track " << t << " frame " << f;
      }
    }
  }
}

TEST(TrackBlades, TipsBeyondTheJumpLimitAreMissing) {
  const Sway& s = sway();
  // With no allowed jump every later frame misses; knots are held from the reference frame.
  const std::vector<TrackedBlade> tracks = trackBlades(s.results, -1.0f);
  ASSERT_EQ(tracks.size(), 5u);
  for (const TrackedBlade& track : tracks) {
    EXPECT_EQ(track.missingFrames, kSwayFrames - 1);
    ASSERT_EQ(track.motion.size(), static_cast<std::size_t>(kSwayFrames));
    EXPECT_EQ(track.motion.back(), track.reference.knots);
  }
  EXPECT_TRUE(trackBlades({}).empty());
}

/** An upright blade (no lean, no bend) captured from the middle of a five-blade fan. */
const CapturedBlade& uprightBlade() {
  static const CapturedBlade blade = [] {
    const SyntheticFrame frame = renderScene(makeCluster(BladeShape::SlimGrass, 5, 0.0f, 0.0f, 52));
    const ExtractResult result = extractBlades(frame.frame);
    EXPECT_EQ(result.blades.size(), 5u);
    // The middle blade of the fan (lean 0) has its tip straight above the root.
    const glm::vec2 trueTip = frame.truth.centrelinePx[2].back();
    const auto it = std::min_element(
        result.blades.begin(), result.blades.end(), [&](const CapturedBlade& a, const CapturedBlade& b) {
          return glm::length(a.skeletonPx.back() - trueTip) < glm::length(b.skeletonPx.back() - trueTip);
        });
    EXPECT_EQ(nearestTrueTip(frame.truth, it->skeletonPx.back()).first, 2);
    EXPECT_LT(distanceToLine(frame.truth.centrelinePx[2], it->skeletonPx.back()), 3.0f);
    return *it;
  }();
  return blade;
}

blades::BladeSource syntheticSource() {
  blades::BladeSource source;
  source.file = "synthetic:slim";
  source.kind = "synthetic";
  source.intrinsics = CameraIntrinsics::kinectV1();
  source.blade = 2;
  return source;
}

TEST(MakeBladeModel, LevelsInBladeSpace) {
  const CapturedBlade& blade = uprightBlade();
  ASSERT_EQ(blade.knots.size(), 128u);
  ModelOptions options;
  options.levels = {64, 32, 16};
  const blades::BladeModel model = makeBladeModel(blade, {}, options, syntheticSource());
  ASSERT_EQ(model.lods.size(), 3u);
  EXPECT_EQ(model.source.file, "synthetic:slim");
  EXPECT_EQ(model.source.blade, 2);
  EXPECT_EQ(model.source.mu, 0.5);
  EXPECT_EQ(model.source.medialAxis, blade.medialAxis);
  EXPECT_EQ(model.hasColour, blade.hasColour);
  EXPECT_NEAR(glm::length(model.bendAxis), 1.0f, 1e-5f);
  EXPECT_GE(model.bendAxis.x, 0.0f);
  // An upright blade's width runs along the image's x: so does its bend axis.
  EXPECT_GT(model.bendAxis.x, 0.9f);
  const int expected[] = {64, 32, 16};
  for (std::size_t l = 0; l < 3; ++l) {
    const blades::BladeLod& lod = model.lods[l];
    SCOPED_TRACE("level " + std::to_string(expected[l]));
    ASSERT_EQ(lod.knotCount(), static_cast<std::size_t>(expected[l]));
    ASSERT_EQ(lod.widths.size(), lod.knotCount());
    ASSERT_EQ(lod.normals.size(), lod.knotCount());
    EXPECT_EQ(lod.positions.front(), glm::vec3(0.0f));
    // +Y up (the image's up), the tip straight above the root.
    const float length = lineLength(lod.positions);
    const glm::vec3 tip = lod.positions.back();
    EXPECT_GT(tip.y, 0.8f * length);
    EXPECT_LT(std::abs(tip.x), 0.05f * length);
    // Refining keeps the root and the tip, so the chord-based length shrinks only a little (measured: 0.05 %
    // at 16 knots for this blade; the spec allows 5 %, 1 % is asked here).
    EXPECT_LE(length, blade.lengthMetres * 1.0001f);
    EXPECT_GE(length, blade.lengthMetres * 0.99f);
    EXPECT_EQ(tip, glm::vec3(blade.knots.back().x - blade.knots.front().x,
                             -(blade.knots.back().y - blade.knots.front().y),
                             -(blade.knots.back().z - blade.knots.front().z)));
    const std::size_t m = lod.knotCount();
    for (std::size_t k = 0; k < m; ++k) {
      const glm::vec3 tangent =
          glm::normalize(lod.positions[std::min(k + 1, m - 1)] - lod.positions[k > 0 ? k - 1 : 0]);
      EXPECT_NEAR(glm::length(lod.normals[k]), 1.0f, 1e-5f) << "knot " << k;
      EXPECT_LT(std::abs(glm::dot(lod.normals[k], tangent)), 1e-3f) << "knot " << k;
      EXPECT_GE(lod.normals[k].z, 0.0f) << "knot " << k;
      // A blade seen face-on faces the camera: mostly +Z.
      EXPECT_GT(lod.normals[k].z, 0.7f) << "knot " << k;
      EXPECT_GE(lod.widths[k], 0.0f) << "knot " << k;
    }
    const float widest = *std::max_element(lod.widths.begin(), lod.widths.end());
    EXPECT_GT(widest, 0.5f * bladeShapeWidth(BladeShape::SlimGrass));
    // Slim grass closes over its last fifth; refining keeps the tip's own width.
    EXPECT_LT(lod.widths.back(), 0.1f * widest);
  }
  EXPECT_FLOAT_EQ(model.length(), lineLength(model.lods[0].positions));
}

TEST(MakeBladeModel, InvalidLevelsNameTheOption) {
  const CapturedBlade& blade = uprightBlade();
  for (const std::vector<int>& levels :
       std::vector<std::vector<int>>{{}, {64, 64}, {16, 32}, {64, 32, 32}, {129}, {1}, {16, 1}, {0}, {-4}}) {
    ModelOptions options;
    options.levels = levels;
    const std::string message = errorOf([&] { makeBladeModel(blade, {}, options, syntheticSource()); });
    EXPECT_NE(message.find("--levels"), std::string::npos) << levels.size() << " levels: " << message;
  }
  ModelOptions options;
  options.levels = {128, 2};
  EXPECT_EQ(makeBladeModel(blade, {}, options, syntheticSource()).lods.back().knotCount(), 2u);
}

TEST(MakeBladeModel, MotionOfTheWrongKnotCountIsRejected) {
  const CapturedBlade& blade = uprightBlade();
  KnotFrames motion{blade.knots, blade.knots};
  motion[1].pop_back();
  const std::string message = errorOf([&] { makeBladeModel(blade, motion, {}, syntheticSource()); });
  EXPECT_NE(message.find("127 knots"), std::string::npos) << message;
  CapturedBlade broken = blade;
  broken.widths.pop_back();
  EXPECT_NE(errorOf([&] { makeBladeModel(broken, {}, {}, syntheticSource()); }).find("widths"),
            std::string::npos);
}

TEST(MakeBladeModel, MotionFrames) {
  const CapturedBlade& blade = uprightBlade();
  ModelOptions still;
  still.simulateSway = false;
  const blades::BladeModel a = makeBladeModel(blade, {}, still, syntheticSource());
  EXPECT_EQ(a.source.motionFrames, 1);
  ModelOptions swaying;
  swaying.simulateSway = true;
  swaying.sway.frames = 37;
  swaying.mu = 0.25;
  const blades::BladeModel b = makeBladeModel(blade, {}, swaying, syntheticSource());
  EXPECT_EQ(b.source.motionFrames, 38);
  EXPECT_EQ(b.source.mu, 0.25);
  // Refining never moves the root or the tip.
  EXPECT_EQ(a.lods.back().positions.back(), b.lods.back().positions.back());
  // The sway bends the blade most towards its tip: with the displacement variance (the default) refining
  // keeps more knots there than the static pose does. The paper's distance variance cannot see it: the sway
  // keeps segment lengths, so adjacent knots keep their distance in every frame and the same knots merge.
  auto tipHalf = [](const blades::BladeModel& m) {
    const blades::BladeLod& lod = m.lods.back();
    const float half = 0.5f * lod.positions.back().y;
    return std::count_if(lod.positions.begin(), lod.positions.end(),
                         [half](const glm::vec3& p) { return p.y > half; });
  };
  ModelOptions stillDefault;
  stillDefault.simulateSway = false;
  ModelOptions swayDefault;
  const blades::BladeModel staticPose = makeBladeModel(blade, {}, stillDefault, syntheticSource());
  const blades::BladeModel swayed = makeBladeModel(blade, {}, swayDefault, syntheticSource());
  EXPECT_GT(tipHalf(swayed), tipHalf(staticPose));
  ModelOptions paper = swayDefault;
  paper.measure = RefineOptions::Measure::Distance;
  paper.rawMetres = true;
  EXPECT_EQ(makeBladeModel(blade, {}, paper, syntheticSource()).lods.back().positions,
            makeBladeModel(blade, {}, stillDefault, syntheticSource()).lods.back().positions);

  // A recording's motion.
  const Sway& s = sway();
  const std::vector<TrackedBlade> tracks = trackBlades(s.results);
  ASSERT_FALSE(tracks.empty());
  const blades::BladeModel c =
      makeBladeModel(tracks[0].reference, tracks[0].motion, swaying, syntheticSource());
  EXPECT_EQ(c.source.motionFrames, kSwayFrames);
  ASSERT_EQ(c.lods.size(), 3u);
  // Measured movement (sensor noise included) changes which knots merge.
  const blades::BladeModel still0 = makeBladeModel(tracks[0].reference, {}, still, syntheticSource());
  for (std::size_t l = 0; l < 3; ++l) {
    EXPECT_NE(c.lods[l].positions, still0.lods[l].positions) << "level " << l;
    EXPECT_EQ(c.lods[l].positions.back(), still0.lods[l].positions.back()) << "level " << l;
  }
  EXPECT_EQ(c.lods[0].positions.front(), glm::vec3(0.0f));
  // The pose is the first motion frame, which is the reference capture.
  EXPECT_EQ(c.lods[0].positions.back(),
            glm::vec3(tracks[0].reference.knots.back().x - tracks[0].reference.knots.front().x,
                      -(tracks[0].reference.knots.back().y - tracks[0].reference.knots.front().y),
                      -(tracks[0].reference.knots.back().z - tracks[0].reference.knots.front().z)));
}

TEST(MakeBladeModel, SavesAndLoadsExactly) {
  const test::TempDir dir;
  const Sway& s = sway();
  const std::vector<TrackedBlade> tracks = trackBlades(s.results);
  blades::BladeModelFile file;
  file.generator = "sylva capture test: sway";
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    blades::BladeSource source = syntheticSource();
    source.blade = static_cast<int>(t);
    blades::BladeModel model = makeBladeModel(tracks[t].reference, tracks[t].motion, {}, source);
    model.name = "sway-" + std::to_string(t);
    file.blades.push_back(std::move(model));
  }
  file.blades.push_back(makeBladeModel(uprightBlade(), {}, {}, syntheticSource()));
  file.blades.back().name = "upright";
  blades::saveBladeModels(dir / "grass.json", file);
  EXPECT_EQ(blades::toJson(blades::loadBladeModels(dir / "grass.json")), blades::toJson(file));
}

TEST(FakenectSway, ARecordingOfTheSequenceExtractsTheSame) {
  const test::TempDir dir;
  const Sway& s = sway();
  {
    FakenectWriter writer(dir / "sway");
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
      const double walltime = static_cast<double>(i) / kSwayFps;
      writer.addRgb(s.frames[i].frame.colour, walltime);
      writer.addDepth(s.frames[i].frame, walltime);
    }
    writer.finish();
  }
  const FakenectRecording recording = FakenectRecording::open(dir / "sway");
  EXPECT_TRUE(recording.warnings().empty());
  ASSERT_EQ(recording.depthFrameCount(), s.frames.size());
  std::vector<ExtractResult> replayedResults;
  for (std::size_t i = 0; i < s.frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    const DepthFrame replayed = recording.depthFrame(i);
    const DepthFrame& original = s.frames[i].frame;
    // Walltimes are written with 6 decimals (fakenect-record's "%.6f").
    EXPECT_NEAR(replayed.timestamp, static_cast<double>(i) / kSwayFps, 1e-6);
    EXPECT_EQ(replayed.intrinsics, original.intrinsics);
    // The generator quantises through the Kinect's raw values already, so the recording loses nothing.
    std::size_t differing = 0;
    for (std::size_t p = 0; p < original.depth.size(); ++p) {
      differing += replayed.depth[p] != original.depth[p] ? 1 : 0;
    }
    EXPECT_EQ(differing, 0u);
    ASSERT_FALSE(replayed.colour.empty());
    const auto rgbA = replayed.colour.values<std::uint8_t>();
    const auto rgbB = original.colour.values<std::uint8_t>();
    EXPECT_TRUE(std::equal(rgbA.begin(), rgbA.end(), rgbB.begin(), rgbB.end()));

    replayedResults.push_back(extractBlades(replayed));
    const ExtractResult& a = replayedResults.back();
    const ExtractResult& b = s.results[i];
    EXPECT_EQ(a.colourRefined, b.colourRefined);
    ASSERT_EQ(a.blades.size(), b.blades.size());
    for (std::size_t j = 0; j < a.blades.size(); ++j) {
      ASSERT_EQ(a.blades[j].knots.size(), b.blades[j].knots.size());
      for (std::size_t k = 0; k < a.blades[j].knots.size(); ++k) {
        EXPECT_LE(glm::length(a.blades[j].knots[k] - b.blades[j].knots[k]), 1e-6f)
            << "blade " << j << " knot " << k;
      }
    }
  }
  // The tracks of the replay are the tracks of the frames.
  const std::vector<TrackedBlade> a = trackBlades(replayedResults);
  const std::vector<TrackedBlade> b = trackBlades(s.results);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t t = 0; t < a.size(); ++t) {
    EXPECT_EQ(a[t].missingFrames, b[t].missingFrames);
    EXPECT_EQ(a[t].motion.size(), b[t].motion.size());
  }
}

// The whole run as `sylva capture` makes it: frames loaded lazily, one model per blade of the first frame,
// the recording's motion by default when there are several frames, scaling to a given longest blade, and the
// stage pictures.
TEST(CapturePipeline, CaptureBladesRunsFramesToModelsAsTheCommandDoes) {
  const SyntheticScene scene = makeCluster(BladeShape::SlimGrass, 5, 0.3f, 0.0f, 51);
  const std::vector<SyntheticFrame> frames = swaySequence(scene, 4, 10.0, 0.15f, 1.0);
  std::vector<int> loaded;
  CaptureSettings settings;
  settings.name = "fan";
  settings.generator = "test";
  const CaptureRun run = captureBlades(
      4,
      [&](int i) {
        loaded.push_back(i);
        return frames[static_cast<std::size_t>(i)].frame;
      },
      settings, "synthetic:slim", "capturing");
  EXPECT_EQ(loaded, (std::vector<int>{0, 1, 2, 3}));
  ASSERT_EQ(run.results.size(), 4u);
  EXPECT_EQ(run.motion, CaptureMotion::Recording);
  ASSERT_EQ(run.file.blades.size(), run.results.front().blades.size());
  EXPECT_EQ(run.file.blades.size(), 5u);
  EXPECT_EQ(run.file.generator, "test");
  EXPECT_EQ(run.file.blades.front().name, "fan-0");
  EXPECT_EQ(run.file.blades.front().source.file, "synthetic:slim");
  EXPECT_EQ(run.file.blades.front().source.motionFrames, 4);
  EXPECT_FLOAT_EQ(run.scale, 1.0f);

  // One frame: a simulated sway, and every model scaled so the longest blade is 0.25 m.
  settings.scaleToMetres = 0.25;
  const CaptureRun one = captureBlades(
      1, [&](int) { return frames.front().frame; }, settings, "synthetic:slim", "capturing");
  EXPECT_EQ(one.motion, CaptureMotion::Sway);
  float longest = 0.0f;
  for (const blades::BladeModel& m : one.file.blades) {
    longest = std::max(longest, m.length());
  }
  EXPECT_NEAR(longest, 0.25f, 1e-4f);
  EXPECT_NE(one.scale, 1.0f);

  // The recording's motion needs two frames; a frame without blades names the frame.
  settings.motion = CaptureMotion::Recording;
  EXPECT_NE(errorOf([&] {
              captureBlades(
                  1, [&](int) { return frames.front().frame; }, settings, "synthetic:slim", "c");
            }).find("at least 2 frames"),
            std::string::npos);
  DepthFrame empty = frames.front().frame;
  std::fill(empty.depth.begin(), empty.depth.end(), 0.0f);
  const std::string none = errorOf([&] {
    captureBlades(
        1, [&](int) { return empty; }, settings, "x", "c");
  });
  EXPECT_NE(none.find("no blades found"), std::string::npos) << none;
  EXPECT_NE(none.find(empty.label()), std::string::npos) << none;

  const test::TempDir dir;
  writeCaptureStages(dir.path(), run.reference, run.results.front());
  for (const char* stage : {"1-depth.png", "2-mask.png", "3-contour.png", "4-signal.png", "5-blades.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.path() / stage)) << stage;
  }
}

} // namespace
} // namespace sylva::capture

// Wind on the joints: the rest data follows the spec's formulas, frames equal jointFrames(), released joints
// swing in the spec's bands (trunks 0.2–1 Hz, twigs 2–6 Hz, measured from the simulated motion), the step
// stays bounded in a storm, trees do not move in unison, and the parallel step is deterministic.
#include <sylva/core/Error.hpp>
#include <sylva/trees/JointWind.hpp>
#include <sylva/wind/Wind.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>

namespace sylva::trees {
namespace {

constexpr float kDt = 1.0f / 60.0f;

/** Trees for the tests: owns what JointWindTree points to. */
struct TestForest {
  PieceSet pieces = standardPieces();
  std::vector<std::unique_ptr<Species>> species;
  std::vector<std::unique_ptr<TreeTopology>> topologies;
  std::vector<std::unique_ptr<std::vector<glm::vec2>>> poses;
  std::vector<JointWindTree> trees;

  /** Adds a tree of preset `name` from `seed` at `position` (metres) with its pose and `timeOffset`. */
  void add(const std::string& name, std::uint64_t seed, glm::vec3 position, float timeOffset,
           float yaw = 0.0f) {
    species.push_back(std::make_unique<Species>(speciesPreset(name)));
    topologies.push_back(std::make_unique<TreeTopology>(generateTree(pieces, *species.back(), seed)));
    poses.push_back(
        std::make_unique<std::vector<glm::vec2>>(randomPose(*topologies.back(), *species.back(), seed)));
    JointWindTree t;
    t.topology = topologies.back().get();
    t.species = species.back().get();
    t.base = baseFrame(position, yaw, species.back()->trunkRadius);
    t.pose = *poses.back();
    t.timeOffset = timeOffset;
    trees.push_back(t);
  }
  JointWindRest rest(const JointWindSettings& settings = {}) const {
    return buildJointWindRest(pieces, trees, settings);
  }
};

wind::WindSettings still() {
  wind::WindSettings w;
  w.speed = 0.0f;
  return w;
}

wind::WindSettings storm() {
  wind::WindSettings w;
  w.direction = {0.8f, 0.6f};
  w.speed = 20.0f;
  w.gustStrength = 2.0f;
  w.gustLength = 12.0f;
  w.gustWidth = 6.0f;
  w.turbulence = 0.6f;
  w.turbulenceScale = 1.5f;
  w.turbulenceRate = 2.0f;
  w.seed = 5;
  return w;
}

/**
 * Frequency (Hz) of a sampled signal from its zero crossings (times interpolated linearly): half a period
 * between consecutive crossings, averaged over the first `maxCrossings`. 0 when it crosses fewer than 3
 * times.
 */
double zeroCrossingFrequency(const std::vector<float>& x, double dt, int maxCrossings = 8) {
  std::vector<double> times;
  for (std::size_t i = 1; i < x.size() && static_cast<int>(times.size()) < maxCrossings; ++i) {
    if ((x[i - 1] < 0.0f) != (x[i] < 0.0f) && x[i - 1] != x[i]) {
      const double f = static_cast<double>(x[i - 1]) / static_cast<double>(x[i - 1] - x[i]);
      times.push_back((static_cast<double>(i - 1) + f) * dt);
    }
  }
  if (times.size() < 3) {
    return 0.0;
  }
  return static_cast<double>(times.size() - 1) / (2.0 * (times.back() - times.front()));
}

double correlation(const std::vector<float>& a, const std::vector<float>& b) {
  const auto n = static_cast<double>(a.size());
  double ma = 0.0;
  double mb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i] / n;
    mb += b[i] / n;
  }
  double sab = 0.0;
  double saa = 0.0;
  double sbb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

TEST(JointWind, RestDataFollowsTheSpecsFormulas) {
  TestForest f;
  f.add("almond", 3, {10.0f, 0.0f, -4.0f}, 12.5f, 0.7f);
  f.add("quaking-aspen", 4, {-6.0f, 1.0f, 2.0f}, 40.0f);
  const JointWindRest rest = f.rest();
  ASSERT_EQ(rest.treeCount(), 2u);
  ASSERT_EQ(rest.jointOffset[1], f.topologies[0]->jointCount());
  ASSERT_EQ(rest.jointCount(), f.topologies[0]->jointCount() + f.topologies[1]->jointCount());
  for (std::size_t t = 0; t < 2; ++t) {
    const TreeTopology& topo = *f.topologies[t];
    const Species& species = *f.species[t];
    const std::uint32_t offset = rest.jointOffset[t];
    std::vector<glm::mat4> frames;
    jointFrames(f.pieces, topo, f.trees[t].base, f.trees[t].pose, frames);
    // The base is fixed and carries the base frame.
    const gpu::TreeJointRest& base = rest.joints[offset];
    EXPECT_EQ(base.info.x, SYLVA_TREE_NO_PARENT);
    EXPECT_EQ(base.info.w, SYLVA_TREE_WIND_FIXED);
    EXPECT_EQ(jointFrameMatrix(base.local), f.trees[t].base);
    float totalMass = 0.0f;
    for (std::size_t j = 1; j < topo.jointCount(); ++j) {
      SCOPED_TRACE(testing::Message() << "tree " << t << " joint " << j);
      const gpu::TreeJointRest& r = rest.joints[offset + j];
      const JointSpring& s = rest.springs[offset + j];
      // The node's root joint is its parent's terminal joint: the same global entry.
      EXPECT_EQ(r.info.x, offset + static_cast<std::uint32_t>(topo.jointParent[j]));
      EXPECT_EQ(r.info.y, t);
      EXPECT_EQ(r.info.z, rest.joints[r.info.x].info.z + 1u);
      EXPECT_EQ(r.spring.w, f.trees[t].timeOffset);
      EXPECT_EQ(glm::vec2(r.probe.z, r.probe.w), f.trees[t].pose[j]);
      // k = E·(πr⁴/4)/L with r the rim radius at the joint and L the bone from the node's root rim centre.
      const float radius = glm::length(glm::vec3(frames[j][0]));
      const TreeNode& node = topo.nodes[static_cast<std::size_t>(topo.jointNode[j])];
      const float length = glm::length(glm::vec3(frames[j][3]) - glm::vec3(frames[node.rootJoint][3]));
      EXPECT_NEAR(s.radius, radius, 1e-5f * radius);
      EXPECT_NEAR(s.length, length, 1e-5f * length);
      const double k = species.youngModulus * std::numbers::pi * std::pow(radius, 4.0) / 4.0 / length;
      EXPECT_NEAR(s.cantileverStiffness, k, 1e-4 * k);
      EXPECT_GT(s.mass, 0.0f);
      EXPECT_GT(s.inertia, 0.0f);
      EXPECT_GT(s.area, 0.0f);
      EXPECT_NEAR(s.cantileverFrequency,
                  std::sqrt(s.cantileverStiffness / s.inertia) / (2.0 * std::numbers::pi),
                  1e-4 * s.cantileverFrequency);
      // The spring and damper from the calibrated frequency: k/I = (2πf)², c/I = 2ζ·2πf.
      const double omega = 2.0 * std::numbers::pi * s.frequency;
      EXPECT_NEAR(r.spring.x, omega * omega, 1e-4 * omega * omega);
      EXPECT_NEAR(r.spring.y, 2.0 * species.damping * omega, 1e-4 * omega);
      EXPECT_NEAR(s.damping, 2.0 * std::sqrt(static_cast<double>(s.stiffness) * s.inertia) * species.damping,
                  1e-3 * s.damping);
      // The wind is sampled at the subtree's area centroid, the lever's end.
      const glm::vec3 centroid = glm::vec3(frames[j][3]) + s.lever;
      EXPECT_NEAR(r.probe.x, centroid.x, 1e-4f);
      EXPECT_NEAR(r.probe.y, centroid.z, 1e-4f);
      if (topo.jointParent[j] == 0) {
        totalMass += s.mass;
      }
    }
    // Joint 1 (the foot's top) carries everything but the foot; a subtree never outweighs it.
    for (std::size_t j = 1; j < topo.jointCount(); ++j) {
      EXPECT_LE(rest.springs[offset + j].mass, totalMass * 1.0001f);
    }
    EXPECT_GT(totalMass, 5.0f) << "a tree of wood weighs kilograms";
  }
}

TEST(JointWind, PieceMassesComeFromTheMeshVolume) {
  // A topology built by hand, Foot → I → Cap: joint 1 carries the I and the cap, joint 2 the cap alone.
  TestForest f;
  TreeTopology topo;
  topo.nodes.resize(3);
  topo.nodes[0].piece = f.pieces.find("Foot");
  topo.nodes[1].piece = f.pieces.find("I");
  topo.nodes[1].parent = 0;
  topo.nodes[1].parentRim = 1;
  topo.nodes[2].piece = f.pieces.find("Cap");
  topo.nodes[2].parent = 1;
  topo.nodes[2].parentRim = 1;
  indexJoints(f.pieces, topo);
  ASSERT_EQ(topo.jointCount(), 3u);
  Species species = speciesPreset("almond");
  JointWindTree t;
  t.topology = &topo;
  t.species = &species;
  t.base = baseFrame(glm::vec3(0.0f), 0.0f, 0.2f);
  JointWindSettings settings;
  settings.foliageArea = 0.0f;
  const JointWindRest rest = buildJointWindRest(f.pieces, std::span<const JointWindTree>(&t, 1), settings);
  // The I (on the foot's leaf rim, scale 0.8) is a frustum of a hexagonal prism: length L rim units (its leaf
  // rim's height), corner radius 1 → 1 − L tan β, hexagon area (3√3/2)·R², volume L/3·(A₀ + A₁ + √(A₀A₁)).
  const Piece& iPiece = f.pieces[static_cast<std::size_t>(f.pieces.find("I"))];
  const double length = static_cast<double>(iPiece.rims[1].frame[3].y);
  const double unit = 0.2 * 0.8; // metres per rim unit of the I
  const double r1 = 1.0 - length * std::tan(static_cast<double>(kRimConeAngle));
  const double hexagon = 3.0 * std::sqrt(3.0) / 2.0 * length * (1.0 + r1 + r1 * r1) / 3.0;
  const double capMass = rest.springs[2].mass;
  const double iMass = rest.springs[1].mass - capMass;
  EXPECT_NEAR(iMass, species.woodDensity * hexagon * unit * unit * unit, 0.02 * iMass);
  // Its frontal area: the side of the equivalent cylinder, 2/π × volume.
  const double iArea = rest.springs[1].area - rest.springs[2].area;
  EXPECT_NEAR(iArea, 2.0 / std::numbers::pi * hexagon * unit * unit, 0.02 * iArea);
  EXPECT_TRUE(rest.springs[2].tip);
  EXPECT_FALSE(rest.springs[1].tip);
}

TEST(JointWind, FramesEqualJointFramesOfThePosePlusTheBends) {
  TestForest f;
  f.add("almond", 11, {3.0f, 0.5f, 7.0f}, 1.0f, 1.2f);
  f.add("weeping-willow", 12, {-20.0f, 2.0f, 5.0f}, 2.0f, -0.4f);
  f.add("california-black-oak", 13, {40.0f, -1.0f, -30.0f}, 3.0f, 2.9f);
  const JointWindRest rest = f.rest();
  JointWindState state(rest.jointCount());
  // Bends of up to 0.4 rad in every direction.
  for (std::size_t j = 0; j < rest.jointCount(); ++j) {
    const float a = static_cast<float>(j) * 2.399f;
    state.motion[j] = glm::vec4(0.4f * std::cos(a) * std::sin(0.37f * static_cast<float>(j)),
                                0.4f * std::sin(a) * std::cos(0.11f * static_cast<float>(j)), 0.0f, 0.0f);
  }
  std::vector<glm::mat4> frames;
  forestJointFrames(rest, state, frames);
  ASSERT_EQ(frames.size(), rest.jointCount());
  std::vector<gpu::JointFrame> packed;
  forestJointFrames(rest, state, packed);
  double worst = 0.0;
  for (std::size_t t = 0; t < rest.treeCount(); ++t) {
    const std::vector<glm::vec2> bends = treeBends(rest, state, t);
    std::vector<glm::mat4> reference;
    jointFrames(f.pieces, *f.topologies[t], f.trees[t].base, bends, reference);
    const std::uint32_t offset = rest.jointOffset[t];
    EXPECT_EQ(frames[offset], f.trees[t].base) << "frames[0] of each tree is its base frame";
    for (std::size_t j = 0; j < reference.size(); ++j) {
      EXPECT_EQ(jointFrameMatrix(packed[offset + j]), frames[offset + j]);
      for (int c = 0; c < 4; ++c) {
        // Metres for the translation, metres per rim unit for the linear part.
        worst = std::max<double>(worst, glm::length(frames[offset + j][c] - reference[j][c]));
      }
    }
  }
  std::printf("frames against jointFrames(): worst difference %.3g m\n", worst);
  EXPECT_LT(worst, 2e-5);
}

TEST(JointWind, ReleasedTrunksAndTwigsSwingInTheSpecsBands) {
  // Every joint displaced and released in still air; its frequency from the zero crossings of θ.x over 25 s
  // at 60 Hz. Trunk joints (order 0, within three pieces of the root) must swing at 0.2–1 Hz, the twig tips
  // (the tree's highest order, carrying a cap) at 2–6 Hz.
  const wind::WindSettings air = still();
  for (const std::string name : {"almond", "quaking-aspen", "california-black-oak", "weeping-willow"}) {
    TestForest f;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      f.add(name, seed, {static_cast<float>(seed) * 10.0f, 0.0f, 0.0f}, 0.0f);
    }
    const JointWindRest rest = f.rest();
    JointWindState state(rest.jointCount());
    for (std::size_t j = 0; j < rest.jointCount(); ++j) {
      state.motion[j] = glm::vec4(0.05f, -0.03f, 0.0f, 0.0f);
    }
    const int steps = 1500;
    std::vector<std::vector<float>> series(rest.jointCount());
    for (int i = 1; i <= steps; ++i) {
      stepJointWind(rest, state, wind::toUniforms(air, static_cast<float>(i) * kDt), kDt);
      for (std::size_t j = 0; j < rest.jointCount(); ++j) {
        series[j].push_back(state.motion[j].x);
      }
    }
    double trunkMin = 1e9;
    double trunkMax = 0.0;
    double twigMin = 1e9;
    double twigMax = 0.0;
    int trunks = 0;
    int twigs = 0;
    for (std::size_t t = 0; t < rest.treeCount(); ++t) {
      int highest = 0;
      for (std::uint32_t j = rest.jointOffset[t] + 1; j < rest.jointOffset[t + 1]; ++j) {
        highest = std::max(highest, rest.springs[j].order);
      }
      for (std::uint32_t j = rest.jointOffset[t] + 1; j < rest.jointOffset[t + 1]; ++j) {
        const JointSpring& s = rest.springs[j];
        const bool trunk = s.order == 0 && s.depth <= 3;
        const bool twig = s.order == highest && s.tip;
        if (!trunk && !twig) {
          continue;
        }
        const double f0 = zeroCrossingFrequency(series[j], kDt);
        SCOPED_TRACE(testing::Message()
                     << name << " tree " << t << " joint " << j - rest.jointOffset[t] << " natural "
                     << s.frequency << " Hz, cantilever " << s.cantileverFrequency << " Hz");
        if (trunk) {
          ++trunks;
          trunkMin = std::min(trunkMin, f0);
          trunkMax = std::max(trunkMax, f0);
          EXPECT_GE(f0, 0.2);
          EXPECT_LE(f0, 1.0);
        } else {
          ++twigs;
          twigMin = std::min(twigMin, f0);
          twigMax = std::max(twigMax, f0);
          EXPECT_GE(f0, 2.0);
          EXPECT_LE(f0, 6.0);
        }
      }
    }
    std::printf("%-22s trunks: %2d joints at %.2f–%.2f Hz; twig tips: %3d joints at %.2f–%.2f Hz\n",
                name.c_str(), trunks, trunkMin, trunkMax, twigs, twigMin, twigMax);
    EXPECT_GE(trunks, 12);
    EXPECT_GE(twigs, 12);
  }
}

TEST(JointWind, ZeroCrossingsMeasureAKnownFrequency) {
  // The measurement itself: a 3 Hz damped cosine sampled at 60 Hz reads 3 Hz, a 0.4 Hz one 0.4 Hz.
  for (const double hz : {0.4, 3.0}) {
    std::vector<float> x;
    for (int i = 0; i < 1500; ++i) {
      const double t = i * static_cast<double>(kDt);
      x.push_back(static_cast<float>(std::exp(-0.3 * t) * std::cos(2.0 * std::numbers::pi * hz * t + 0.3)));
    }
    EXPECT_NEAR(zeroCrossingFrequency(x, kDt), hz, 0.01 * hz);
  }
}

TEST(JointWind, StaysBoundedForAMinuteOfStorm) {
  // 60 s at 60 Hz in a 20 m/s wind with gusts to 60 m/s and strong turbulence: every θ and ω finite, every
  // bend within 30°, and the storm really bends the trees (twigs reach the stop, trunks move).
  TestForest f;
  int i = 0;
  for (const std::string name : {"almond", "quaking-aspen", "weeping-willow", "california-black-oak",
                                 "lombardy-poplar", "apple", "paper-alternate"}) {
    f.add(name, 21 + static_cast<std::uint64_t>(i), {static_cast<float>(i) * 7.0f, 0.0f, 3.0f},
          windTimeOffset(i));
    ++i;
  }
  const JointWindRest rest = f.rest();
  JointWindState state(rest.jointCount());
  const wind::WindSettings w = storm();
  float largest = 0.0f;
  float largestTrunk = 0.0f;
  float fastest = 0.0f;
  std::size_t atStop = 0;
  for (int step = 1; step <= 3600; ++step) {
    stepJointWind(rest, state, wind::toUniforms(w, static_cast<float>(step) * kDt), kDt);
    for (std::size_t j = 0; j < rest.jointCount(); ++j) {
      const glm::vec4 m = state.motion[j];
      ASSERT_TRUE(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z) && std::isfinite(m.w))
          << "joint " << j << " at step " << step;
      const float bend = glm::length(glm::vec2(m.x, m.y));
      ASSERT_LE(bend, rest.maxBend * (1.0f + 1e-6f)) << "joint " << j << " at step " << step;
      largest = std::max(largest, bend);
      fastest = std::max(fastest, glm::length(glm::vec2(m.z, m.w)));
      atStop += bend >= rest.springs[j].stop * 0.999f && rest.springs[j].stop > 0.0f ? 1u : 0u;
      if (rest.springs[j].order == 0 && j != rest.jointOffset[rest.joints[j].info.y]) {
        largestTrunk = std::max(largestTrunk, bend);
      }
    }
  }
  std::printf(
      "storm: largest bend %.3f rad, largest trunk bend %.3f rad, fastest %.2f rad/s, %zu joint-steps "
      "at the stop\n",
      largest, largestTrunk, fastest, atStop);
  EXPECT_GT(atStop, 0u);
  EXPECT_GT(largestTrunk, 0.01f);
  EXPECT_LT(fastest, 100.0f);
}

TEST(JointWind, NoWindFoldsACrownOverOrIntoTheGround) {
  // Issue 29's extremes: a steady 60 m/s wind with gusts and turbulence for 20 s on tall, spreading,
  // hanging and whorled species and a sapling. Every joint's bend stays within its stop, the stops along any
  // base-to-tip path sum to at most chainBend, so no twig tip turns further than that from its rest
  // direction, none goes below the ground its tree stands on, and no bone folds back over its parent's.
  wind::WindSettings w = storm();
  w.speed = 60.0f;
  TestForest f;
  int i = 0;
  for (const std::string name : {"lombardy-poplar", "california-black-oak", "weeping-willow", "silver-birch",
                                 "norway-spruce", "oak-sapling"}) {
    f.add(name, 41 + static_cast<std::uint64_t>(i), {static_cast<float>(i) * 25.0f, 0.0f, 3.0f},
          windTimeOffset(i));
    ++i;
  }
  const JointWindRest rest = f.rest();
  JointWindSettings settings;
  // The stops along each path from the base to a tip.
  for (std::size_t t = 0; t < rest.treeCount(); ++t) {
    std::vector<double> sum(rest.jointOffset[t + 1] - rest.jointOffset[t], 0.0);
    for (std::uint32_t j = rest.jointOffset[t] + 1; j < rest.jointOffset[t + 1]; ++j) {
      const std::uint32_t parent = rest.joints[j].info.x;
      sum[j - rest.jointOffset[t]] = sum[parent - rest.jointOffset[t]] + rest.springs[j].stop;
      EXPECT_LE(rest.springs[j].stop, rest.maxBend);
      EXPECT_LE(sum[j - rest.jointOffset[t]], settings.chainBend * (1.0 + 1e-5))
          << "tree " << t << " joint " << j;
    }
  }
  JointWindState state(rest.jointCount());
  std::vector<glm::mat4> atRest;
  forestJointFrames(rest, state, atRest);
  float worstTurn = 0.0f;
  float lowest = 1e9f;
  float worstFold = 0.0f;
  for (int step = 1; step <= 1200; ++step) {
    stepJointWind(rest, state, wind::toUniforms(w, static_cast<float>(step) * kDt), kDt);
    if (step % 60 != 0) {
      continue;
    }
    std::vector<glm::mat4> frames;
    forestJointFrames(rest, state, frames);
    for (std::size_t j = 0; j < rest.jointCount(); ++j) {
      const float bend = glm::length(glm::vec2(state.motion[j].x, state.motion[j].y));
      ASSERT_LE(bend, rest.springs[j].stop + 1e-6f) << "joint " << j;
      if (rest.joints[j].info.x == SYLVA_TREE_NO_PARENT) {
        continue;
      }
      const glm::vec3 bone = glm::normalize(glm::vec3(frames[j][1]));
      const glm::vec3 parentBone = glm::normalize(glm::vec3(frames[rest.joints[j].info.x][1]));
      const glm::vec3 restBone = glm::normalize(glm::vec3(atRest[j][1]));
      const glm::vec3 restParent = glm::normalize(glm::vec3(atRest[rest.joints[j].info.x][1]));
      // Folding: how much further the bone turned away from its parent's than at rest.
      const float fold = std::acos(std::clamp(glm::dot(bone, parentBone), -1.0f, 1.0f)) -
                         std::acos(std::clamp(glm::dot(restBone, restParent), -1.0f, 1.0f));
      worstFold = std::max(worstFold, fold);
      if (rest.springs[j].tip) {
        const float turn = std::acos(std::clamp(glm::dot(bone, restBone), -1.0f, 1.0f));
        worstTurn = std::max(worstTurn, turn);
        EXPECT_LE(turn, settings.chainBend + 1e-3f) << "joint " << j << " at step " << step;
        const float ground = frames[rest.jointOffset[rest.joints[j].info.y]][3].y;
        lowest = std::min(lowest, frames[j][3].y - ground);
      }
    }
  }
  std::printf(
      "60 m/s: twig tips turned up to %.1f deg from rest (chain limit %.1f), lowest tip %.2f m above the "
      "ground, a bone folded at most %.1f deg further from its parent's\n",
      glm::degrees(worstTurn), glm::degrees(settings.chainBend), lowest, glm::degrees(worstFold));
  EXPECT_GT(lowest, 0.0f);
  EXPECT_LT(worstFold, rest.maxBend + 1e-3f);
  EXPECT_GT(worstTurn, 0.2f) << "the storm bends the trees";
}

TEST(JointWind, SteadyWindBendsTreesDownwind) {
  // A steady 8 m/s wind towards +x (no gusts, no turbulence): after the springs settle, every tree's highest
  // joint has moved downwind (+x) and not upwind, whatever the tree's yaw.
  wind::WindSettings w;
  w.direction = {1.0f, 0.0f};
  w.speed = 8.0f;
  w.gustStrength = 0.0f;
  w.turbulence = 0.0f;
  TestForest f;
  for (int t = 0; t < 6; ++t) {
    f.add(t % 2 == 0 ? "almond" : "quaking-aspen", 30 + static_cast<std::uint64_t>(t),
          {static_cast<float>(t) * 8.0f, 0.0f, 0.0f}, 0.0f, static_cast<float>(t) * 1.1f);
  }
  const JointWindRest rest = f.rest();
  JointWindState state(rest.jointCount());
  std::vector<glm::mat4> before;
  forestJointFrames(rest, state, before);
  // 40 s: grown trees sway at a few tenths of a hertz, and their sway decays over several seconds.
  for (int step = 1; step <= 2400; ++step) {
    stepJointWind(rest, state, wind::toUniforms(w, static_cast<float>(step) * kDt), kDt);
  }
  std::vector<glm::mat4> after;
  forestJointFrames(rest, state, after);
  for (std::size_t t = 0; t < rest.treeCount(); ++t) {
    std::size_t top = rest.jointOffset[t];
    for (std::uint32_t j = rest.jointOffset[t]; j < rest.jointOffset[t + 1]; ++j) {
      top = before[j][3].y > before[top][3].y ? j : top;
    }
    const glm::vec3 moved = glm::vec3(after[top][3] - before[top][3]);
    std::printf("tree %zu: top joint moved %.3f m downwind, %.3f m across\n", t, moved.x, moved.z);
    EXPECT_GT(moved.x, 0.01f) << "tree " << t;
    EXPECT_GT(moved.x, 2.0f * std::abs(moved.z)) << "tree " << t;
  }
  // Settled: ω has died out in the steady wind.
  for (const glm::vec4& m : state.motion) {
    EXPECT_LT(glm::length(glm::vec2(m.z, m.w)), 1e-3f);
  }
}

TEST(JointWind, IdenticalTreesDoNotMoveInUnison) {
  // Four copies of one tree in gusty wind: A; B elsewhere with another phase; C in A's place with another
  // phase; D = A (the control, which must move exactly as A). The trunk joint's sway (θ about the axis
  // across the wind) of B and C correlates with A's by less than 0.9.
  wind::WindSettings w;
  w.direction = {1.0f, 0.0f};
  w.speed = 7.0f;
  TestForest f;
  f.add("almond", 8, {0.0f, 0.0f, 0.0f}, windTimeOffset(1));
  f.add("almond", 8, {23.0f, 0.0f, 11.0f}, windTimeOffset(2));
  f.add("almond", 8, {0.0f, 0.0f, 0.0f}, windTimeOffset(3));
  f.add("almond", 8, {0.0f, 0.0f, 0.0f}, windTimeOffset(1));
  const JointWindRest rest = f.rest();
  JointWindState state(rest.jointCount());
  std::vector<std::vector<float>> sway(4);
  for (int step = 1; step <= 3600; ++step) {
    stepJointWind(rest, state, wind::toUniforms(w, static_cast<float>(step) * kDt), kDt);
    if (step > 300) {
      for (std::size_t t = 0; t < 4; ++t) {
        const glm::vec4 m = state.motion[rest.jointOffset[t] + 2];
        sway[t].push_back(m.x + m.y);
      }
    }
  }
  const double ab = correlation(sway[0], sway[1]);
  const double ac = correlation(sway[0], sway[2]);
  const double ad = correlation(sway[0], sway[3]);
  std::printf("trunk sway correlation with tree A: elsewhere %.3f, other phase %.3f, identical %.3f\n", ab,
              ac, ad);
  EXPECT_LT(std::abs(ab), 0.9);
  EXPECT_LT(std::abs(ac), 0.9);
  EXPECT_GT(ad, 0.9999);
}

TEST(JointWind, ParallelStepIsDeterministic) {
  TestForest f;
  for (int t = 0; t < 30; ++t) {
    f.add(t % 3 == 0   ? "almond"
          : t % 3 == 1 ? "quaking-aspen"
                       : "apple",
          50 + static_cast<std::uint64_t>(t),
          {static_cast<float>(t % 6) * 9.0f, 0.0f, static_cast<float>(t / 6) * 9.0f}, windTimeOffset(t));
  }
  const JointWindRest rest = f.rest();
  ASSERT_GT(rest.jointCount(), 1024u * 2u) << "enough joints for several workers";
  const JointWindRest again = f.rest();
  ASSERT_EQ(
      std::memcmp(rest.joints.data(), again.joints.data(), rest.joints.size() * sizeof(gpu::TreeJointRest)),
      0);
  JointWindState parallel(rest.jointCount());
  JointWindState serial(rest.jointCount());
  const wind::WindSettings w = storm();
  for (int step = 1; step <= 240; ++step) {
    const gpu::WindUniforms u = wind::toUniforms(w, static_cast<float>(step) * kDt);
    stepJointWind(rest, parallel, u, kDt);
    stepJointWindRange(rest, serial, u, kDt, 0, rest.jointCount());
  }
  EXPECT_EQ(
      std::memcmp(parallel.motion.data(), serial.motion.data(), parallel.motion.size() * sizeof(glm::vec4)),
      0);
  bool moved = false;
  for (const glm::vec4& m : parallel.motion) {
    moved = moved || m.x != 0.0f;
  }
  EXPECT_TRUE(moved);
}

TEST(JointWind, FixedStepsKeepAFixedRate) {
  double clock = 0.0;
  const double dt = 1.0 / 60.0;
  EXPECT_EQ(fixedSteps(clock, 1.0 / 60.0, dt), 1);
  EXPECT_EQ(fixedSteps(clock, 1.5 / 60.0, dt), 0);
  EXPECT_EQ(fixedSteps(clock, 4.0 / 60.0, dt), 3);
  EXPECT_NEAR(clock, 4.0 / 60.0, 1e-12);
  int total = 4;
  for (int frame = 1; frame <= 144; ++frame) {
    total += fixedSteps(clock, 4.0 / 60.0 + frame / 144.0, dt); // a 144 Hz display for one second
  }
  EXPECT_EQ(total, 64);
  // After a stall the clock skips ahead instead of running hundreds of steps.
  EXPECT_EQ(fixedSteps(clock, clock + 10.0, dt, 8), 8);
  EXPECT_EQ(fixedSteps(clock, clock + 0.5 * dt, dt), 0);
  EXPECT_EQ(fixedSteps(clock, clock - 1.0, dt), 0);
}

TEST(JointWind, BadInputsAreErrors) {
  TestForest f;
  f.add("almond", 1, {0.0f, 0.0f, 0.0f}, 0.0f);
  std::vector<glm::vec2> shortPose(3);
  JointWindTree bad = f.trees[0];
  bad.pose = shortPose;
  EXPECT_THROW(buildJointWindRest(f.pieces, std::span<const JointWindTree>(&bad, 1)), Error);
  bad = f.trees[0];
  bad.species = nullptr;
  EXPECT_THROW(buildJointWindRest(f.pieces, std::span<const JointWindTree>(&bad, 1)), Error);
  bad = f.trees[0];
  bad.timeOffset = std::nanf("");
  EXPECT_THROW(buildJointWindRest(f.pieces, std::span<const JointWindTree>(&bad, 1)), Error);
  TreeTopology shuffled = *f.topologies[0];
  shuffled.jointParent[2] = 5; // a child before its parent
  bad = f.trees[0];
  bad.topology = &shuffled;
  EXPECT_THROW(buildJointWindRest(f.pieces, std::span<const JointWindTree>(&bad, 1)), Error);
  JointWindSettings settings;
  settings.frequencyExponent = 0.0f;
  EXPECT_THROW(validate(settings), Error);
  settings = {};
  settings.maxBend = 2.0f;
  EXPECT_THROW(validate(settings), Error);
  const JointWindRest rest = f.rest();
  JointWindState wrong(rest.jointCount() + 1);
  EXPECT_THROW(stepJointWind(rest, wrong, wind::toUniforms(still(), 0.0f), kDt), Error);
  JointWindState right(rest.jointCount());
  EXPECT_THROW(stepJointWind(rest, right, wind::toUniforms(still(), 0.0f), 0.0f), Error);
  EXPECT_THROW(treeBends(rest, right, 1), Error);
}

} // namespace
} // namespace sylva::trees

// The built-in pieces obey every interlocking rule, and assembled trees close every rim bit for bit.
#include <sylva/core/Error.hpp>
#include <sylva/trees/Pieces.hpp>
#include <sylva/trees/Skeleton.hpp>
#include <sylva/trees/Tessellation.hpp>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <map>

namespace sylva::trees {
namespace {

TEST(Pieces, StandardSetValidatesAndHasTheNamedPieces) {
  const PieceSet set = standardPieces();
  ASSERT_EQ(set.size(), 6u);
  const std::map<std::string, std::size_t> leafRims{{"I", 1},      {"Y", 2},   {"Psi", 3},
                                                    {"Branch", 2}, {"Cap", 0}, {"Foot", 1}};
  for (const Piece& p : set.pieces) {
    SCOPED_TRACE(p.name);
    EXPECT_NO_THROW(validatePiece(p, "test"));
    EXPECT_EQ(p.leafRims(), leafRims.at(p.name));
    EXPECT_EQ(p.tileClass.size(), p.quads.size());
  }
}

TEST(Pieces, TheCapTapersToAPointWithoutABulge) {
  // Twig tips close to a point (issue 29: at most 5 % of the base radius), not in a rounded stub.
  // Samples the Phong-tessellated surface of every quad and takes the widest point in each band of height.
  const Piece cap = makeCap();
  constexpr int kBands = 20;
  std::array<float, kBands> widest{};
  float top = 0.0f;
  for (const auto& q : cap.quads) {
    std::array<glm::vec3, 4> p{};
    std::array<glm::vec3, 4> n{};
    for (std::size_t c = 0; c < 4; ++c) {
      p[c] = cap.vertices[q[c]].position;
      n[c] = cap.vertices[q[c]].normal;
    }
    for (int i = 0; i <= 32; ++i) {
      for (int j = 0; j <= 32; ++j) {
        const glm::vec3 s = phongQuad(p, n, static_cast<float>(i) / 32.0f, static_cast<float>(j) / 32.0f);
        top = std::max(top, s.y);
        const int band = std::clamp(static_cast<int>(s.y / kCapLength * kBands), 0, kBands - 1);
        widest[static_cast<std::size_t>(band)] =
            std::max(widest[static_cast<std::size_t>(band)], glm::length(glm::vec2(s.x, s.z)));
      }
    }
  }
  EXPECT_NEAR(top, kCapLength, 1e-4f);
  EXPECT_GE(kCapLength, 3.0f); // a taper, not a dome (the old cap ended 1.85 radii up)
  // The last band, from 95 % of the length to the tip, is under 5 % of the rim's radius (1).
  EXPECT_LE(widest[kBands - 1], 0.05f);
  // Narrower all the way up (a little slack for the hexagon's corners between bands).
  for (int b = 1; b < kBands; ++b) {
    EXPECT_LE(widest[static_cast<std::size_t>(b)], widest[static_cast<std::size_t>(b - 1)] + 0.01f) << b;
  }
}

TEST(Pieces, QuadsFaceOutwardsAndCornersAreTheCanonicalConstants) {
  const Piece i = makeI();
  for (const auto& q : i.quads) {
    glm::vec3 c(0.0f);
    for (auto v : q) {
      c += i.vertices[v].position * 0.25f;
    }
    const glm::vec3 n = glm::cross(i.vertices[q[2]].position - i.vertices[q[0]].position,
                                   i.vertices[q[3]].position - i.vertices[q[1]].position);
    EXPECT_GT(glm::dot(n, glm::vec3(c.x, 0.0f, c.z)), 0.0f);
  }
  for (int k = 0; k < kRimCorners; ++k) {
    const glm::vec3 corner = rimCorner(k);
    EXPECT_EQ(std::memcmp(&i.vertices[i.rims[0].vertices[static_cast<std::size_t>(k)]].position, &corner, 12),
              0);
    EXPECT_NEAR(glm::length(rimNormal(k)), 1.0f, 1e-6f);
  }
  EXPECT_EQ(rimCorner(0), glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(rimCorner(3), glm::vec3(-1.0f, 0.0f, 0.0f));
}

TEST(Pieces, RimRotationMapsCornersOntoCorners) {
  for (int s = 0; s < 6; ++s) {
    for (int k = 0; k < 6; ++k) {
      const glm::vec3 p = glm::vec3(rimRotation(s) * glm::vec4(rimCorner(k), 1.0f));
      EXPECT_NEAR(glm::length(p - rimCorner(k + s)), 0.0f, 1e-6f) << s << " " << k;
    }
  }
}

TEST(Pieces, ValidationNamesTheBrokenRim) {
  Piece y = makeY();
  y.vertices[y.rims[2].vertices[3]].position += glm::vec3(0.0f, 0.01f, 0.0f);
  try {
    validatePiece(y, "broken.gltf");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.gltf: piece 'Y': leaf rim 2 is not a regular hexagon"),
              std::string::npos)
        << e.what();
  }
  Piece wrongNormal = makeI();
  wrongNormal.vertices[wrongNormal.rims[1].vertices[0]].normal = glm::vec3(1.0f, 0.0f, 0.0f);
  EXPECT_THROW(validatePiece(wrongNormal, "x"), Error);
  Piece noRoot = makeI();
  noRoot.rims.clear();
  noRoot.joints.clear();
  EXPECT_THROW(validatePiece(noRoot, "x"), Error);
}

/** World positions of every rim corner of every node of a tree, computed as the shader does: frame · corner.
 */
TEST(Assembly, ChildRootRimsMeetParentLeafRimsBitForBit) {
  const PieceSet pieces = standardPieces();
  for (const std::string& name : speciesPresetNames()) {
    SCOPED_TRACE(name);
    const Species species = speciesPreset(name);
    const TreeTopology tree = generateTree(pieces, species, 7);
    EXPECT_NO_THROW(validate(tree, pieces, "generated"));
    std::vector<glm::mat4> frames;
    const std::vector<glm::vec2> pose = randomPose(tree, species, 3);
    jointFrames(pieces, tree, baseFrame({1.0f, 2.0f, 3.0f}, 0.7f, 0.2f), pose, frames);
    for (std::size_t n = 1; n < tree.nodes.size(); ++n) {
      const TreeNode& node = tree.nodes[n];
      // The child's root rim corner k sits at canonical corner (k + rotation) of the shared joint frame; the
      // parent's leaf rim corner m at canonical corner m of the same frame: the same float operations.
      const glm::mat4& shared = frames[node.rootJoint];
      for (int k = 0; k < 6; ++k) {
        const glm::vec4 child = shared * glm::vec4(rimCorner((k + node.rotation) % 6), 1.0f);
        const glm::vec4 parent = shared * glm::vec4(rimCorner((k + node.rotation) % 6), 1.0f);
        EXPECT_EQ(std::memcmp(&child, &parent, sizeof child), 0);
      }
      // And the child's rotated model agrees with the canonical corners to float precision.
      const glm::mat4 placed = shared * rimRotation(node.rotation);
      for (int k = 0; k < 6; ++k) {
        const glm::vec3 a(placed * glm::vec4(rimCorner(k), 1.0f));
        const glm::vec3 b(shared * glm::vec4(rimCorner(k + node.rotation), 1.0f));
        EXPECT_LT(glm::length(a - b), 1e-5f);
      }
    }
  }
}

TEST(Assembly, GenerationIsDeterministicAndSeedsDiffer) {
  const PieceSet pieces = standardPieces();
  const Species s = speciesPreset("almond");
  const TreeTopology a = generateTree(pieces, s, 42);
  const TreeTopology b = generateTree(pieces, s, 42);
  const TreeTopology c = generateTree(pieces, s, 43);
  EXPECT_EQ(toJson(a, pieces), toJson(b, pieces));
  EXPECT_NE(toJson(a, pieces), toJson(c, pieces));
  EXPECT_EQ(a.nodes[0].piece, pieces.find("Foot"));
}

TEST(Assembly, PaperRulesAlternateAndChooseUniformly) {
  const PieceSet pieces = standardPieces();
  const TreeTopology alt = generateTree(pieces, speciesPreset("paper-alternate"), 1);
  for (const TreeNode& n : alt.nodes) {
    const std::string& name = pieces[static_cast<std::size_t>(n.piece)].name;
    if (n.depth > 0 && name != "Cap") {
      EXPECT_EQ(name, n.depth % 2 == 0 ? "Y" : "I") << n.depth;
    }
  }
  const TreeTopology uni = generateTree(pieces, speciesPreset("paper-random"), 1);
  const TreeStats stats = treeStats(pieces, uni);
  EXPECT_GT(stats.piecesByType[static_cast<std::size_t>(pieces.find("I"))], 0u);
  EXPECT_GT(stats.piecesByType[static_cast<std::size_t>(pieces.find("Y"))], 0u);
}

TEST(Assembly, TreeJsonRoundTripsAndRejectsBadFiles) {
  const PieceSet pieces = standardPieces();
  const TreeTopology a = generateTree(pieces, speciesPreset("california-black-oak"), 5);
  const TreeTopology b = treeFromJson(toJson(a, pieces), pieces, "t.json");
  EXPECT_EQ(toJson(a, pieces), toJson(b, pieces));
  EXPECT_EQ(a.jointScale, b.jointScale);
  auto expectError = [&](nlohmann::json j, const std::string& part) {
    try {
      treeFromJson(j, pieces, "t.json");
      ADD_FAILURE() << "no error for " << part;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  nlohmann::json j = toJson(a, pieces);
  j["nodes"][1]["piece"] = "Q";
  expectError(j, "unknown piece 'Q'");
  j = toJson(a, pieces);
  j["nodes"][1]["rotation"] = 6;
  expectError(j, "/nodes/1/rotation: 6 is more than 5");
  j = toJson(a, pieces);
  j["nodes"].erase(j["nodes"].size() - 1);
  expectError(j, "is open");
  j = toJson(a, pieces);
  j["nodes"][2]["scale"] = std::nan("");
  expectError(j, "/nodes/2/scale");
  j = toJson(a, pieces);
  j["extra"] = 1;
  expectError(j, "/extra: unknown field");
  // The root is the Foot: a trunk of I pieces standing on nothing is refused, by the loader and by validate.
  j = toJson(a, pieces);
  j["nodes"][0]["piece"] = "I";
  expectError(j, "t.json: /nodes/0/piece: the root is always a Foot (the trunk's base), not 'I'");
  TreeTopology rootless = a;
  rootless.nodes[0].piece = pieces.find("Y");
  try {
    validate(rootless, pieces, "t.json");
    ADD_FAILURE() << "validate accepted a Y root";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nodes/0/piece: the root is always a Foot"), std::string::npos)
        << e.what();
  }
  // A chain deeper than the recursion limit.
  nlohmann::json deep{{"version", 1}, {"nodes", nlohmann::json::array({{{"piece", "Foot"}}})}};
  for (int i = 1; i < 70; ++i) {
    deep["nodes"].push_back({{"piece", "I"}, {"parent", i - 1}, {"rim", 1}});
  }
  expectError(deep, "recursion limit");
}

TEST(Assembly, StretchedSegmentsAreLongerNotThickerAndRoundTrip) {
  // The oak's segments are stretched: each stretched node's leaf joints sit `stretch` times as far up its
  // axis as the piece models them, at the same radius, and the stretch survives tree JSON.
  const PieceSet pieces = standardPieces();
  const Species species = speciesPreset("california-black-oak");
  const TreeTopology tree = generateTree(pieces, species, 5);
  std::vector<glm::mat4> frames;
  jointFrames(pieces, tree, glm::mat4(1.0f), {}, frames);
  int stretched = 0;
  for (const TreeNode& node : tree.nodes) {
    const Piece& piece = pieces[static_cast<std::size_t>(node.piece)];
    if (node.stretch == 1.0f || piece.leafRims() == 0) {
      continue;
    }
    ++stretched;
    EXPECT_GE(node.stretch, kMinStretch);
    EXPECT_LE(node.stretch, kMaxStretch);
    const glm::mat4 root = frames[node.rootJoint] * rimRotation(node.rotation);
    const float scale = glm::length(glm::vec3(root[0]));
    for (std::size_t r = 1; r <= piece.leafRims(); ++r) {
      const glm::mat4& leaf = frames[node.jointBase + r - 1];
      const glm::vec3 local = glm::vec3(glm::inverse(root) * leaf[3]);
      const glm::vec3 modelled(piece.joints[r].bind[3]);
      EXPECT_NEAR(local.y, modelled.y * node.stretch, 1e-3f * std::abs(modelled.y * node.stretch));
      EXPECT_NEAR(local.x, modelled.x, 1e-3f);
      EXPECT_NEAR(local.z, modelled.z, 1e-3f);
      // Not thicker: the leaf rim's radius is the piece's own (bone scales aside).
      EXPECT_NEAR(glm::length(glm::vec3(leaf[0])) / scale,
                  glm::length(glm::vec3(piece.joints[r].bind[0])) * tree.jointScale[node.jointBase + r - 1],
                  1e-4f);
    }
  }
  EXPECT_GT(stretched, 10);
  const TreeTopology back = treeFromJson(toJson(tree, pieces), pieces, "t.json");
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    EXPECT_EQ(back.nodes[n].stretch, tree.nodes[n].stretch) << n;
  }
  nlohmann::json j = toJson(tree, pieces);
  j["nodes"][1]["stretch"] = 40;
  try {
    treeFromJson(j, pieces, "t.json");
    ADD_FAILURE() << "a stretch of 40 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nodes/1/stretch"), std::string::npos) << e.what();
  }
  TreeTopology bad = tree;
  bad.nodes[3].stretch = 0.1f;
  EXPECT_THROW(validate(bad, pieces, "t.json"), Error);
}

TEST(Assembly, ThinSideBranchesKeepTheCrossSection) {
  // sideRadius: at every Branch piece of the poplar's trunk the side branch has sideRadius of the stem's
  // radius and the stem keeps the rest of the cross-section (r_stem² + r_side² = r²: the pipe model).
  const PieceSet pieces = standardPieces();
  const Species species = speciesPreset("lombardy-poplar");
  const float side = species.order(0).sideRadius;
  ASSERT_GT(side, 0.0f);
  const TreeTopology tree = generateTree(pieces, species, 2);
  std::vector<glm::mat4> frames;
  jointFrames(pieces, tree, glm::mat4(1.0f), {}, frames);
  auto radius = [&](std::uint32_t j) { return glm::length(glm::vec3(frames[j][0])); };
  int checked = 0;
  for (const TreeNode& node : tree.nodes) {
    if (node.piece != pieces.find("Branch") || node.order != 0) {
      continue;
    }
    const float r = radius(node.rootJoint);
    const float stem = radius(node.jointBase);
    const float branch = radius(node.jointBase + 1);
    EXPECT_NEAR(branch / r, side, 1e-4f);
    EXPECT_NEAR(stem * stem + branch * branch, r * r, 1e-4f * r * r);
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST(Species, PresetsValidateAndJsonRoundTrips) {
  const std::vector<std::string> names = speciesPresetNames();
  EXPECT_GE(names.size(), 10u);
  for (const std::string& n : names) {
    const Species s = speciesPreset(n);
    const Species back = speciesFromJson(toJson(s), n + ".json");
    EXPECT_EQ(toJson(s), toJson(back));
  }
  nlohmann::json bad = toJson(speciesPreset("almond"));
  bad["orders"][0]["fork"] = 0.9;
  bad["orders"][0]["sideBranch"] = 0.9;
  EXPECT_THROW(speciesFromJson(bad, "bad.json"), Error);
  EXPECT_THROW(speciesPreset("baobab"), Error);
}

TEST(Species, SpruceBranchesGrowInWhorls) {
  // The spruce's trunk carries its side branches in whorls of three: three Branch pieces in a row, short,
  // each turned two rim steps (120°) from the last, so the three branches leave at one height all round;
  // then an internode of I pieces. Other presets have no whorls.
  const PieceSet pieces = standardPieces();
  const int branch = pieces.find("Branch");
  const int i = pieces.find("I");
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE(seed);
    const TreeTopology tree = generateTree(pieces, speciesPreset("norway-spruce"), seed);
    // Walk the trunk: from the foot, always the stem's rim (rim 1).
    std::vector<int> trunk;
    int node = 0;
    for (;;) {
      int next = -1;
      for (std::size_t c = 0; c < tree.nodes.size(); ++c) {
        if (tree.nodes[c].parent == node && tree.nodes[c].parentRim == 1 && tree.nodes[c].order == 0) {
          next = static_cast<int>(c);
        }
      }
      if (next < 0) {
        break;
      }
      trunk.push_back(next);
      node = next;
    }
    int whorls = 0;
    for (std::size_t k = 0; k + 3 < trunk.size(); ++k) {
      const TreeNode& a = tree.nodes[static_cast<std::size_t>(trunk[k])];
      if (a.piece != branch ||
          (k > 0 && tree.nodes[static_cast<std::size_t>(trunk[k - 1])].piece == branch)) {
        continue;
      }
      // A whorl starts here: two more Branch pieces turned 120°, all short, then an I.
      const TreeNode& b = tree.nodes[static_cast<std::size_t>(trunk[k + 1])];
      const TreeNode& c = tree.nodes[static_cast<std::size_t>(trunk[k + 2])];
      const TreeNode& d = tree.nodes[static_cast<std::size_t>(trunk[k + 3])];
      EXPECT_EQ(b.piece, branch);
      EXPECT_EQ(c.piece, branch);
      EXPECT_EQ(b.rotation, 2);
      EXPECT_EQ(c.rotation, 2);
      EXPECT_EQ(a.stretch, kMinStretch);
      EXPECT_EQ(c.stretch, kMinStretch);
      EXPECT_EQ(d.piece, i);
      ++whorls;
    }
    EXPECT_GE(whorls, 8) << "of " << trunk.size() << " trunk pieces";
  }
  for (const std::string& n : realSpeciesPresetNames()) {
    const Species s = speciesPreset(n);
    for (const OrderParams& o : s.orders) {
      EXPECT_TRUE(o.whorl == 0 || n == "norway-spruce") << n;
    }
  }
  nlohmann::json j = toJson(speciesPreset("norway-spruce"));
  EXPECT_EQ(j["orders"][0]["whorl"], 3);
  j["orders"][0]["whorl"] = 7;
  EXPECT_THROW((void)speciesFromJson(j, "spruce.json"), Error);
}

TEST(Species, DeciduousLeavesFallAndEvergreensKeepTheirs) {
  const Species oak = speciesPreset("california-black-oak");
  const Species spruce = speciesPreset("norway-spruce");
  EXPECT_FALSE(oak.evergreen);
  EXPECT_FALSE(speciesPreset("european-larch").evergreen) << "the larch drops its needles";
  EXPECT_TRUE(spruce.evergreen);
  EXPECT_FLOAT_EQ(seasonalLeafDensity(oak, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(seasonalLeafDensity(oak, 0.25f), 0.75f);
  EXPECT_FLOAT_EQ(seasonalLeafDensity(oak, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(seasonalLeafDensity(oak, 5.0f), 0.0f); // clamped
  EXPECT_FLOAT_EQ(seasonalLeafDensity(spruce, 1.0f), 1.0f);
  Species sparse = oak;
  sparse.leafDensity = 0.5f;
  EXPECT_FLOAT_EQ(seasonalLeafDensity(sparse, 0.5f), 0.25f);
  // Species JSON carries both; a density out of range names the field.
  nlohmann::json j = toJson(spruce);
  EXPECT_EQ(j["evergreen"], true);
  j["leafDensity"] = 0.6;
  EXPECT_FLOAT_EQ(speciesFromJson(j, "spruce.json").leafDensity, 0.6f);
  j["leafDensity"] = 1.5;
  try {
    (void)speciesFromJson(j, "dense.json");
    ADD_FAILURE() << "a leaf density over 1 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("leafDensity"), std::string::npos) << e.what();
  }
}

TEST(Species, ConifersCarryNeedles) {
  // The larch is a conifer: needle sprays, not broad-leaf clusters; the broad-leaved presets keep leaves.
  EXPECT_EQ(speciesPreset("european-larch").foliage, FoliageKind::Needles);
  EXPECT_EQ(speciesPreset("norway-spruce").foliage, FoliageKind::Needles);
  EXPECT_EQ(speciesPreset("california-black-oak").foliage, FoliageKind::Broadleaf);
  nlohmann::json j = toJson(speciesPreset("almond"));
  EXPECT_EQ(j["foliage"], "broadleaf");
  j["foliage"] = "needles";
  EXPECT_EQ(speciesFromJson(j, "fir.json").foliage, FoliageKind::Needles);
  j["foliage"] = "scales";
  try {
    (void)speciesFromJson(j, "cypress.json");
    ADD_FAILURE() << "an unknown foliage kind was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("foliage"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cypress.json"), std::string::npos) << e.what();
  }
}

TEST(Species, LeavesTurnToTheirAutumnColour) {
  // Every real species has its own autumn colour, warmer than its summer green (red over green rises: the
  // tupelo turns scarlet, the birch and the aspen yellow), and the season blends linearly between them.
  int evergreen = 0;
  for (const std::string& n : realSpeciesPresetNames()) {
    SCOPED_TRACE(n);
    const Species s = speciesPreset(n);
    const glm::vec3 summer = seasonalLeafColour(s, 0.0f);
    const glm::vec3 autumn = seasonalLeafColour(s, 1.0f);
    EXPECT_EQ(summer, s.leafColour);
    EXPECT_EQ(autumn, s.autumnColour);
    if (s.autumnColour == s.leafColour) {
      // Evergreen: only a conifer keeps its colour (the spruce); the larch, a conifer too, turns golden.
      EXPECT_EQ(s.foliage, FoliageKind::Needles);
      ++evergreen;
      continue;
    }
    EXPECT_GT(autumn.r / autumn.g, 1.0f);
    EXPECT_LT(summer.r / summer.g, 1.0f);
    const glm::vec3 half = seasonalLeafColour(s, 0.5f);
    EXPECT_NEAR(half.r, 0.5f * (summer.r + autumn.r), 1e-6f);
    EXPECT_EQ(seasonalLeafColour(s, 3.0f), autumn); // clamped
  }
  EXPECT_EQ(evergreen, 1);
  EXPECT_GT(speciesPreset("black-tupelo").autumnColour.r / speciesPreset("black-tupelo").autumnColour.g,
            4.0f);
  // A species file may give its own; a bad one names the field.
  nlohmann::json j = toJson(speciesPreset("almond"));
  j["autumnColour"] = {0.9, 0.1, 0.05};
  EXPECT_EQ(speciesFromJson(j, "red.json").autumnColour, glm::vec3(0.9f, 0.1f, 0.05f));
  j["autumnColour"] = {0.9, 0.1};
  try {
    (void)speciesFromJson(j, "bad.json");
    ADD_FAILURE() << "a two-number colour was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("autumnColour"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace sylva::trees

#include <sylva/trees/Tessellation.hpp>

namespace sylva::trees {
namespace {

TEST(Tessellation, NoPieceFoldsAtAnyLevel) {
  // A fold (a tessellated triangle facing against the surface normal) would show the inside through the
  // surface at high levels, whatever the rims do.
  for (const Piece& p : standardPieces().pieces) {
    for (int level : {1, 2, 4, 8, 16, 32, 64}) {
      EXPECT_EQ(countFolds(p, level), 0) << p.name << " at level " << level;
    }
  }
}

TEST(Tessellation, EdgesDependOnlyOnTheirTwoCorners) {
  const std::array<glm::vec3, 4> p{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0.3f),
                                   glm::vec3(0, 1, 0)};
  const std::array<glm::vec3, 4> n{glm::normalize(glm::vec3(0, -0.2f, 1)),
                                   glm::normalize(glm::vec3(0.3f, 0, 1)), glm::vec3(0, 0, 1),
                                   glm::normalize(glm::vec3(-0.4f, 0.1f, 1))};
  std::array<glm::vec3, 4> other = p;
  other[2] = glm::vec3(5, 7, -3);
  other[3] = glm::vec3(-2, 4, 9);
  for (float u : {0.0f, 0.25f, 0.5f, 0.875f, 1.0f}) {
    EXPECT_EQ(phongQuad(p, n, u, 0.0f), phongQuad(other, n, u, 0.0f));
  }
  // Phong bulges a curved edge outwards: the midpoint leaves the chord.
  EXPECT_GT(glm::length(phongQuad(p, n, 0.5f, 0.0f) - 0.5f * (p[0] + p[1])), 1e-3f);
}

TEST(Tessellation, QuadVerticesFollowFractionalOddSpacing) {
  // Levels round up to an odd segment count (at most 63); a quad has (segments + 1)² vertices.
  EXPECT_EQ(quadVertices(1.0f), 4u);
  EXPECT_EQ(quadVertices(1.5f), 16u);
  EXPECT_EQ(quadVertices(3.0f), 16u);
  EXPECT_EQ(quadVertices(3.01f), 36u);
  EXPECT_EQ(quadVertices(16.0f), 18u * 18u);
  EXPECT_EQ(quadVertices(63.0f), 64u * 64u);
  EXPECT_EQ(quadVertices(64.0f), 64u * 64u);
  EXPECT_EQ(quadVertices(1000.0f), 64u * 64u);
  EXPECT_EQ(quadVertices(0.0f), 4u);
  EXPECT_EQ(quadVertices(-3.0f), 4u);
  EXPECT_EQ(quadVertices(std::numeric_limits<float>::quiet_NaN()), 4u);
}

TEST(Tessellation, CommandsStayWithinTheVertexBudgetAtEveryLevel) {
  // The default largest level keeps the full chunk; the finest level draws one quad per command.
  EXPECT_EQ(quadsPerCommand(16.0f), kMaxQuadsPerCommand);
  EXPECT_EQ(quadsPerCommand(32.0f), 4u);
  EXPECT_EQ(quadsPerCommand(64.0f), 1u);
  std::uint32_t previous = kMaxQuadsPerCommand;
  for (float level = 0.5f; level <= 70.0f; level += 0.25f) {
    const std::uint32_t q = quadsPerCommand(level);
    ASSERT_GE(q, 1u) << level;
    ASSERT_LE(q, previous) << level << ": finer levels never get larger chunks";
    // Within the budget (one quad may exceed it only when a single quad does), and always within the 16-bit
    // vertex numbering of Mesa's draw module.
    ASSERT_TRUE(q * quadVertices(level) <= kVerticesPerCommand || q == 1) << level;
    ASSERT_LT(q * quadVertices(level), 65536u) << level;
    previous = q;
  }
}

} // namespace
} // namespace sylva::trees

#include <sylva/trees/Forest.hpp>

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace sylva::trees {
namespace {

TEST(SizeCulling, TermsTurnPixelsIntoMetresForBothProjections) {
  // Perspective: 720 pixels over a 45° field of view is a focal length of 720 / (2 tan 22.5°) pixels, so one
  // pixel at distance d spans d / focal metres.
  const float focal = 720.0f / (2.0f * std::tan(glm::radians(22.5f)));
  const glm::vec2 perspective = sizeCullTerms(glm::radians(45.0f), 0.0f, 720, 1.0f);
  EXPECT_NEAR(perspective.x, 1.0f / focal, 1e-7f);
  EXPECT_EQ(perspective.y, 0.0f);
  EXPECT_NEAR(sizeCullTerms(glm::radians(45.0f), 0.0f, 720, 3.0f).x, 3.0f / focal, 1e-7f);
  // Orthographic (a shadow cascade): ±10 m over 1,000 texels is 0.02 m a texel, whatever the distance.
  const glm::vec2 ortho = sizeCullTerms(glm::radians(45.0f), 10.0f, 1000, 1.0f);
  EXPECT_EQ(ortho.x, 0.0f);
  EXPECT_NEAR(ortho.y, 0.02f, 1e-7f);
  // Off: no pixels asked for, or no target.
  EXPECT_EQ(sizeCullTerms(glm::radians(45.0f), 0.0f, 720, 0.0f), glm::vec2(0.0f));
  EXPECT_EQ(sizeCullTerms(glm::radians(45.0f), 10.0f, 0, 1.0f), glm::vec2(0.0f));
}

TEST(SizeCulling, WidthCullingDropsThinBranchesWhoseSpheresStillSpanPixels) {
  // One birch (long, thin, stretched twigs) seen from 40 m: the sphere rule keeps twigs whose length spans
  // pixels; the width rule drops exactly the pieces whose root rim (2 · frame scale) is under the width.
  const Forest forest = gridForest({"silver-birch"}, 1, 1.0f, 3);
  const PackedInstances packed = packInstances(forest);
  std::vector<gpu::JointFrame> frames;
  forestFrames(forest, {}, frames);
  std::vector<gpu::TreePieceGpu> table;
  for (const Piece& p : forest.pieces.pieces) {
    table.push_back(pieceTableEntry(p));
  }
  const glm::vec3 camera(0.0f, 8.0f, 40.0f);
  std::array<glm::vec4, 6> planes{};
  planes.fill(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)); // every point inside
  const glm::vec2 onePixel = sizeCullTerms(glm::radians(50.0f), 0.0f, 720, 1.0f);
  auto count = [](const std::vector<std::vector<std::uint32_t>>& lists) {
    std::size_t n = 0;
    for (const auto& l : lists) {
      n += l.size();
    }
    return n;
  };
  const auto sphere = cullInstances(packed, table, frames, planes, camera, 0.0f, 1.25f, onePixel);
  const auto width = cullInstances(packed, table, frames, planes, camera, 0.0f, 1.25f, onePixel, onePixel);
  EXPECT_LT(count(width), count(sphere) * 3 / 4);
  EXPECT_GT(count(width), 0u);
  for (std::size_t t = 0; t < width.size(); ++t) {
    for (std::uint32_t i : sphere[t]) {
      const gpu::JointFrame& root = frames[packed.instances[i].joints.x];
      const float scale = glm::length(glm::vec3(root.x.x, root.y.x, root.z.x));
      const bool kept = std::binary_search(width[t].begin(), width[t].end(), i);
      // Wide pieces (2 · scale well over a pixel at their distance, at most 60 m) are always kept.
      if (2.0f * scale > onePixel.x * 60.0f) {
        EXPECT_TRUE(kept) << "instance " << i;
      }
      if (2.0f * scale < onePixel.x * 30.0f) {
        EXPECT_FALSE(kept) << "instance " << i;
      }
    }
  }
}

} // namespace
} // namespace sylva::trees

// Artist pieces through Assimp: every built-in piece goes out as OBJ and glTF and comes back identical
// (vertices, quads in order, rims and their frames, weights and normals), and bad files fail with one line
// naming the file and the rim at fault.
#include "TempDir.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/trees/Import.hpp>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace sylva::trees {
namespace {

namespace fs = std::filesystem;

/** For each vertex of `b`, the vertex of `a` at the same position (within 1e-5), or a test failure. */
std::vector<std::uint32_t> matchVertices(const Piece& a, const Piece& b) {
  std::vector<std::uint32_t> map(b.vertices.size(), 0);
  std::vector<bool> taken(a.vertices.size(), false);
  for (std::size_t i = 0; i < b.vertices.size(); ++i) {
    float best = std::numeric_limits<float>::infinity();
    for (std::size_t j = 0; j < a.vertices.size(); ++j) {
      const float d = glm::length(a.vertices[j].position - b.vertices[i].position);
      if (d < best) {
        best = d;
        map[i] = static_cast<std::uint32_t>(j);
      }
    }
    EXPECT_LT(best, 1e-5f) << "vertex " << i;
    EXPECT_FALSE(taken[map[i]]) << "two vertices at one position";
    taken[map[i]] = true;
  }
  return map;
}

void expectNear(const glm::mat4& a, const glm::mat4& b, float tolerance, const std::string& what) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      EXPECT_NEAR(a[c][r], b[c][r], tolerance) << what << " [" << c << "][" << r << "]";
    }
  }
}

/** Distance of `p` from the segment between the root rim's centre and leaf rim `r`'s (as skinning measures).
 */
float distanceToLeaf(const Piece& piece, const glm::vec3& p, std::size_t r) {
  const glm::vec3 b(piece.rims[r].frame[3]);
  const float t = std::clamp(glm::dot(p, b) / glm::dot(b, b), 0.0f, 1.0f);
  return glm::length(p - b * t);
}

/**
 * The imported piece is the original up to the order of its vertices. With `exactFrames` false (OBJ: frames
 * refitted from the corners, equal to ~1e-7), a vertex equally near two leaf rims may be bound to either.
 */
void expectSamePiece(const Piece& original, const Piece& imported, bool exactFrames) {
  EXPECT_EQ(imported.name, original.name);
  EXPECT_EQ(imported.bearsFoliage, original.bearsFoliage);
  ASSERT_EQ(imported.vertices.size(), original.vertices.size());
  ASSERT_EQ(imported.quads.size(), original.quads.size());
  ASSERT_EQ(imported.rims.size(), original.rims.size());
  ASSERT_EQ(imported.joints.size(), original.joints.size());
  const std::vector<std::uint32_t> map = matchVertices(original, imported);
  // Quad i is quad i (stable ids), corners in the same order.
  for (std::size_t q = 0; q < original.quads.size(); ++q) {
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(map[imported.quads[q][k]], original.quads[q][k]) << "quad " << q << " corner " << k;
    }
  }
  for (std::size_t r = 0; r < original.rims.size(); ++r) {
    expectNear(imported.rims[r].frame, original.rims[r].frame, 1e-5f, "rim " + std::to_string(r));
    if (exactFrames) {
      EXPECT_EQ(imported.rims[r].frame, original.rims[r].frame) << "rim " << r;
    }
    expectNear(imported.joints[r].bind, original.joints[r].bind, 1e-5f, "joint " + std::to_string(r));
    for (std::size_t k = 0; k < kRimCorners; ++k) {
      EXPECT_EQ(map[imported.rims[r].vertices[k]], original.rims[r].vertices[k])
          << "rim " << r << " corner " << k;
    }
  }
  for (std::size_t i = 0; i < imported.vertices.size(); ++i) {
    const PieceVertex& a = imported.vertices[i];
    const PieceVertex& b = original.vertices[map[i]];
    EXPECT_EQ(a.rim, b.rim) << i;
    EXPECT_EQ(a.corner, b.corner) << i;
    if (a.joints != b.joints && !exactFrames) {
      // A tie broken the other way by float noise: the same weights, and the two leaf rims equally near.
      EXPECT_EQ(a.joints[0], b.joints[0]) << i;
      EXPECT_NEAR(distanceToLeaf(original, b.position, a.joints[1]),
                  distanceToLeaf(original, b.position, b.joints[1]), 1e-5f)
          << i;
    } else {
      EXPECT_EQ(a.joints, b.joints) << i;
    }
    EXPECT_LT(glm::length(a.weights - b.weights), 1e-5f) << i;
    EXPECT_LT(glm::length(a.normal - b.normal), 1e-5f) << i;
    EXPECT_NEAR(a.u, b.u, 1e-5f) << i;
    EXPECT_NEAR(a.v, b.v, 1e-5f) << i;
  }
}

TEST(Import, EveryBuiltInPieceRoundTripsThroughObjAndGltf) {
  const test::TempDir dir;
  for (const Piece& piece : standardPieces().pieces) {
    for (const char* ext : {".obj", ".gltf"}) {
      SCOPED_TRACE(piece.name + ext);
      const fs::path file = dir / (piece.name + ext);
      if (std::string(ext) == ".obj") {
        exportPieceObj(piece, file);
      } else {
        exportPieceGltf(piece, file);
      }
      const Piece back = importPiece(file);
      expectSamePiece(piece, back, std::string(ext) == ".gltf");
      EXPECT_NO_THROW(validatePiece(back, file.filename().string()));
    }
  }
}

TEST(Import, TextureCoordinatesRoundTrip) {
  const test::TempDir dir;
  Piece y = makeY();
  for (std::size_t i = 0; i < y.vertices.size(); ++i) {
    y.vertices[i].u = 0.125f * static_cast<float>(i % 8);
    y.vertices[i].v = 0.25f * static_cast<float>(i);
  }
  for (const char* ext : {".obj", ".gltf"}) {
    SCOPED_TRACE(ext);
    const fs::path file = dir / (std::string("Y") + ext);
    if (std::string(ext) == ".obj") {
      exportPieceObj(y, file);
    } else {
      exportPieceGltf(y, file);
    }
    expectSamePiece(y, importPiece(file), std::string(ext) == ".gltf");
  }
}

TEST(Import, GltfIsValidJsonWithRimJointsAndTwoTrianglesPerQuad) {
  const test::TempDir dir;
  const Piece psi = makePsi();
  exportPieceGltf(psi, dir / "psi.gltf");
  const nlohmann::json gltf = loadJsonFile(dir / "psi.gltf");
  EXPECT_EQ(gltf["asset"]["version"], "2.0");
  std::vector<std::string> names;
  for (const auto& node : gltf["nodes"]) {
    names.push_back(node["name"]);
  }
  EXPECT_EQ(names,
            (std::vector<std::string>{"Psi", "piece", "rim_root", "rim_leaf_1", "rim_leaf_2", "rim_leaf_3"}));
  const auto& indices = gltf["accessors"][gltf["meshes"][0]["primitives"][0]["indices"].get<std::size_t>()];
  EXPECT_EQ(indices["count"].get<std::size_t>(), psi.quads.size() * 6);
  EXPECT_EQ(gltf["skins"][0]["joints"].size(), psi.rims.size() + 1);
}

/** The error importPiece() throws for `file`, or "(imported)". */
std::string importError(const fs::path& file, const ImportOptions& options = {}) {
  try {
    (void)importPiece(file, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "(imported)";
}

void expectError(const fs::path& file, const std::string& expected) {
  const std::string message = importError(file);
  EXPECT_NE(message.find(expected), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
  EXPECT_EQ(message.rfind(file.filename().string(), 0), 0u)
      << "does not start with the file name: " << message;
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(Import, DistortedHexagonNamesTheRimAndCorner) {
  const test::TempDir dir;
  Piece y = makeY();
  y.vertices[y.rims[2].vertices[3]].position += glm::vec3(0.12f, 0.0f, 0.0f);
  exportPieceObj(y, dir / "branch.obj");
  expectError(dir / "branch.obj", "branch.obj: leaf rim 2 is not a regular hexagon (corner 3 is ");
  exportPieceGltf(y, dir / "branch.gltf");
  expectError(dir / "branch.gltf", "branch.gltf: rim_leaf_2 is not a regular hexagon (corner 3 is ");
  // Within the tolerance the corner is snapped back onto the hexagon.
  Piece close = makeY();
  close.vertices[close.rims[2].vertices[3]].position += glm::vec3(2e-4f, 0.0f, 0.0f);
  exportPieceObj(close, dir / "close.obj");
  const Piece back = importPiece(dir / "close.obj");
  const glm::vec3 corner = back.vertices[back.rims[2].vertices[3]].position;
  EXPECT_LT(glm::length(corner - glm::vec3(back.rims[2].frame * glm::vec4(rimCorner(3), 1.0f))), 1e-6f);
}

TEST(Import, MissingRootRim) {
  const test::TempDir dir;
  Piece lifted = makeI();
  for (PieceVertex& v : lifted.vertices) {
    v.position.y += 0.5f;
  }
  exportPieceObj(lifted, dir / "lifted.obj");
  expectError(dir / "lifted.obj", "lifted.obj: missing root rim");
  // glTF: no joint named rim_root.
  exportPieceGltf(makeY(), dir / "piece.gltf");
  nlohmann::json gltf = loadJsonFile(dir / "piece.gltf");
  for (auto& node : gltf["nodes"]) {
    if (node["name"] == "rim_root") {
      node["name"] = "bottom";
    }
  }
  writeTextFile(dir / "piece.gltf", gltf.dump());
  expectError(dir / "piece.gltf", "piece.gltf: missing root rim");
}

TEST(Import, WrongNormalsNameTheRim) {
  const test::TempDir dir;
  // Flare the ring under leaf rim 1: its quads leave the fixed cone.
  Piece y = makeY();
  const glm::vec3 centre(y.rims[1].frame[3]);
  std::vector<bool> ring(y.vertices.size(), false);
  for (const auto& q : y.quads) {
    for (std::uint32_t v : q) {
      if (y.vertices[v].rim == 1) {
        for (std::uint32_t w : q) {
          ring[w] = y.vertices[w].rim < 0;
        }
      }
    }
  }
  for (std::size_t i = 0; i < y.vertices.size(); ++i) {
    if (ring[i]) {
      y.vertices[i].position = centre + (y.vertices[i].position - centre) * 1.4f;
    }
  }
  exportPieceGltf(y, dir / "piece.gltf");
  expectError(dir / "piece.gltf", "piece.gltf: rim_leaf_1: wrong normals");
  // Quads facing inwards.
  Piece inside = makeI();
  for (auto& q : inside.quads) {
    std::reverse(q.begin(), q.end());
  }
  exportPieceObj(inside, dir / "inside.obj");
  expectError(dir / "inside.obj", "inside.obj: root rim: wrong normals");
}

TEST(Import, TrianglesAndPolygonsAreNotQuadMeshes) {
  const test::TempDir dir;
  writeTextFile(dir / "x.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 5 3\n");
  expectError(dir / "x.obj", "x.obj: not a quad mesh (face 1 has 3 corners)");
  writeTextFile(dir / "ngon.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0 0\nf 1 2 3 4 5\n");
  expectError(dir / "ngon.obj", "ngon.obj: not a quad mesh (face 0 has 5 corners)");
  // glTF stores quad i as triangles 2i and 2i + 1: an odd triangle count cannot be quads.
  exportPieceGltf(makeCap(), dir / "cap.gltf");
  nlohmann::json gltf = loadJsonFile(dir / "cap.gltf");
  auto& indices = gltf["accessors"][gltf["meshes"][0]["primitives"][0]["indices"].get<std::size_t>()];
  indices["count"] = indices["count"].get<int>() - 3;
  writeTextFile(dir / "cap.gltf", gltf.dump());
  expectError(dir / "cap.gltf", "cap.gltf: not a quad mesh (");
}

TEST(Import, UnreadableFilesGiveOneLine) {
  const test::TempDir dir;
  exportPieceGltf(makeY(), dir / "full.gltf");
  const std::string text = readTextFile(dir / "full.gltf");
  writeBytes(dir / "truncated.gltf", text.substr(0, text.size() / 2));
  expectError(dir / "truncated.gltf", "truncated.gltf: cannot read the file: ");
  exportPieceObj(makeY(), dir / "full.obj");
  const std::string obj = readTextFile(dir / "full.obj");
  writeBytes(dir / "truncated.obj", obj.substr(0, obj.size() * 3 / 4));
  expectError(dir / "truncated.obj", "truncated.obj: ");

  std::mt19937 rng(7);
  std::string garbage(4096, '\0');
  for (char& c : garbage) {
    c = static_cast<char>(rng() & 0xff);
  }
  writeBytes(dir / "garbage.gltf", garbage);
  expectError(dir / "garbage.gltf", "garbage.gltf: cannot read the file: ");
  writeBytes(dir / "garbage.obj", garbage);
  expectError(dir / "garbage.obj", "garbage.obj: ");
  writeBytes(dir / "garbage.fbx", garbage);
  expectError(dir / "garbage.fbx", "garbage.fbx: ");
  expectError(dir / "absent.obj", "absent.obj: no such file");
}

TEST(Import, NanInObjIsRejected) {
  const test::TempDir dir;
  exportPieceObj(makeI(), dir / "good.obj");
  std::string obj = readTextFile(dir / "good.obj");
  const std::size_t at = obj.find("\nv ") + 1;
  obj.replace(at, obj.find('\n', at) - at, "v nan 0 0");
  writeTextFile(dir / "nan.obj", obj);
  expectError(dir / "nan.obj", "nan.obj: a vertex position is not finite");
}

TEST(Import, PieceSetReplacesBuiltInsAndAddsNewPieces) {
  const test::TempDir dir;
  Piece longI = makeI();
  exportPieceObj(longI, dir / "I.obj");
  exportPieceGltf(makeBranch(), dir / "Twig.gltf");
  const PieceSet set = loadPieceSet(dir.path());
  ASSERT_EQ(set.size(), 7u);
  EXPECT_EQ(set.find("I"), 0);
  EXPECT_EQ(set.find("Twig"), 6);
  EXPECT_EQ(set[6].leafRims(), 2u);
  // A replacement must keep the number of leaf rims the assembly rules rely on.
  exportPieceObj(makeY(), dir / "Cap.obj");
  try {
    (void)loadPieceSet(dir.path());
    FAIL() << "loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Cap.obj: replaces the built-in piece 'Cap', which has 0 leaf rims"),
              std::string::npos)
        << e.what();
  }
}

} // namespace
} // namespace sylva::trees

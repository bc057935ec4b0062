// Whole-tree export read back by independent readers: the glTF through tinygltf (joints = the tree's joints
// in its hierarchy, inverse bind matrices inverting the joints' world transforms, weights summing to 1, LOD
// vertex counts growing with the level, bounds equal to the CPU's skinned rest pose, the skin reproducing a
// bent pose, atlases, impostor and wind extras) and the OBJ through Assimp (vertex and face counts, every
// face corner where the mesh has it). Failed exports throw one line naming the file and leave nothing behind.
#include "TempDir.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/trees/Export.hpp>
#include <sylva/trees/JointWind.hpp>
#include <sylva/trees/Skeleton.hpp>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace sylva::trees {
namespace {

namespace fs = std::filesystem;

struct Fixture {
  PieceSet pieces = standardPieces();
  Species species;
  TreeTopology tree;

  Fixture(const std::string& name, std::uint64_t seed) : species(speciesPreset(name)) {
    tree = generateTree(pieces, species, seed);
  }
};

tinygltf::Model load(const fs::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err;
  std::string warn;
  const bool ok = path.extension() == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                                             : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  EXPECT_TRUE(ok) << err;
  EXPECT_TRUE(err.empty()) << err;
  return model;
}

/** Element `i` of accessor `a` as `n` floats (float or unsigned short components). */
std::vector<double> element(const tinygltf::Model& m, int a, std::size_t i) {
  const tinygltf::Accessor& acc = m.accessors.at(static_cast<std::size_t>(a));
  const tinygltf::BufferView& view = m.bufferViews.at(static_cast<std::size_t>(acc.bufferView));
  const tinygltf::Buffer& buffer = m.buffers.at(static_cast<std::size_t>(view.buffer));
  const int n = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(acc.type));
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(acc.componentType));
  const std::size_t stride = view.byteStride ? view.byteStride : static_cast<std::size_t>(n * size);
  const std::uint8_t* p = buffer.data.data() + view.byteOffset + acc.byteOffset + i * stride;
  std::vector<double> out(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    if (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
      float f = 0.0f;
      std::memcpy(&f, p + k * 4, 4);
      out[static_cast<std::size_t>(k)] = f;
    } else if (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      std::uint16_t u = 0;
      std::memcpy(&u, p + k * 2, 2);
      out[static_cast<std::size_t>(k)] = u;
    } else if (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      std::uint32_t u = 0;
      std::memcpy(&u, p + k * 4, 4);
      out[static_cast<std::size_t>(k)] = u;
    } else {
      ADD_FAILURE() << "unexpected component type " << acc.componentType;
    }
  }
  return out;
}

glm::dmat4 nodeMatrix(const tinygltf::Node& node) {
  if (!node.matrix.empty()) {
    glm::dmat4 m(1.0);
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) {
        m[c][r] = node.matrix[static_cast<std::size_t>(c * 4 + r)];
      }
    }
    return m;
  }
  glm::dmat4 m(1.0);
  if (!node.rotation.empty()) {
    m = glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
  }
  if (!node.scale.empty()) {
    m[0] *= node.scale[0];
    m[1] *= node.scale[1];
    m[2] *= node.scale[2];
  }
  if (!node.translation.empty()) {
    m[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
  }
  return m;
}

/** World transform of every node (parents from the children lists). */
std::vector<glm::dmat4> worldTransforms(const tinygltf::Model& m, std::vector<int>& parent) {
  parent.assign(m.nodes.size(), -1);
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    for (int c : m.nodes[n].children) {
      parent[static_cast<std::size_t>(c)] = static_cast<int>(n);
    }
  }
  std::vector<glm::dmat4> world(m.nodes.size());
  std::vector<bool> done(m.nodes.size(), false);
  auto compute = [&](auto&& self, std::size_t n) -> glm::dmat4 {
    if (!done[n]) {
      const glm::dmat4 local = nodeMatrix(m.nodes[n]);
      world[n] = parent[n] < 0 ? local : self(self, static_cast<std::size_t>(parent[n])) * local;
      done[n] = true;
    }
    return world[n];
  };
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    compute(compute, n);
  }
  return world;
}

/**
 * The rest pose's skinned piece vertices (the tessellation's level-1 corners), computed here from the piece
 * data and jointFrames() as shaders/trees/piece.vert skins them: bounds in metres.
 */
Bounds skinnedBounds(const Fixture& f, const std::vector<glm::vec2>& pose) {
  std::vector<glm::mat4> frames;
  jointFrames(f.pieces, f.tree, baseFrame(glm::vec3(0.0f), 0.0f, f.species.trunkRadius), pose, frames);
  Bounds b{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
  for (const TreeNode& node : f.tree.nodes) {
    const Piece& piece = f.pieces[static_cast<std::size_t>(node.piece)];
    auto global = [&](std::size_t j) { return j == 0 ? node.rootJoint : node.jointBase + j - 1; };
    for (const PieceVertex& v : piece.vertices) {
      glm::vec3 p(0.0f);
      if (v.rim >= 0) {
        const int c = v.rim == 0 ? (v.corner + node.rotation) % 6 : v.corner;
        p = glm::vec3(
            frames[global(static_cast<std::size_t>(piece.rims[static_cast<std::size_t>(v.rim)].joint))] *
            glm::vec4(rimCorner(c), 1.0f));
      } else {
        for (int k = 0; k < 4; ++k) {
          const std::size_t j = v.joints[static_cast<std::size_t>(k)];
          const glm::mat4 m = j == 0 ? frames[node.rootJoint] * rimRotation(node.rotation)
                                     : frames[global(j)] * glm::inverse(piece.joints[j].bind);
          p += v.weights[k] * glm::vec3(m * glm::vec4(v.position, 1.0f));
        }
      }
      b.min = glm::min(b.min, p);
      b.max = glm::max(b.max, p);
    }
  }
  return b;
}

int positionAccessor(const tinygltf::Model& m, std::size_t mesh) {
  return m.meshes.at(mesh).primitives.at(0).attributes.at("POSITION");
}

TEST(TreeExport, GltfSkinReadsBackThroughTinygltf) {
  const Fixture f("almond", 42);
  const test::TempDir dir;
  TreeExportOptions options;
  options.levels = {4, 2, 1};
  options.pose = randomPose(f.tree, f.species, 42);
  const TreeExportStats stats = exportTreeGltf(f.pieces, f.tree, f.species, dir / "almond.glb", options);
  const tinygltf::Model m = load(dir / "almond.glb");
  ASSERT_EQ(m.skins.size(), 1u);
  const tinygltf::Skin& skin = m.skins[0];
  const std::size_t joints = f.tree.jointCount();
  ASSERT_EQ(skin.joints.size(), joints);
  EXPECT_EQ(stats.joints, joints);

  // The joint hierarchy is the tree's, and the joints' world transforms are the rest pose's frames.
  std::vector<int> parent;
  const std::vector<glm::dmat4> world = worldTransforms(m, parent);
  std::vector<glm::mat4> frames;
  jointFrames(f.pieces, f.tree, baseFrame(glm::vec3(0.0f), 0.0f, f.species.trunkRadius), options.pose,
              frames);
  const double size = f.species.trunkRadius;
  for (std::size_t j = 0; j < joints; ++j) {
    const int node = skin.joints[j];
    const int expectedParent = f.tree.jointParent[j];
    EXPECT_EQ(parent[static_cast<std::size_t>(node)],
              expectedParent < 0 ? -1 : skin.joints[static_cast<std::size_t>(expectedParent)])
        << "joint " << j;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 3; ++r) {
        ASSERT_NEAR(world[static_cast<std::size_t>(node)][c][r], frames[j][c][r],
                    2e-5 * (c == 3 ? 10.0 : size))
            << "joint " << j << " column " << c << " row " << r;
      }
    }
    // Inverse bind matrices invert the joints' world transforms.
    const std::vector<double> ibm = element(m, skin.inverseBindMatrices, j);
    glm::dmat4 inverse(1.0);
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) {
        inverse[c][r] = ibm[static_cast<std::size_t>(c * 4 + r)];
      }
    }
    const glm::dmat4 product = world[static_cast<std::size_t>(node)] * inverse;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) {
        ASSERT_NEAR(product[c][r], c == r ? 1.0 : 0.0, 1e-5) << "joint " << j;
      }
    }
  }

  // One mesh per level, finer levels with more vertices; every vertex's weights sum to 1 on valid joints.
  ASSERT_EQ(m.meshes.size(), 3u);
  std::vector<std::size_t> counts;
  for (std::size_t l = 0; l < m.meshes.size(); ++l) {
    const tinygltf::Primitive& prim = m.meshes[l].primitives.at(0);
    const std::size_t n = m.accessors.at(static_cast<std::size_t>(prim.attributes.at("POSITION"))).count;
    counts.push_back(n);
    EXPECT_EQ(n, stats.vertices[l]);
    for (std::size_t i = 0; i < n; ++i) {
      const std::vector<double> w = element(m, prim.attributes.at("WEIGHTS_0"), i);
      const std::vector<double> jt = element(m, prim.attributes.at("JOINTS_0"), i);
      double sum = 0.0;
      for (std::size_t k = 0; k < 4; ++k) {
        ASSERT_GE(w[k], 0.0);
        ASSERT_LT(jt[k], static_cast<double>(joints));
        sum += w[k];
      }
      ASSERT_NEAR(sum, 1.0, 1e-6) << "LOD " << l << " vertex " << i;
    }
  }
  EXPECT_GT(counts[0], counts[1]);
  EXPECT_GT(counts[1], counts[2]);

  // Bounds: the coarsest LOD (level 1: the piece vertices) spans exactly the CPU-skinned rest pose; finer
  // levels only add Phong bulges between them (a few per cent of a trunk radius).
  const Bounds cpu = skinnedBounds(f, options.pose);
  const tinygltf::Accessor& coarse = m.accessors.at(static_cast<std::size_t>(positionAccessor(m, 2)));
  const tinygltf::Accessor& fine = m.accessors.at(static_cast<std::size_t>(positionAccessor(m, 0)));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(coarse.minValues[static_cast<std::size_t>(k)], cpu.min[k], 1e-5);
    EXPECT_NEAR(coarse.maxValues[static_cast<std::size_t>(k)], cpu.max[k], 1e-5);
    EXPECT_NEAR(fine.minValues[static_cast<std::size_t>(k)], cpu.min[k], 0.1 * f.species.trunkRadius);
    EXPECT_NEAR(fine.maxValues[static_cast<std::size_t>(k)], cpu.max[k], 0.1 * f.species.trunkRadius);
  }
  EXPECT_GT(cpu.max.y - cpu.min.y, 2.0f); // a tree, metres

  // The skin animates: bending joints moves rigidly bound vertices exactly as the renderer's skinning does.
  std::vector<glm::vec2> bent = options.pose;
  for (std::size_t j = 1; j < bent.size(); j += 3) {
    bent[j] += glm::vec2(0.2f, -0.1f);
  }
  std::vector<glm::mat4> bentFrames;
  jointFrames(f.pieces, f.tree, baseFrame(glm::vec3(0.0f), 0.0f, f.species.trunkRadius), bent, bentFrames);
  TreeExportOptions bentOptions = options;
  bentOptions.pose = bent;
  bentOptions.levels = {1};
  const TreeMesh expected = buildTreeMesh(f.pieces, f.tree, f.species, bentOptions);
  const tinygltf::Primitive& prim = m.meshes[2].primitives.at(0);
  ASSERT_EQ(expected.lods[0].positions.size(), counts[2]);
  std::size_t rigid = 0;
  for (std::size_t i = 0; i < counts[2]; ++i) {
    const std::vector<double> w = element(m, prim.attributes.at("WEIGHTS_0"), i);
    if (w[0] != 1.0) {
      continue;
    }
    const std::size_t j = static_cast<std::size_t>(element(m, prim.attributes.at("JOINTS_0"), i)[0]);
    const std::vector<double> p = element(m, prim.attributes.at("POSITION"), i);
    const std::vector<double> ibm = element(m, skin.inverseBindMatrices, j);
    glm::dmat4 inverse(1.0);
    for (int c = 0; c < 16; ++c) {
      inverse[c / 4][c % 4] = ibm[static_cast<std::size_t>(c)];
    }
    const glm::dvec4 skinned = glm::dmat4(bentFrames[j]) * inverse * glm::dvec4(p[0], p[1], p[2], 1.0);
    ASSERT_NEAR(glm::distance(glm::dvec3(skinned), glm::dvec3(expected.lods[0].positions[i])), 0.0, 1e-4)
        << "vertex " << i << " on joint " << j;
    ++rigid;
  }
  EXPECT_GT(rigid, counts[2] / 4);

  // Wind: every bending joint's spring as buildJointWindRest() computes it.
  JointWindTree windTree;
  windTree.topology = &f.tree;
  windTree.species = &f.species;
  windTree.base = frames[0];
  windTree.pose = options.pose;
  const JointWindRest rest = buildJointWindRest(f.pieces, std::span(&windTree, 1));
  std::size_t springs = 0;
  for (std::size_t j = 1; j < joints; ++j) {
    const tinygltf::Value& extras = m.nodes[static_cast<std::size_t>(skin.joints[j])].extras;
    ASSERT_TRUE(extras.Has("wind")) << "joint " << j;
    const tinygltf::Value& wind = extras.Get("wind");
    EXPECT_NEAR(wind.Get("frequencyHz").GetNumberAsDouble(), rest.springs[j].frequency, 1e-6);
    EXPECT_NEAR(wind.Get("dampingRatio").GetNumberAsDouble(), f.species.damping, 1e-6);
    ++springs;
  }
  EXPECT_EQ(springs, joints - 1);
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_NEAR(m.scenes[0].extras.Get("wind").Get("youngModulusPa").GetNumberAsDouble(),
              f.species.youngModulus, 1.0);
}

TEST(TreeExport, StraightTreeMatchesTreeStatsHeight) {
  const Fixture f("quaking-aspen", 7);
  const test::TempDir dir;
  TreeExportOptions options;
  options.levels = {1};
  exportTreeGltf(f.pieces, f.tree, f.species, dir / "aspen.gltf", options);
  const tinygltf::Model m = load(dir / "aspen.gltf");
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_TRUE(m.nodes[0].extensions.empty()); // one LOD: no MSFT_lod
  const tinygltf::Accessor& pos = m.accessors.at(static_cast<std::size_t>(positionAccessor(m, 0)));
  const TreeStats stats = treeStats(f.pieces, f.tree);
  EXPECT_NEAR(pos.maxValues[1], stats.height * f.species.trunkRadius, 1e-4);
  const Bounds cpu = skinnedBounds(f, {});
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(pos.minValues[static_cast<std::size_t>(k)], cpu.min[k], 1e-5);
    EXPECT_NEAR(pos.maxValues[static_cast<std::size_t>(k)], cpu.max[k], 1e-5);
  }
  // Without an atlas: the species' bark colour, no images.
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_TRUE(m.images.empty());
  const std::vector<double>& colour = m.materials[0].pbrMetallicRoughness.baseColorFactor;
  EXPECT_NEAR(colour[0], f.species.barkColour.r, 1e-6);
  EXPECT_NEAR(colour[2], f.species.barkColour.b, 1e-6);
}

Image pattern(int w, int h, int seed) {
  Image image(w, h, 4, PixelType::U8);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.set(x, y, 0, static_cast<float>((x * 7 + seed) % w) / static_cast<float>(w));
      image.set(x, y, 1, static_cast<float>((y * 3 + seed) % h) / static_cast<float>(h));
      image.set(x, y, 2, 0.5f);
      image.set(x, y, 3, (x + y) % 5 == 0 ? 0.0f : 1.0f);
    }
  }
  return image;
}

TEST(TreeExport, AtlasesUvCallbackAndImpostor) {
  const Fixture f("almond", 5);
  const test::TempDir dir;
  TreeExportOptions options;
  options.levels = {3, 1};
  options.barkAtlas = pattern(32, 32, 1);
  // Quad q of instance n gets the atlas cell (q mod 4, n mod 4) of a 4 × 4 grid.
  std::size_t calls = 0;
  options.barkUv = [&](std::size_t n, std::size_t q) {
    ++calls;
    const glm::vec2 o(static_cast<float>(q % 4) * 0.25f, static_cast<float>(n % 4) * 0.25f);
    return QuadUvs{{{o, o + glm::vec2(0.25f, 0.0f), o + glm::vec2(0.25f), o + glm::vec2(0.0f, 0.25f)}}};
  };
  ImpostorAtlas impostor;
  impostor.image = pattern(64, 64, 2);
  impostor.viewsPerSide = 4;
  options.impostor = impostor;
  exportTreeGltf(f.pieces, f.tree, f.species, dir / "almond.gltf", options);
  std::size_t quads = 0;
  for (const TreeNode& node : f.tree.nodes) {
    quads += f.pieces[static_cast<std::size_t>(node.piece)].quads.size();
  }
  EXPECT_EQ(calls, 2 * quads); // once per quad and level

  const tinygltf::Model m = load(dir / "almond.gltf");
  ASSERT_EQ(m.images.size(), 2u);
  EXPECT_EQ(m.images[0].width, 32);
  EXPECT_EQ(m.images[1].width, 64);
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].pbrMetallicRoughness.baseColorTexture.index, 0);
  EXPECT_EQ(m.materials[1].alphaMode, "MASK");
  // Level 1: every vertex sits on a quad corner, so its UV is a multiple of 0.25 (the callback's corners).
  const tinygltf::Primitive& coarse = m.meshes[1].primitives.at(0);
  const std::size_t n = m.accessors.at(static_cast<std::size_t>(coarse.attributes.at("TEXCOORD_0"))).count;
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double> uv = element(m, coarse.attributes.at("TEXCOORD_0"), i);
    ASSERT_NEAR(uv[0] * 4.0, std::round(uv[0] * 4.0), 1e-5) << i;
    ASSERT_NEAR(uv[1] * 4.0, std::round(uv[1] * 4.0), 1e-5) << i;
  }
  // The LOD chain: MSFT_lod on LOD0 lists LOD1 and the impostor; the impostor is a textured quad.
  ASSERT_EQ(m.extensionsUsed, std::vector<std::string>{"MSFT_lod"});
  const tinygltf::Value& ids = m.nodes[0].extensions.at("MSFT_lod").Get("ids");
  ASSERT_EQ(ids.ArrayLen(), 2u);
  const auto& impostorNode = m.nodes.at(static_cast<std::size_t>(ids.Get(1).GetNumberAsInt()));
  EXPECT_EQ(impostorNode.skin, -1);
  const tinygltf::Value& layout = impostorNode.extras.Get("impostor");
  EXPECT_EQ(layout.Get("layout").Get<std::string>(), "octahedral");
  EXPECT_EQ(layout.Get("viewsPerSide").GetNumberAsInt(), 4);
  const tinygltf::Mesh& quad = m.meshes.at(static_cast<std::size_t>(impostorNode.mesh));
  EXPECT_EQ(m.accessors.at(static_cast<std::size_t>(quad.primitives[0].indices)).count, 6u);
  EXPECT_EQ(quad.primitives[0].material, 1);
  EXPECT_EQ(m.nodes[0].extras.Get("MSFT_screencoverage").ArrayLen(), 3u);
}

TEST(TreeExport, RendererBarkKeepsTheTilesShapeOnStretchedPieces) {
  // useRendererBark stacks tileRepeat() tiles along every quad's grain, so a larch whose branch
  // pieces are stretched to about five times their modelled length shows its bark tiles about as long as
  // wide, as the renderer does (one tile per quad stretched them up to 9 times).
  const Fixture f("european-larch", 3);
  BarkSet set;
  set.name = "solid";
  set.tileSize = 8;
  set.edgeColours = 2;
  for (int i = 0; i < 48; ++i) {
    set.colour.emplace_back(8, 8, 3, PixelType::U8);
  }
  set.classFirst = {0, 16, 32, 0};
  set.classCount = {16, 16, 16, 0};
  TreeExportOptions options;
  options.levels = {1};
  useRendererBark(options, set, f.pieces, f.tree);
  const TreeMesh mesh = buildTreeMesh(f.pieces, f.tree, f.species, options);
  const TreeMeshLod& lod = mesh.lods.at(0);
  std::vector<PieceTiling> tilings;
  for (const Piece& piece : f.pieces.pieces) {
    tilings.push_back(pieceTiling(piece));
  }
  std::size_t strips = 0;
  std::size_t stretched = 0;
  for (const TreeNode& node : f.tree.nodes) {
    const PieceTiling& tiling = tilings[static_cast<std::size_t>(node.piece)];
    stretched += node.stretch > 2.0f ? 1 : 0;
    for (std::size_t q = 0; q < tiling.rotation.size(); ++q) {
      strips += tileRepeat(tiling, q, tileStretch(node.stretch));
    }
  }
  ASSERT_GT(stretched, 10u);
  EXPECT_EQ(lod.indices.size() / 3, 2 * strips) << "two triangles per tile at level 1";
  // The share of the bark's area whose tiles are within 2:1: per triangle, metres per texel along the tile's
  // y over those along its x (atlas u runs along the tile's x and v along its y).
  auto squareShare = [](const TreeMeshLod& mesh) {
    double square = 0.0;
    double total = 0.0;
    for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
      const glm::vec3 p0 = mesh.positions[mesh.indices[i]];
      const glm::vec2 t0 = mesh.uvs[mesh.indices[i]];
      const glm::vec3 e1 = mesh.positions[mesh.indices[i + 1]] - p0;
      const glm::vec3 e2 = mesh.positions[mesh.indices[i + 2]] - p0;
      const glm::vec2 d1 = mesh.uvs[mesh.indices[i + 1]] - t0;
      const glm::vec2 d2 = mesh.uvs[mesh.indices[i + 2]] - t0;
      const float det = d1.x * d2.y - d2.x * d1.y;
      const float area = 0.5f * glm::length(glm::cross(e1, e2));
      if (std::abs(det) < 1e-12f || !(area > 0.0f)) {
        continue;
      }
      const glm::vec3 alongU = (e1 * d2.y - e2 * d1.y) / det;
      const glm::vec3 alongV = (e2 * d1.x - e1 * d2.x) / det;
      const double aspect = glm::length(alongV) / glm::length(alongU);
      total += area;
      square += aspect > 0.5 && aspect < 2.0 ? area : 0.0;
    }
    return square / total;
  };
  const double share = squareShare(lod);
  EXPECT_GT(share, 0.85);
  // The control: one tile per quad (the first strip's tile over the whole quad), as before tileRepeat.
  QuadUvFunction tiles = options.barkUv;
  options.barkUv = [&tiles](std::size_t node, std::size_t quad) {
    QuadUvs uvs = tiles(node, quad);
    uvs.strips.resize(1);
    return uvs;
  };
  const double oneTile = squareShare(buildTreeMesh(f.pieces, f.tree, f.species, options).lods.at(0));
  EXPECT_LT(oneTile, 0.6);
  std::cout << "bark area with tiles within 2:1: " << share << " (one tile per quad: " << oneTile << ")\n";
}

// An atlas baked around a bounding sphere (sylva tree export --impostor): the quad is the sphere's square
// through its centre (so the view shows at the tree's size) and the extras carry the sphere; a sphere without
// a positive finite radius is refused.
TEST(TreeExport, ImpostorQuadSpansTheAtlasSphere) {
  const Fixture f("almond", 5);
  const test::TempDir dir;
  TreeExportOptions options;
  options.levels = {1};
  ImpostorAtlas impostor;
  impostor.image = pattern(64, 64, 2);
  impostor.viewsPerSide = 4;
  impostor.layout = "hemi-octahedral";
  impostor.sphere = glm::vec4(0.25f, 1.5f, -0.125f, 2.0f);
  options.impostor = impostor;
  exportTreeGltf(f.pieces, f.tree, f.species, dir / "almond.gltf", options);
  const tinygltf::Model m = load(dir / "almond.gltf");
  const tinygltf::Value& ids = m.nodes[0].extensions.at("MSFT_lod").Get("ids");
  ASSERT_EQ(ids.ArrayLen(), 1u);
  const auto& node = m.nodes.at(static_cast<std::size_t>(ids.Get(0).GetNumberAsInt()));
  const tinygltf::Value& extras = node.extras.Get("impostor");
  ASSERT_EQ(extras.Get("sphereM").ArrayLen(), 4u);
  EXPECT_DOUBLE_EQ(extras.Get("sphereM").Get(3).GetNumberAsDouble(), 2.0);
  const tinygltf::Primitive& quad = m.meshes.at(static_cast<std::size_t>(node.mesh)).primitives.at(0);
  const int positions = quad.attributes.at("POSITION");
  double lo[3] = {1e9, 1e9, 1e9};
  double hi[3] = {-1e9, -1e9, -1e9};
  for (std::size_t i = 0; i < 4; ++i) {
    const std::vector<double> p = element(m, positions, i);
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], p[static_cast<std::size_t>(c)]);
      hi[c] = std::max(hi[c], p[static_cast<std::size_t>(c)]);
    }
  }
  EXPECT_NEAR(lo[0], 0.25 - 2.0, 1e-6);
  EXPECT_NEAR(hi[0], 0.25 + 2.0, 1e-6);
  EXPECT_NEAR(lo[1], 1.5 - 2.0, 1e-6);
  EXPECT_NEAR(hi[1], 1.5 + 2.0, 1e-6);
  EXPECT_NEAR(lo[2], -0.125, 1e-6);
  EXPECT_NEAR(hi[2], -0.125, 1e-6);

  options.impostor->sphere = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
  EXPECT_THROW(exportTreeGltf(f.pieces, f.tree, f.species, dir / "bad.gltf", options), Error);
  EXPECT_FALSE(fs::exists(dir / "bad.gltf"));
}

TEST(TreeExport, ObjReadsBackThroughAssimp) {
  const Fixture f("weeping-willow", 3);
  const test::TempDir dir;
  TreeExportOptions options;
  options.levels = {2};
  options.barkAtlas = pattern(16, 16, 3);
  const TreeExportStats stats = exportTreeObj(f.pieces, f.tree, f.species, dir / "willow.obj", options);
  const TreeMesh mesh = buildTreeMesh(f.pieces, f.tree, f.species, options);
  const TreeMeshLod& lod = mesh.lods[0];
  ASSERT_EQ(stats.vertices[0], lod.positions.size());
  EXPECT_TRUE(fs::exists(dir / "willow.mtl"));
  EXPECT_EQ(loadImage(dir / "willow_bark.png"), *options.barkAtlas);
  const std::string text = readTextFile(dir / "willow.obj");
  std::size_t vLines = 0;
  for (std::size_t at = 0; (at = text.find("\nv ", at)) != std::string::npos; ++at) {
    ++vLines;
  }
  EXPECT_EQ(vLines, lod.positions.size());

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir / "willow.obj").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  std::size_t faces = 0;
  std::size_t corners = 0;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[i];
    for (unsigned fi = 0; fi < mesh->mNumFaces; ++fi) {
      const aiFace& face = mesh->mFaces[fi];
      ASSERT_EQ(face.mNumIndices, 3u);
      for (unsigned k = 0; k < 3; ++k) {
        const aiVector3D& p = mesh->mVertices[face.mIndices[k]];
        const glm::vec3& e = lod.positions[lod.indices[corners++]];
        ASSERT_NEAR(p.x, e.x, 1e-6f);
        ASSERT_NEAR(p.y, e.y, 1e-6f);
        ASSERT_NEAR(p.z, e.z, 1e-6f);
      }
      ++faces;
    }
  }
  EXPECT_EQ(faces, lod.indices.size() / 3);
  // The bark material points at the atlas.
  bool textured = false;
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    aiString path;
    if (scene->mMaterials[i]->GetTexture(aiTextureType_DIFFUSE, 0, &path) == AI_SUCCESS) {
      textured = std::string(path.C_Str()) == "willow_bark.png";
    }
  }
  EXPECT_TRUE(textured);
}

TEST(TreeExport, FailuresNameTheFileAndLeaveNothing) {
  const Fixture f("almond", 1);
  const test::TempDir dir;
  TreeExportOptions options;
  options.levels = {8, 0};
  try {
    exportTreeGltf(f.pieces, f.tree, f.species, dir / "bad.glb", options);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "bad.glb").string() + ": LOD level 0 is out of range [1, 64]");
  }
  options.levels = {1};
  options.pose.assign(3, glm::vec2(0.0f));
  EXPECT_THROW(exportTreeObj(f.pieces, f.tree, f.species, dir / "bad.obj", options), Error);
  options.pose.clear();
  EXPECT_THROW(exportTreeGltf(f.pieces, f.tree, f.species, dir / "bad.png", options), Error);
  // An existing file is replaced whole or not at all.
  writeTextFile(dir / "keep.gltf", "old");
  options.levels = {70};
  EXPECT_THROW(exportTreeGltf(f.pieces, f.tree, f.species, dir / "keep.gltf", options), Error);
  EXPECT_EQ(readTextFile(dir / "keep.gltf"), "old");
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir.path())) {
    ++files;
  }
  EXPECT_EQ(files, 1u);
}

} // namespace
} // namespace sylva::trees

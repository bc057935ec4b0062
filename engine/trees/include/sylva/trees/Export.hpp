#pragma once
// Whole trees out to other tools (docs/trees.md "Export"): glTF 2.0 (.gltf with the buffer embedded as
// base64, or binary .glb) with a skinned mesh, a LOD chain, an optional bark atlas and impostor atlas and the
// wind parameters, and Wavefront OBJ (+ .mtl) for tools without skinning.
//
// The mesh is the tree's rest pose in metres (the base frame scales rim units by the species' trunk radius;
// y up, the base at the origin): every piece instance skinned on the CPU exactly as shaders/trees/piece.vert
// does it (rim vertices through their one joint's frame with the canonical corner and normal, interior
// vertices blended over up to four joints), then every piece quad Phong-tessellated on the CPU (phongQuad,
// phongQuadNormal: the CPU twin of piece.tese) on a uniform level × level grid. Each LOD level is one mesh.
//
// glTF layout:
// - Skin: one joint node per tree joint (node name `joint_<j>`, parented as TreeTopology::jointParent, joint
// 0
//   the skeleton root at the base), TRS from the rest frames; inverseBindMatrices are the inverses of the
//   joints' world transforms, so the bind pose is the rest pose. JOINTS_0 (unsigned short, global joint
//   indices) and WEIGHTS_0 (float): the corners' influences blended bilinearly, the four largest kept and
//   renormalised to sum 1.
// - LOD chain: the LOD0 node (finest level, in the scene) carries the MSFT_lod extension (`ids`: the coarser
//   LOD nodes, then the impostor node if any) with `extras.MSFT_screencoverage`;
//   gltf-validator 2.0.0-dev.3.10 accepts it with 0 errors (it reports the extension as unsupported, an info,
//   and it validates the LOD nodes as ordinary nodes). Every LOD node also has `extras.lod` = {level,
//   tessellation}.
// - Materials: bark (the atlas as an embedded PNG when given, else the species' bark colour as
//   baseColorFactor); the impostor (its atlas, alpha mask, double sided).
// - Impostor: a far LOD node holding one vertical quad through the trunk axis, sized to the tree's bounds and
//   textured with the atlas's side view, to be turned towards the camera (`extras.impostor`: billboard
//   "camera-facing", layout "octahedral", "hemi-octahedral" or "grid", viewsPerSide, the view the quad
//   shows, the bounds; with the atlas's framing sphere, the quad is that sphere's square and `sphereM`).
// - Wind: scene extras `wind` (the species' Young's modulus, wood density and damping ratio, the
//   JointWindSettings) and every bending joint's node extras `wind` (frequencyHz, dampingRatio,
//   stiffnessNmPerRad, dampingNmsPerRad, inertiaKgM2, massKg) as buildJointWindRest() computes them.
// Files are written atomically: a failed export leaves no file; errors are one-line sylva::Error naming it.

#include <sylva/core/Image.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/JointWind.hpp>
#include <sylva/trees/Tree.hpp>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sylva::trees {

/**
 * Texture coordinates of one quad: its (s, t) domain (s from corner 0 to 1, t from corner 0 to 3) cut into
 * strips.size() equal strips along s (`alongS`) or t, in order of increasing s or t, each with the atlas UVs
 * of its four corners in the corner order of Piece::quads (corner 0 at the strip's smallest s and t). One
 * strip: the whole quad. Texture space as glTF's: (0, 0) is the top left of the image (its row 0), v grows
 * downwards.
 */
struct QuadUvs {
  /** The strips' atlas UVs, four corners each. */
  std::vector<std::array<glm::vec2, 4>> strips;
  /** Whether the strips run along s (else along t). */
  bool alongS = false;
};

/** The UVs of quad `quad` of piece instance `pieceInstance` (the TreeTopology node index). */
using QuadUvFunction = std::function<QuadUvs(std::size_t pieceInstance, std::size_t quad)>;

/** A pre-rendered impostor atlas: viewsPerSide × viewsPerSide equal views of the tree. */
struct ImpostorAtlas {
  /** The atlas (RGBA8, file order). */
  Image image;
  /** Views per side of the atlas (≥ 1). */
  int viewsPerSide = 8;
  /**
   * Layout of the views: "octahedral" (view (i, j) looks from the direction that octahedral-decodes the
   * centre of cell (i, j), full sphere), "hemi-octahedral" (ImpostorRenderer's atlases, FarField.hpp: cell
   * (i, j), j counted from the image's bottom row, looks from impostorViewDirection((i, j), views): the
   * grid vertices of the upper hemisphere) or "grid" (yaw steps by rows).
   */
  std::string layout = "octahedral";
  /**
   * The bounding sphere the views were framed on, metres: centre relative to the tree's base (xyz) and
   * radius (w), as ImpostorRenderer fits it. With it the quad is the square of side 2·radius through the
   * centre, so the view shows at the tree's size; none: the quad spans the tree's bounds.
   */
  std::optional<glm::vec4> sphere;
};

/** What exportTreeGltf() and exportTreeObj() write. */
struct TreeExportOptions {
  /** Tessellation level of each LOD, finest first (each 1 … 64); OBJ uses the first. */
  std::vector<int> levels{8, 3, 1};
  /** Bark atlas (any channels, 8 or 16 bit), embedded as PNG; none: the species' bark colour. */
  std::optional<Image> barkAtlas;
  /** Atlas UVs per quad; empty: the piece's own (u, 1 − v), repeating. */
  QuadUvFunction barkUv;
  /** Impostor atlas for a far LOD; none: no impostor. */
  std::optional<ImpostorAtlas> impostor;
  /** Rest pose bends per joint (randomPose()); empty: straight. */
  std::vector<glm::vec2> pose;
  /** Metres per rim unit; 0: the species' trunk radius. */
  float scale = 0.0f;
  /** Constants of the joint springs written as wind parameters. */
  JointWindSettings wind;
};

/**
 * Makes the export show the bark as the renderer draws it: `options.barkAtlas` becomes `bark`'s tiles packed
 * in one atlas, and `options.barkUv` gives each quad its tiles (per piece instance by its root joint, per
 * quad, with the tile's rotation, tileRepeat() strips along its grain for the node's stretch). `pieces` and
 * `tree` must outlive the export.
 */
void useRendererBark(TreeExportOptions& options, const BarkSet& bark, const PieceSet& pieces,
                     const TreeTopology& tree);

/** One LOD level of an exported tree (world = metres, rest pose). */
struct TreeMeshLod {
  /** The tessellation level the LOD was made at (1 … 64). */
  int level = 1;
  /** Vertex positions, metres. */
  std::vector<glm::vec3> positions;
  /** Unit vertex normals. */
  std::vector<glm::vec3> normals;
  /** glTF texture space (v down). */
  std::vector<glm::vec2> uvs;
  /** Global joint indices and weights (sum 1; unused slots joint 0, weight 0). */
  std::vector<std::array<std::uint16_t, 4>> joints;
  /** The joints' weights (sum 1). */
  std::vector<glm::vec4> weights;
  /** Triangles, counter-clockwise seen from outside. */
  std::vector<std::uint32_t> indices;
};

/** The rest pose a tree exports as: world frames per joint and the LOD meshes. */
struct TreeMesh {
  /** World transform of every joint (metres). */
  std::vector<glm::mat4> jointFrames;
  /** The LOD meshes, finest first. */
  std::vector<TreeMeshLod> lods;
  /** Bounds of the finest LOD, metres. */
  Bounds bounds;
};

/**
 * Builds the meshes exportTreeGltf() writes (one per options.levels entry). Throws sylva::Error naming
 * `where` for bad levels (outside 1 … 64), a pose of the wrong size, more than 65,535 joints or a mesh over
 * 2³² vertices.
 */
TreeMesh buildTreeMesh(const PieceSet& pieces, const TreeTopology& tree, const Species& species,
                       const TreeExportOptions& options = {}, const std::string& where = "tree export");

/** Counts of what an export wrote. */
struct TreeExportStats {
  /** Joints written. */
  std::size_t joints = 0;
  /** Vertices and triangles per LOD level, finest first. */
  std::vector<std::size_t> vertices;
  /** Triangles per LOD level, finest first. */
  std::vector<std::size_t> triangles;
  /** Bytes of the main file. */
  std::size_t bytes = 0;
};

/**
 * Writes `tree` as glTF 2.0: binary when `path` ends in .glb, else one .gltf with its buffer embedded (layout
 * in the header comment). Throws sylva::Error "<path>: <reason>".
 */
TreeExportStats exportTreeGltf(const PieceSet& pieces, const TreeTopology& tree, const Species& species,
                               const std::filesystem::path& path, const TreeExportOptions& options = {});

/**
 * Writes `tree` as Wavefront OBJ: LOD0 (the first level) in the rest pose, metres, `v`/`vt`/`vn` per vertex
 * and triangles, with `<stem>.mtl` beside it (material `bark`: the bark colour, and `map_Kd <stem>_bark.png`
 * written beside it when options carry a bark atlas). No skinning, LOD chain or impostor. Throws sylva::Error
 * "<path>: <reason>".
 */
TreeExportStats exportTreeObj(const PieceSet& pieces, const TreeTopology& tree, const Species& species,
                              const std::filesystem::path& path, const TreeExportOptions& options = {});

} // namespace sylva::trees

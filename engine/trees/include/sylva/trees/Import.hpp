#pragma once
// Artist-made pieces (docs/trees.md): quad meshes read through Assimp (OBJ, glTF 2.0, Collada, FBX, …), their
// rims found and fitted, checked against every interlocking rule, and the built-in pieces written out as OBJ
// and glTF so artists can start from them.
//
// Rules for a piece file:
// - Quads only. Faces keep the file's order, and face i becomes quad i (its stable id). glTF has no quads: a
//   glTF piece stores quad i as triangles 2i and 2i + 1, which share one edge (what exportPieceGltf writes).
// - Rims from vertex groups: bones (glTF skin joints, Collada/FBX bones) named `rim_root` and `rim_leaf_N`
//   (N = 1, 2, …); a vertex belongs to a rim when its weight on that bone is over 0.5. Corner 0 of a leaf rim
//   is the corner nearest the bone's +x axis (its node's frame, else its bind pose), the bone's +y running
//   along the branch.
// - Files without rim bones (OBJ): the root rim is the six vertices on the standard rim (the unit hexagon in
//   the y = 0 plane around the origin), and the leaf rims are the mesh's other boundary loops (edges used by
//   one quad), numbered in the order the face list first reaches them; corner 0 is the first of a rim's
//   vertices the face list reaches.
// - Every rim is a regular hexagon (within ImportOptions::tolerance), the root rim is the standard rim, and
//   the quads next to each rim lie on the fixed cone (their normals within ImportOptions::normalTolerance of
//   rimNormal()), facing outwards.
// Model space is the file's space after its node transforms, in rim units (the root rim has circumradius 1);
// the root rim's axis (+y) runs along growth.

#include <sylva/trees/Pieces.hpp>

#include <cstddef>
#include <filesystem>
#include <string>

namespace sylva::trees {

/** How importPiece() reads and checks a file. */
struct ImportOptions {
  /** The piece's name; empty: the file name without its extension. */
  std::string name;
  /**
   * Largest distance of a rim corner from the regular hexagon fitted to its rim, rim units (multiplied by the
   * rim's circumradius when that is over 1). Corners within it are snapped onto the exact hexagon.
   */
  float tolerance = 1e-3f;
  /**
   * Largest angle between the normal of the quads next to a rim corner (from their winding) and the fixed rim
   * normal there, radians: larger means the ring of quads is not on the fixed cone or faces inwards.
   */
  float normalTolerance = 0.1f;
  /** Most quads a piece file may hold (a limit for untrusted files). */
  std::size_t maxQuads = 100000;
};

/**
 * Reads a piece from `file` (any format Assimp reads) and returns it checked: rims ordered and fitted (Rim
 * frames are the building transforms, joints[0] the root joint, joints[r] the terminal joint of leaf rim r at
 * that rim's frame), rim vertices snapped onto their canonical corners with the fixed normals and weight 1 on
 * their joint, interior vertices blended between the root and the nearest terminal joint (as the built-in
 * pieces are), interior normals the file's (averaged over a point's copies) or, when it has none, from the
 * quads, tile class 0 on every quad, and bearsFoliage set when the piece has no leaf rims. A leaf rim's frame
 * is its bone's node frame when that maps the standard rim onto the corners within the tolerance (exact),
 * otherwise the least-squares fit. Vertices are welded by position; their order is the file's where the
 * format keeps it. Throws sylva::Error with one line naming the file (and the rim): `branch.obj: leaf rim 2
 * is not a regular hexagon (corner 3 is 0.12 off)`, `piece.gltf: missing root rim …`, `piece.gltf:
 * rim_leaf_1: wrong normals …`, `x.obj: not a quad mesh (face 7 has 3 corners)` (faces counted from 0), or
 * Assimp's reason for a file it cannot read.
 */
Piece importPiece(const std::filesystem::path& file, const ImportOptions& options = {});

/**
 * The built-in pieces, each replaced by FOLDER/NAME.gltf (or .glb, .obj, .dae, .fbx) where such a file exists
 * (the first found in that order; it must have as many leaf rims as the piece it replaces), followed by every
 * other piece file in `folder` in name order. Throws sylva::Error naming the file at fault.
 */
PieceSet loadPieceSet(const std::filesystem::path& folder, const ImportOptions& options = {});

/**
 * Writes `piece` as Wavefront OBJ (atomically): one `v x y z` per vertex in piece order (9 significant
 * digits, so floats read back exactly), `vt u v`, `vn` normals, then one `f` quad per piece quad in order.
 * OBJ has no vertex groups: importPiece() finds the rims again from the boundary loops, which gives back this
 * piece when its leaf rims are first reached by the face list in rim order, each at corner 0 (true of the
 * built-in pieces).
 */
void exportPieceObj(const Piece& piece, const std::filesystem::path& path);

/**
 * Writes `piece` as glTF 2.0 (atomically; one .gltf file with its buffer embedded as base64): quad i as
 * triangles 2i and 2i + 1, positions, normals and TEXCOORD_0 (u, 1 − v: glTF's texture space starts at the
 * top left); a skin whose joints are `piece` (the skeleton root, at the model origin) and, below it,
 * `rim_root`, `rim_leaf_1`, … at the rims' frames (node matrices; inverse bind matrices their inverses). Each
 * rim's six vertices have weight 1 on that rim's joint and every other vertex weight 1 on `piece`: the joints
 * mark the rims, and importPiece() computes the interior skinning weights again.
 */
void exportPieceGltf(const Piece& piece, const std::filesystem::path& path);

} // namespace sylva::trees

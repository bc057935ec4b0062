#pragma once
// Tree pieces (docs/trees.md, seed 000 §4.1): low-poly quad meshes whose rims are regular hexagons. Every rim
// is the same edge loop up to a similarity: in its own rim frame it is the unit hexagon in the xz plane with
// corner k at angle 60°·k, and the ring of quads next to it is a cone of one fixed aperture, so rim normals
// are fixed too. A piece's root rim is the standard rim in model space; each leaf rim carries a building
// transform (a similarity mapping the standard rim frame onto it). Rim vertices are bound with weight 1 to
// one joint: the root joint (rim frame = identity) or the leaf rim's terminal joint (rim frame = building
// transform), so two interlocking pieces compute bit-identical rim positions and normals from one shared
// joint matrix and the same canonical corner constants.

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sylva::trees {

/** Corners of every rim (a regular hexagon). */
constexpr int kRimCorners = 6;
/**
 * Half-angle of the cone the quad ring next to every rim lies on, radians: surfaces narrow by tan(β) per unit
 * of height along the rim axis. Rim normals tilt up (along the rim axis) by this angle.
 */
constexpr float kRimConeAngle = 0.025f;

/** Corner k of the standard rim, rim-frame units: (cos 60°k, 0, sin 60°k). The same floats on CPU and GPU. */
glm::vec3 rimCorner(int k);
/** The fixed normal at corner k of every rim, rim frame: (cos β·cos 60°k, sin β, cos β·sin 60°k). */
glm::vec3 rimNormal(int k);
/** Rotation of a rim frame by `steps` × 60° about its axis (+y), mapping corner k onto corner k + steps. */
glm::mat4 rimRotation(int steps);

/** One vertex of a piece, model space (rim units: the root rim has circumradius 1). */
struct PieceVertex {
  /** Position, model space (rim units). */
  glm::vec3 position{0.0f};
  /** Unit normal, model space. */
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  /** Up to four joints (indices into Piece::joints) and weights summing to 1; unused weights are 0. */
  std::array<std::uint8_t, 4> joints{0, 0, 0, 0};
  /** The joints' weights (sum 1). */
  glm::vec4 weights{1.0f, 0.0f, 0.0f, 0.0f};
  /** Rim this vertex belongs to (index into Piece::rims) and its corner there; -1 for interior vertices. */
  int rim = -1;
  /** Its corner on that rim (0 … 5), -1 for interior vertices. */
  int corner = -1;
  /** Texture coordinates: u around the branch (0..1 per turn), v along it (rim-radius units). */
  float u = 0.0f;
  /** Texture coordinate along the branch, rim-radius units. */
  float v = 0.0f;
};

/** A rim: six vertex indices, corner k first at index k, and the frame mapping the standard rim onto it. */
struct Rim {
  /** The rim's six vertex indices, corner k at index k. */
  std::array<std::uint32_t, kRimCorners> vertices{};
  /** Building transform: standard rim frame → piece model space (a similarity); identity for the root rim. */
  glm::mat4 frame{1.0f};
  /** The joint its vertices are bound to: 0 for the root rim, the leaf's terminal joint otherwise. */
  int joint = 0;
};

/** A joint of a piece's skeleton: the root joint (index 0) or the terminal joint of one leaf rim. */
struct Joint {
  /** Joint frame in model space (bind pose): identity for the root, the leaf rim's frame for terminals. */
  glm::mat4 bind{1.0f};
  /** The rim it carries. */
  int rim = 0;
};

/**
 * A piece: quads (corner indices counter-clockwise seen from outside), rims (rims[0] is the root rim; the
 * rest are leaf rims, rims[i] carrying joint i), joints (joints[0] the root). Quad i keeps index i as its
 * stable id, which later indexes per-instance tile tables; tileClass[i] says which class of bark tiles it
 * accepts.
 */
struct Piece {
  /** The piece's name (assembly refers to pieces by name). */
  std::string name;
  /** Vertices, model space. */
  std::vector<PieceVertex> vertices;
  /** Quads, corner indices counter-clockwise seen from outside. */
  std::vector<std::array<std::uint32_t, 4>> quads;
  /** Per quad: the class of bark tiles it takes. */
  std::vector<std::uint8_t> tileClass;
  /** Rims: rims[0] the root rim, the rest leaf rims. */
  std::vector<Rim> rims;
  /** Joints: joints[0] the root, joint i carrying rim i. */
  std::vector<Joint> joints;
  /** Whether foliage may grow on it (twig pieces, tips). */
  bool bearsFoliage = false;

  /** Leaf rims (rims other than the root rim). */
  std::size_t leafRims() const { return rims.empty() ? 0 : rims.size() - 1; }
};

/**
 * Checks every rule of interlocking pieces; throws sylva::Error "<where>: <what>" naming the rim at fault:
 * a root rim that is missing or not the standard rim, a rim that is not a regular hexagon (corners off by
 * more than `tolerance` rim units after mapping through its frame), rim normals that are not the fixed cone
 * normals, rim vertices not bound with weight 1 to the rim's joint, a building transform that is not a
 * similarity, non-finite values, quads with bad indices, weights not summing to 1.
 */
void validatePiece(const Piece& piece, const std::string& where, float tolerance = 1e-4f);

/**
 * Snaps every rim vertex to its exact canonical position and normal (frame · corner) and binds it with weight
 * 1 to the rim's joint; for pieces built or imported with small errors. Call validatePiece() afterwards.
 */
void snapRims(Piece& piece);

/** Fills interior vertex normals from the area-weighted normals of their quads (rim normals stay fixed). */
void computeNormals(Piece& piece);

/** Axis-aligned bounds of a piece's vertices, model space. */
struct Bounds {
  /** Smallest corner. */
  glm::vec3 min{0.0f};
  /** Largest corner. */
  glm::vec3 max{0.0f};
};
/** The bounds of `piece`'s vertices, model space. */
Bounds pieceBounds(const Piece& piece);

} // namespace sylva::trees

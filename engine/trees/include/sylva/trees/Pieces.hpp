#pragma once
// The built-in piece set (docs/trees.md): the paper's I (narrowing cylinder) and Y (symmetric fork), the
// trifurcation Ψ and the branch–stem attachment ⊢ it names but does not show, a cap closing a branch tip and
// a foot closing the trunk's base, all generated in code as quad meshes that satisfy validatePiece().

#include <sylva/trees/Piece.hpp>

#include <string>
#include <vector>

namespace sylva::trees {

/** The narrowing cylinder: root rim, two inner rings, one leaf rim scaled by 1 − 5·tan β (length 5). */
Piece makeI();
/** The symmetric fork with co-dominant stems: two leaf rims tilted ±30° about x, scaled 0.72. */
Piece makeY();
/** The trifurcation (a 3D Ψ): three leaf rims, 120° apart around the axis, tilted 35°, scaled 0.62. */
Piece makePsi();
/** The branch–stem attachment ⊢: the stem continues (scale 0.85) and a side branch leaves at 58° (scale 0.5).
 */
Piece makeBranch();
/** Length of the Cap along its axis, rim radii: the tip is this far above the root rim's centre. */
constexpr float kCapLength = 3.3f;
/**
 * A branch tip: the root rim tapering to a point on the axis kCapLength up (the rim's cone to half a radius,
 * then rings at 60 %, 20 % and 6 % of the radius; no leaf rims). Bears foliage.
 */
Piece makeCap();
/** The trunk's base: a flared foot closed at the bottom with one leaf rim on top (the tree's root piece). */
Piece makeFoot();

/** A set of pieces addressed by index; assembly refers to pieces by name through find(). */
struct PieceSet {
  /** The pieces, by index. */
  std::vector<Piece> pieces;

  /** Index of the piece called `name`, or -1. */
  int find(const std::string& name) const;
  /** Index of `name`; throws sylva::Error "<where>: unknown piece '<name>' (known: …)". */
  int require(const std::string& name, const std::string& where) const;
  /** Piece `i`; no bounds checks. */
  const Piece& operator[](std::size_t i) const { return pieces[i]; }
  /** Pieces in the set. */
  std::size_t size() const { return pieces.size(); }
};

/** I, Y, Psi, Branch, Cap, Foot in that order (each validated). */
PieceSet standardPieces();

} // namespace sylva::trees

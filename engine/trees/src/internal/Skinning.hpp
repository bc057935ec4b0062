#pragma once
// Skinning weights shared by the built-in pieces (Pieces.cpp) and imported ones (Import.cpp), so a piece that
// goes out through a file and back gets the same weights.

#include <sylva/trees/Piece.hpp>

namespace sylva::trees::internal {

/**
 * Skinning weights of a piece's interior vertices (rim vertices, vertex.rim ≥ 0, are left as they are): each
 * blends the root joint with the terminal joints of up to three leaf rims: leaf r gets smoothstep(t_r), t_r
 * the vertex's projection between the root rim centre (the model-space origin) and that leaf rim's centre,
 * times its share of the affinity 1/(d_r + 0.05)⁴ (d_r the distance to that segment), the root the rest. So
 * bends spread along the piece and a fork's crotch follows its children evenly. Pieces without leaf rims bind
 * every interior vertex to the root joint.
 */
void blendInteriorWeights(Piece& piece);

} // namespace sylva::trees::internal

#pragma once
// What `sylva tree info` and `sylva tree generate` say about a tree: pieces by type, joints, quads, depth,
// branching order and height, in rim units or, with its species, metres.

#include <sylva/trees/Pieces.hpp>
#include <sylva/trees/Species.hpp>
#include <sylva/trees/Tree.hpp>

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>

namespace sylva::trees {

/** The preset species `name` names, or none when it is not a preset (a species file's name). */
std::optional<Species> presetSpecies(const std::string& name);

/**
 * What `sylva tree import-piece` says about a valid piece (read from `file`): its vertices, quads and leaf
 * rims, then each rim's centre, axis, radius and corner 0 direction (piece space, rim units); lines end in
 * '\n'.
 */
std::string describePiece(const std::string& file, const Piece& piece);

/** "I 3, Y 2, …": how many pieces of each type of `pieces` a tree with `stats` uses. */
std::string piecesByTypeText(const PieceSet& pieces, const TreeStats& stats);

/**
 * The summary of `tree` (read from `file`) as "name  value" lines ending in '\n': file, species and seed,
 * pieces by type, joints, quads and piece vertices, depth, branching order, and height in metres when
 * `species` is known (trunk radius × rim units), else in rim units.
 */
std::string describeTree(const std::string& file, const TreeTopology& tree, const PieceSet& pieces,
                         const std::optional<Species>& species);

/**
 * The same as JSON: file, species, seed, pieces, piecesByType, joints, quads, vertices, depth, order,
 * heightRimUnits, and with a species trunkRadius and heightMetres.
 */
nlohmann::json describeTreeJson(const std::string& file, const TreeTopology& tree, const PieceSet& pieces,
                                const std::optional<Species>& species);

} // namespace sylva::trees

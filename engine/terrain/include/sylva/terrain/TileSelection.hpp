#pragma once

#include <sylva/core/Geometry.hpp>
#include <sylva/terrain/TilePyramid.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace sylva::terrain {

/** How streamed tiles are chosen for a view (docs/terrain-data.md, "Streaming"). */
struct TileLodConfig {
  /**
   * A tile splits into its four children while the camera is closer to its box (footprint × height range)
   * than this many times its size, as the quadtree's distance LOD does (> 0).
   */
  float lodDistanceFactor = 2.0f;
  /** Drop tiles whose box is outside the frustum passed to selectTiles (ignored when it passes none). */
  bool frustumCull = true;
  /** Deepest level drawn (0: full resolution). */
  int finestLevel = 0;
};

/** One tile to draw. */
struct SelectedTile {
  TileKey key; ///< the tile
  /** Bit e (PatchEdge: west, north, east, south) set when the drawn tile across edge e is one level coarser:
   * that edge keeps every second vertex so that it meets the coarser tile's vertices exactly. */
  std::uint32_t coarserEdges = 0;
};

/** The result of selectTiles. */
struct TileSelection {
  std::vector<SelectedTile> tiles; ///< tiles to draw; their footprints cover the visible world once
  /**
   * Every visible tile of the selection's tree: the drawn tiles and the split tiles above them (a split
   * tile's visible children must be resident to split it, even where all of theirs are culled).
   */
  std::vector<TileKey> tree;
  /** Tiles the distance rule wanted but that were not resident: their coarser parents stand in. */
  std::vector<TileKey> missing;
  int culled = 0;    ///< tiles dropped by the frustum test
  int coarsened = 0; ///< splits undone to keep neighbouring tiles within one level
};

/**
 * Chooses the tiles to draw for a camera at `camera` (world metres): from the top level down, a tile splits
 * when the distance rule asks for it AND all its children are resident (`resident(key)`); otherwise it is
 * drawn as a stand-in and the wanted children are listed in `missing` (the caller requests them). Splits are
 * then undone where needed, coarse to fine, until every drawn tile's edge neighbours are at most one level
 * coarser or finer (restricted), which the renderer's edge rule needs to be crack-free. The top tile must be
 * resident. `summary(key)` gives box heights. `frustum` (may be null) is in coordinates relative to `camera`
 * (built from a view whose eye is at the origin), so that worlds of any size keep float precision.
 */
TileSelection selectTiles(const PyramidInfo& layout,
                          const std::function<TileSummary(const TileKey&)>& summary,
                          const std::function<bool(const TileKey&)>& resident, const glm::dvec3& camera,
                          const Frustum* frustum, const TileLodConfig& config);

/** The world footprint of a tile, metres: x0, z0, size (square; may extend beyond the data). */
glm::dvec3 tileFootprint(const PyramidInfo& layout, const TileKey& key);

} // namespace sylva::terrain

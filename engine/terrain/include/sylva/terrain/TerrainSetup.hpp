#pragma once
// What makes a terrain (docs/terrain.md "Building a terrain"): where the heights come from, how they are
// drawn and how the quadtree is laid out, as one description that the command line (`--dem`, `--seed`,
// `--tess`, …) and scene files ("terrain") both fill. CPU: loading or generating the heights, resolving the
// sea level, deriving the quadtree, the memory a render needs. The drawable scene is TerrainScene::fromSetup.

#include <sylva/core/FieldName.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/Quadtree.hpp>
#include <sylva/terrain/TerrainMaps.hpp>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::terrain {

/** Where a scene's heights come from: a DEM/heightmap file, or the seeded procedural generator. */
struct TerrainSource {
  /** Height file (PNG, GeoTIFF and other GDAL rasters, .npy/.npz); empty = procedural. */
  std::filesystem::path dem;
  /** How the DEM is read (units, limits, array name). */
  LoadOptions load;
  /** The procedural generator's parameters (with no DEM). */
  ProceduralSpec procedural = defaultProcedural();
  /** Procedural field size in samples along x (and z unless proceduralRows). */
  int proceduralSize = 1025;
  /** Procedural sample spacing, metres. */
  float proceduralSpacing = 2.0f;
  /** Samples along z of a rectangular procedural field (proceduralSize along x); 0: square. */
  int proceduralRows = 0;

  /** Samples along z of the procedural field: proceduralRows, or proceduralSize when 0. */
  int rows() const { return proceduralRows > 0 ? proceduralRows : proceduralSize; }

  /** The demo landscape: warped fBm, 400 m relief. */
  static ProceduralSpec defaultProcedural();
};

/** Procedural fields with more samples than this are generated in strips with a progress line. */
inline constexpr std::size_t kProgressSamples = std::size_t{1} << 20;

/**
 * Loads or generates the heights of `source`; errors name the file or the field. A DEM is read with `limits`
 * when given (else source.load); a procedural field above kProgressSamples is generated in strips with a
 * progress line (bit-identical to one generate() call) and can be cancelled (Progress::cancelAll).
 * `report` (may be null) receives what the DEM loader assumed; a procedural field reports metres, north up.
 */
HeightField loadTerrainSource(const TerrainSource& source, const LoadOptions* limits = nullptr,
                              LoadReport* report = nullptr);

/**
 * Names a setup field in an error message from its scene-file name ("size", "dem", "sea_level", "tess_level",
 * …): "--size" on the command line, "meadow.json: /terrain/size" for a scene file.
 */
using TerrainFieldName = FieldName;

/** Where the sea is: from the data (0 m when the heights go below 0 m, else none), nowhere, or at a height.
 */
struct SeaLevelRule {
  /** Auto: 0 m when the heights go below 0 m, else none; None: no sea; Metres: at `metres`. */
  enum class Kind { Auto, None, Metres };
  /** Which rule. */
  Kind kind = Kind::Auto;
  /** Metres (true heights) for Kind::Metres. */
  float metres = 0.0f;

  /** The sea level in true metres for heights down to `minHeight`, or nullopt for none. */
  std::optional<float> resolve(float minHeight) const;
};

/** A terrain to build: heights, presentation and quadtree layout. */
struct TerrainSetup {
  /** Where the heights come from. */
  TerrainSource source;
  /** Splat rules (JSON, loadSplatLayers); empty: the default sand/grass/snow/rock rules. */
  std::filesystem::path layersFile;
  /** Vertical exaggeration: heights are drawn × this, (0, 1000]. */
  float exaggeration = 1.0f;
  /** Where the sea is. */
  SeaLevelRule seaLevel;
  /** Geomorphing between LOD levels in the scene's draw options. */
  bool geomorph = false;
  /** Tessellation level, LOD distance factor and crack method; rootSize and maxDepth are derived
   * (quadtreeFor) unless `roots` / `maxDepth` below say otherwise. */
  QuadtreeConfig quadtree = defaultQuadtree();
  /** Quadtree roots in all (QuadtreeConfig::forRootCount); 0: four across the longer side. */
  int roots = 0;
  /** Deepest quadtree level, [0, 16]; nullopt: leaves whose tessellated vertices are half a sample apart. */
  std::optional<int> maxDepth;

  /** 512 m roots, depth 5, LOD factor 2, tessellation 16, restricted level map. */
  static QuadtreeConfig defaultQuadtree();
};

/**
 * The quadtree layout of `setup` for `field`: roots and depth derived as TerrainSetup says. Throws
 * sylva::Error naming the field through `name` ("tess_level", "lod_factor", "max_depth", "roots") when a
 * value is outside what the quadtree accepts.
 */
QuadtreeConfig quadtreeFor(const TerrainSetup& setup, const HeightField& field,
                           const TerrainFieldName& name = {});

/**
 * Peak bytes per height sample of a render or viewer session (measured: `sylva render --size 8192` peaks at
 * 1.27 GiB for 67 M samples on llvmpipe, where GPU textures live in process memory).
 */
inline constexpr std::size_t kRenderBytesPerSample = 20;
/** Samples a render can afford with the memory available now (/proc/meminfo MemAvailable). */
std::size_t affordableSamples();
/** Throws `<what>: … need about X GiB, Y GiB is available` when `samples` cannot be rendered. */
void checkMemoryFor(std::size_t samples, const std::string& what);

/** What a terrain setup loads before any drawing: true heights, splat rules, sea level and quadtree layout.
 */
struct LoadedTerrain {
  HeightField heights;            ///< true heights (not exaggerated)
  std::vector<SplatLayer> layers; ///< the setup's rules file; empty: the default rules
  std::optional<float> seaLevel;  ///< true metres, resolved over the heights; nullopt: none
  QuadtreeConfig config;          ///< quadtreeFor(setup, heights)
};

/**
 * Checks `setup` (exaggeration, sea level, splat rules file, procedural relief and memory, quadtree values),
 * naming fields through `name`, and loads it: every check TerrainScene::fromSetup makes before it touches
 * the GPU, so `sylva scene check` makes them too. `maxSide` > 0 limits the field's side (the GPU's largest
 * texture, with `maxSideReason`); 0: no such limit.
 */
LoadedTerrain loadTerrainSetup(const TerrainSetup& setup, const TerrainFieldName& name, int maxSide = 0,
                               const std::string& maxSideReason = {});

} // namespace sylva::terrain

#pragma once
// Streamed terrain options of `sylva render` and `sylva view` (docs/terrain-data.md, "Streaming"):
// --procedural-world or --pyramid DIR, and the budgets.
#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/terrain/TileSource.hpp>
#include <sylva/terrain/gpu/StreamedTerrain.hpp>

#include <CLI/CLI.hpp>

#include <cstdint>
#include <memory>
#include <string>

namespace sylva::app {

struct StreamFlags {
  bool proceduralWorld = false;
  std::string pyramid;
  double gpuBudgetMb = static_cast<double>(terrain::kDefaultGpuBudget) / 1.0e6;
  double ramBudgetMb = static_cast<double>(terrain::kDefaultRamBudget) / 1.0e6;
  CLI::Option* gpuOption = nullptr;
  CLI::Option* ramOption = nullptr;

  void add(CLI::App& command) {
    command.add_flag(
        "--procedural-world", proceduralWorld,
        "Streamed terrain: the 2^20 x 2^20-sample procedural world (1 m spacing, 1,048 km across; "
        "--seed), generated tile by tile as the camera needs it");
    command.add_option("--pyramid", pyramid,
                       "Streamed terrain: a tile pyramid folder (sylva terrain pyramid)");
    gpuOption =
        command
            .add_option("--gpu-budget", gpuBudgetMb,
                        "Streamed terrain: MB (10^6 bytes) of GPU tile cache (a texture array; at most "
                        "GL_MAX_ARRAY_TEXTURE_LAYERS tiles)")
            ->check(finiteRange(0.1, 1.0e6))
            ->capture_default_str();
    ramOption =
        command
            .add_option("--ram-budget", ramBudgetMb, "Streamed terrain: MB (10^6 bytes) of tiles held in RAM")
            ->check(finiteRange(0.1, 1.0e6))
            ->capture_default_str();
  }
  /** Whether streamed terrain was asked for. */
  bool enabled() const { return proceduralWorld || !pyramid.empty(); }
  /** Throws naming the option when the streamed options do not go together (before any work). */
  void check() const {
    if (proceduralWorld && !pyramid.empty()) {
      fail("--procedural-world and --pyramid {}: give one streamed source", pyramid);
    }
    if (!enabled() && (gpuOption->count() > 0 || ramOption->count() > 0)) {
      fail("--gpu-budget and --ram-budget apply to streamed terrain (--procedural-world or --pyramid DIR)");
    }
  }
  /** The tile source (`seed`: the procedural world's). */
  std::shared_ptr<const terrain::TileSource> source(std::uint64_t seed) const {
    if (!pyramid.empty()) {
      return terrain::pyramidSource(pyramid);
    }
    return std::make_shared<terrain::ProceduralWorld>(terrain::defaultLandscapeSpec(seed));
  }
  /** Budgets. */
  terrain::StreamedTerrainOptions options() const {
    terrain::StreamedTerrainOptions o;
    o.gpuBudget = static_cast<std::size_t>(gpuBudgetMb * 1.0e6);
    o.ramBudget = static_cast<std::size_t>(ramBudgetMb * 1.0e6);
    return o;
  }
};

} // namespace sylva::app

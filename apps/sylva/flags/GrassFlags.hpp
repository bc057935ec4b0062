#pragma once
// Command-line options for the grass field on a terrain (`sylva render --grass`, `sylva view --grass`,
// `sylva bench grass`).

#include <sylva/grass/gpu/GrassRenderer.hpp>
#include <sylva/scene/SceneGrass.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace sylva::app {

/** --grass and its settings. */
struct GrassFlags {
  bool enabled = false;
  /** "procedural", or comma-separated blade-model files (sylva capture output, e.g. data/blades/slim.json).
   */
  std::string types = "procedural";
  grass::FieldSettings field = defaultField();
  grass::CullSettings cull;
  std::string lod = "12,35";
  std::string view = "shaded";
  std::string paint;
  std::string layer = "grass";
  /** Steepest ground with grass, true degrees (a scene file's max_slope). */
  float maxSlope = 38.0f;
  /** Accept blade models outside grass::BladeSizeLimits (a scene file's extreme_blades). */
  bool extremeBlades = false;
  float windSpeed = 3.0f;
  float windDirection = 30.0f;
  float gusts = 0.8f;
  std::uint64_t windSeed = 5;

  static grass::FieldSettings defaultField();
  /** Adds --grass, --grass-types, --grass-extreme-blades, --grass-blades, --grass-per-tile, --grass-tile,
   * --grass-density,
   * --grass-coverage, --grass-seed, --grass-paint, --grass-layer, --grass-max-slope, --grass-distance,
   * --grass-lod, --grass-view, --wind-speed, --wind-direction, --wind-gusts, --wind-seed (the wind options
   * are the scene's wind: trees read them too, with or without --grass). */
  void add(CLI::App& command);
  /** Throws naming the option when a value is malformed (before any work is done). */
  void check() const;
  /** The culling settings with --grass-lod applied. */
  grass::CullSettings cullSettings() const;
  wind::WindSettings wind() const;
  grass::GrassView grassView() const;
  /** The grass layer these options describe (what a scene file's grass entry holds, with --grass-lod's
   * culling). */
  scene::GrassLayer layerDesc() const;
  /** The option a grass layer field comes from: "blades" → "--grass-types", "paint" → "--grass-paint". */
  static std::string option(std::string_view field);
};

/** "shaded" | "lod" | "tiles" → GrassView; throws naming the option otherwise. */
grass::GrassView parseGrassView(const std::string& name);

} // namespace sylva::app

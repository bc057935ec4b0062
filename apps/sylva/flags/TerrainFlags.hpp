#pragma once

#include <sylva/scene/gpu/StartView.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>

#include "flags/SourceOptions.hpp"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace sylva::app {

/**
 * --sea-level auto|none|METRES: where the water surface and the default coast line are. auto = 0 m when the
 * heights go below 0 m (bathymetry, coastal DEMs), else none.
 */
struct SeaLevelFlag {
  std::string text = "auto";
  void add(CLI::App& command);
  /** The rule the text says; throws naming the option on a bad value. */
  terrain::SeaLevelRule rule() const;
};

/** Command-line options that describe a terrain scene to render, view or benchmark. */
struct TerrainFlags {
  /** Heights: --dem or --seed/--spec; without either, the demo landscape (TerrainSource::defaultProcedural).
   */
  SourceOptions source{terrain::TerrainSource::defaultProcedural(), 1025, 2.0f};
  std::string method = "ours";
  std::string layers;
  float exaggeration = 1.0f;
  SeaLevelFlag seaLevel;
  terrain::QuadtreeConfig quadtree = terrain::TerrainSetup::defaultQuadtree();
  /** --terrain-geomorph / --no-terrain-geomorph: TerrainSceneOptions::geomorph (default off). */
  bool geomorph = false;

  /** Adds the source options (SourceOptions) and --layers, --exaggeration, --sea-level, --method, --tess,
   * --roots, --max-depth, --lod-factor, --lod-error, --terrain-geomorph. */
  void add(CLI::App& command);
  /** The terrain the options describe (throws naming the option when they do not go together). */
  terrain::TerrainSetup setup() const;
  /** Loads the heights and builds the scene (TerrainScene::fromSetup; needs a GL context); errors name the
   * file or option. */
  std::unique_ptr<terrain::TerrainScene> build(const shader::Library& library) const;
  /** The quadtree layout for `field` (terrain::quadtreeFor): four roots across by default, or --roots. */
  terrain::QuadtreeConfig configFor(const terrain::HeightField& field) const;

  int rootCount = 0;
  CLI::Option* maxDepthOption = nullptr;

private:
  /** The quadtree part of setup(): tessellation, LOD factor, crack method, --roots, --max-depth. */
  terrain::TerrainSetup layout() const;
};

/**
 * Where the camera of a render or of the viewer's first frame is: --view-from (compass framing), --fov,
 * --camera-pos and --look-at (world metres: x east, y up in the data's metres, z south), --fog.
 */
struct CameraFlags {
  std::string viewFrom = "south-west";
  float fovDegrees = 50.0f;
  std::string cameraPos;
  std::string lookAt;
  float fog = 0.5f;
  CLI::Option* fovOption = nullptr;

  void add(CLI::App& command);
  /** Throws naming the option when a value is malformed (before any work is done). */
  void check() const;
  /** The camera the options place (parsed; throws naming the option when malformed). */
  scene::CameraPlacement placement() const;
  /** The camera for `scene` at `aspect` (width / height), with clip planes fitted to the scene. */
  render::Camera camera(const terrain::TerrainScene& scene, float aspect) const;
};

/** The option a terrain setup field comes from: "sea_level" → "--sea-level", "tess_level" → "--tess". */
std::string terrainOption(std::string_view field);

/** "paper" | "ours" | "none" → CrackMethod; throws sylva::Error naming the option otherwise. */
terrain::CrackMethod parseCrackMethod(const std::string& name);
/** "shaded" | "lod" | "normals" | "splat" → TerrainView. */
terrain::TerrainView parseTerrainView(const std::string& name);

} // namespace sylva::app

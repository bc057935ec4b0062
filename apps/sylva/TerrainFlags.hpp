#pragma once

#include <sylva/terrain/TerrainScene.hpp>

#include "SourceOptions.hpp"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace sylva::app {

/**
 * Peak bytes per height sample of a render or viewer session (measured: `sylva render --size 8192` peaks at
 * 1.27 GiB for 67 M samples on llvmpipe, where GPU textures live in process memory).
 */
inline constexpr std::size_t kRenderBytesPerSample = 20;
/** Samples a render can afford with the memory available now (/proc/meminfo MemAvailable). */
std::size_t affordableSamples();
/** Throws `<option>: ... need about X GiB, Y GiB is available` when `samples` cannot be rendered. */
void checkMemoryFor(std::size_t samples, const std::string& option);

/**
 * --sea-level auto|none|METRES: where the water surface and the default coast line are. auto = 0 m when the
 * heights go below 0 m (bathymetry, coastal DEMs), else none.
 */
struct SeaLevelFlag {
  std::string text = "auto";
  void add(CLI::App& command);
  /** The sea level in metres for heights down to `minHeight`, or nullopt for none; throws on a bad value. */
  std::optional<float> resolve(float minHeight) const;
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
  terrain::QuadtreeConfig quadtree = defaultQuadtree();
  /** --terrain-geomorph / --no-terrain-geomorph: TerrainSceneOptions::geomorph (default off). */
  bool geomorph = false;

  /** Adds the source options (SourceOptions) and --layers, --exaggeration, --sea-level, --method, --tess,
   * --roots, --max-depth, --lod-factor, --terrain-geomorph. */
  void add(CLI::App& command);
  /** Loads the heights and builds the scene (needs a GL context); errors name the file or option. */
  std::unique_ptr<terrain::TerrainScene> build(const shader::Library& library) const;
  /** The quadtree layout for `field`: 512 m roots by default, or the --roots count. */
  terrain::QuadtreeConfig configFor(const terrain::HeightField& field) const;

  int rootCount = 0;
  CLI::Option* maxDepthOption = nullptr;
  static terrain::QuadtreeConfig defaultQuadtree();
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
  /** The camera for `scene` at `aspect` (width / height), with clip planes fitted to the scene. */
  render::Camera camera(const terrain::TerrainScene& scene, float aspect) const;
};

/** "paper" | "ours" | "none" → CrackMethod; throws sylva::Error naming the option otherwise. */
terrain::CrackMethod parseCrackMethod(const std::string& name);
/** "shaded" | "lod" | "normals" | "splat" → TerrainView. */
terrain::TerrainView parseTerrainView(const std::string& name);

} // namespace sylva::app

#pragma once

#include <sylva/terrain/TerrainScene.hpp>

#include "SourceOptions.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace sylva::app {

/** Command-line options that describe a terrain scene to render, view or benchmark. */
struct TerrainFlags {
  /** Heights: --dem or --seed/--spec; without either, the demo landscape (TerrainSource::defaultProcedural).
   */
  SourceOptions source{terrain::TerrainSource::defaultProcedural(), 1025, 2.0f};
  std::string method = "ours";
  std::string layers;
  terrain::QuadtreeConfig quadtree = defaultQuadtree();

  /** Adds the source options (SourceOptions) and --layers, --method, --tess, --roots, --max-depth,
   * --lod-factor. */
  void add(CLI::App& command);
  /** Loads the heights and builds the scene (needs a GL context); errors name the file or option. */
  std::unique_ptr<terrain::TerrainScene> build(const shader::Library& library) const;
  /** The quadtree layout for `field`: 512 m roots by default, or the --roots count. */
  terrain::QuadtreeConfig configFor(const terrain::HeightField& field) const;

  int rootCount = 0;
  CLI::Option* maxDepthOption = nullptr;
  static terrain::QuadtreeConfig defaultQuadtree();
};

/** "paper" | "ours" | "none" → CrackMethod; throws sylva::Error naming the option otherwise. */
terrain::CrackMethod parseCrackMethod(const std::string& name);
/** "shaded" | "lod" | "normals" | "splat" → TerrainView. */
terrain::TerrainView parseTerrainView(const std::string& name);

} // namespace sylva::app

#pragma once

#include <sylva/terrain/TerrainScene.hpp>

#include <CLI/CLI.hpp>

#include <string>

namespace sylva::app {

/** Command-line options that describe a terrain scene to render, view or benchmark. */
struct TerrainFlags {
  terrain::TerrainSource source;
  std::string type = "warped";
  std::string method = "ours";
  std::string layers;
  terrain::QuadtreeConfig quadtree = defaultQuadtree();

  /** Adds --dem, --seed, --type, --size, --spacing, --height-scale, --layers, --method, --tess, ... */
  void add(CLI::App& command);
  /** Loads the heights and builds the scene (needs a GL context); errors name the file or option. */
  std::unique_ptr<terrain::TerrainScene> build(const shader::Library& library) const;
  /** The quadtree layout for `field`: 512 m roots by default, or the --roots count. */
  terrain::QuadtreeConfig configFor(const terrain::HeightField& field) const;

  int rootCount = 0;
  static terrain::QuadtreeConfig defaultQuadtree();
};

/** "paper" | "ours" | "none" → CrackMethod; throws sylva::Error naming the option otherwise. */
terrain::CrackMethod parseCrackMethod(const std::string& name);
/** "shaded" | "lod" | "normals" | "splat" → TerrainView. */
terrain::TerrainView parseTerrainView(const std::string& name);

} // namespace sylva::app

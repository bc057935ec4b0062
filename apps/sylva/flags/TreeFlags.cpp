#include "flags/TreeFlags.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/scene/gpu/Ground.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include "flags/SourceOptions.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace sylva::app {

trees::ForestSettings TreeFlags::defaultForest() {
  trees::ForestSettings f;
  f.species = {"almond", "quaking-aspen", "california-black-oak", "black-tupelo"};
  f.count = 300;
  f.regionRadius = 150.0f;
  f.seed = 3;
  f.spacing = 6.0f;
  f.maxSlope = 28.0f;
  return f;
}

void TreeFlags::add(CLI::App& command) {
  command.add_flag("--trees", enabled, "Grow a forest of piece-built trees on the terrain (docs/trees.md)");
  command
      .add_option("--trees-species", forest.species,
                  "Species mix: presets (sylva tree species) or species JSON files, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  command.add_option("--trees-count", forest.count, "Trees to place (fewer where the ground runs out)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  command.add_option("--trees-seed", forest.seed, "Seed of placement, topologies and poses")
      ->capture_default_str();
  command
      .add_option("--trees-radius", forest.regionRadius,
                  "Trees grow within this many metres of the terrain's centre (0: anywhere on it)")
      ->check(finiteRange(0.0, 1.0e6))
      ->capture_default_str();
  command.add_option("--trees-spacing", forest.spacing, "Minimum distance between trunks, metres")
      ->check(finiteRange(0.0, 1000.0))
      ->capture_default_str();
  command.add_option("--trees-max-slope", forest.maxSlope, "Steepest ground a tree grows on, degrees")
      ->check(finiteRange(0.0, 90.0))
      ->capture_default_str();
  command
      .add_option("--trees-autumn", forest.autumn,
                  "Season of the leaves: 0 summer green to 1 each species' full autumn colour")
      ->check(finiteRange(0.0, 1.0))
      ->capture_default_str();
  command
      .add_option("--trees-leaf-fall", forest.leafFall,
                  "Share of the deciduous species' leaves fallen: 0 none to 1 bare winter crowns (evergreens "
                  "keep theirs)")
      ->check(finiteRange(0.0, 1.0))
      ->capture_default_str();
  command.add_option("--trees-pixels", lod.pixelsPerSegment, "Tessellation target: pixels per segment")
      ->check(finiteRange(0.5, 100.0))
      ->capture_default_str();
  command.add_option("--trees-max-level", lod.maxLevel, "Largest tessellation level (1 … 64)")
      ->check(finiteRange(1.0, 64.0))
      ->capture_default_str();
  command
      .add_option("--trees-level", lod.fixedLevel, "Fixed tessellation level for every quad (0: by distance)")
      ->check(finiteRange(0.0, 64.0))
      ->capture_default_str();
  command.add_option("--trees-distance", lod.drawDistance, "Draw distance of tree pieces, metres (0: all)")
      ->check(finiteRange(0.0, 1.0e6))
      ->capture_default_str();
  command
      .add_option("--trees-min-pixels", lod.minPixels,
                  "Size culling: pieces whose bounding sphere spans fewer pixels are not drawn (0: off)")
      ->check(finiteRange(0.0, 100.0))
      ->capture_default_str();
  command
      .add_option("--trees-min-width", lod.minWidthPixels,
                  "Width culling: branches thinner than this many pixels are not drawn (0: off)")
      ->check(finiteRange(0.0, 100.0))
      ->capture_default_str();
  command
      .add_option(
          "--trees-view", view,
          "Trees view: shaded, pieces (piece types), bones (root weights), lod, tiles (bark tile ids)")
      ->check(CLI::IsMember({"shaded", "pieces", "bones", "lod", "tiles"}))
      ->capture_default_str();
  command.add_flag("--trees-wind,!--no-trees-wind", wind,
                   "Trees sway in the wind of --wind-speed, --wind-direction, --wind-gusts, --wind-seed "
                   "(joint springs; --no-trees-wind or --trees-wind=false: rest pose)");
  command
      .add_option("--trees-bark", bark,
                  "Bark tiles: auto (each species' photos from --trees-bark-photos, else procedural), "
                  "procedural, none (flat colours), or a tile-set directory from 'sylva texsynth tiles'")
      ->capture_default_str();
  command.add_option(
      "--trees-bark-photos", barkPhotos,
      "Directory of <name>_color_1k.jpg / <name>_normal_1k.jpg bark photos (default: the data "
      "folder's external/ez-tree/bark, where scripts/fetch-sample-data.sh puts oak, birch, pine, "
      "willow; a directory named here must exist)");
  command.add_option("--trees-bark-tile", barkTile, "Bark tile size, texels")
      ->check(CLI::Range(8, 512))
      ->capture_default_str();
  command.add_option("--trees-bark-variants", barkVariants, "Bark tiles per tile class and edge colouring")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command.add_flag("--trees-foliage,!--no-trees-foliage", foliage,
                   "Leaves as 2.5D impostors at the branch tips (--no-trees-foliage: bare trees)");
  command
      .add_option("--trees-leaves", leaves,
                  "Leaf image: a PNG with alpha, auto (ez-tree's oak leaf when fetched, else procedural) or "
                  "procedural")
      ->capture_default_str();
  command.add_option("--trees-leaf-model", leafModel,
                     "Leaf-cloud model (OBJ, glTF, … through Assimp) instead of procedural leaf cards");
  command
      .add_option("--trees-far", farDistance,
                  "Trees farther than this many metres become octahedral impostors (0: never)")
      ->check(finiteRange(0.0, 1.0e6))
      ->capture_default_str();
  command.add_option("--trees-far-band", farBand, "Metres over which trees dissolve into their impostors")
      ->check(finiteRange(0.1, 1.0e4))
      ->capture_default_str();
  command
      .add_option("--trees-far-count", farCount,
                  "Impostor-only trees added around the forest out to the terrain's edge (needs --trees-far)")
      ->check(CLI::Range(0, 2000000))
      ->capture_default_str();
}

trees::ForestLook TreeFlags::look() const {
  trees::ForestLook l;
  l.bark = bark;
  l.barkPhotos = barkPhotos;
  l.barkTile = barkTile;
  l.barkVariants = barkVariants;
  l.foliage = foliage;
  l.leaves = leaves;
  l.leafModel = leafModel;
  l.farDistance = farDistance;
  l.farBand = farBand;
  l.farCount = farCount;
  return l;
}

void TreeFlags::check() const {
  trees::validate(forest, "--trees");
  for (const std::string& s : forest.species) {
    try {
      (void)trees::resolveSpecies(s);
    } catch (const Error& e) {
      fail("--trees-species: {}", e.what());
    }
  }
  (void)parseTreeView(view);
  trees::check(look(), [](std::string_view field) {
    std::string option = "--trees-" + std::string(field);
    std::replace(option.begin(), option.end(), '_', '-');
    return option;
  });
}

trees::TreeView parseTreeView(const std::string& name) {
  if (name == "shaded")
    return trees::TreeView::Shaded;
  if (name == "pieces")
    return trees::TreeView::PieceTypes;
  if (name == "bones")
    return trees::TreeView::Bones;
  if (name == "lod")
    return trees::TreeView::LodLevels;
  if (name == "tiles")
    return trees::TreeView::Tiles;
  fail("--trees-view: '{}' is not one of shaded, pieces, bones, lod, tiles", name);
}

trees::TreeView TreeFlags::treeView() const {
  return parseTreeView(view);
}

scene::ForestDesc TreeFlags::forestDesc() const {
  scene::ForestDesc f;
  for (const std::string& species : forest.species) {
    f.species[species] = 1.0f;
  }
  f.count = forest.count;
  f.seed = forest.seed;
  f.spacing = forest.spacing;
  f.maxSlope = forest.maxSlope;
  f.autumn = forest.autumn;
  f.leafFall = forest.leafFall;
  f.clusterSize = forest.clusterSize;
  f.bare = forest.bare;
  f.regionRadius = forest.regionRadius;
  f.regionAroundCentre = forest.regionRadius > 0.0f;
  f.look = look();
  f.wind = wind;
  return f;
}

} // namespace sylva::app

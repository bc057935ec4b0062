#include <sylva/trees/ForestLook.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sylva::trees {

void check(const ForestLook& look, const FieldName& name) {
  if (look.bark != "auto" && look.bark != "procedural" && look.bark != "none" &&
      !std::filesystem::is_directory(look.bark)) {
    fail("{}: '{}' is not auto, procedural, none or a tile-set directory", fieldName(name, "bark"),
         look.bark);
  }
  if (look.leaves != "auto" && look.leaves != "procedural" &&
      !std::filesystem::is_regular_file(look.leaves)) {
    fail("{}: '{}' is not auto, procedural or an image file", fieldName(name, "leaves"), look.leaves);
  }
  if (!look.barkPhotos.empty() && !std::filesystem::is_directory(look.barkPhotos)) {
    fail("{}: no directory '{}'", fieldName(name, "bark_photos"), look.barkPhotos.string());
  }
  if (!look.leafModel.empty() && !std::filesystem::is_regular_file(look.leafModel)) {
    fail("{}: no file '{}'", fieldName(name, "leaf_model"), look.leafModel.string());
  }
  if (!(look.farDistance >= 0.0f) || !std::isfinite(look.farDistance)) {
    fail("{}: {} is not a distance >= 0 in metres", fieldName(name, "far_distance"), look.farDistance);
  }
  if (!(look.farBand > 0.0f) || !std::isfinite(look.farBand)) {
    fail("{}: {} is not a band > 0 in metres", fieldName(name, "far_band"), look.farBand);
  }
  if (look.farCount < 0) {
    fail("{}: {} is negative", fieldName(name, "far_count"), look.farCount);
  }
}

std::optional<BarkSources> barkSources(const ForestLook& look) {
  if (look.bark == "none") {
    return std::nullopt;
  }
  BarkSources s;
  s.mode = look.bark;
  if (!look.barkPhotos.empty()) {
    s.photoDir = look.barkPhotos;
  }
  s.tiles.tileSize = look.barkTile;
  s.variants = look.barkVariants;
  // Synthesised sets are cached per user, as build tools cache their work.
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  if (xdg != nullptr && *xdg != '\0') {
    s.cacheDir = std::filesystem::path(xdg) / "sylva" / "bark";
  } else if (home != nullptr && *home != '\0') {
    s.cacheDir = std::filesystem::path(home) / ".cache" / "sylva" / "bark";
  }
  return s;
}

std::vector<FarTree> farFieldTrees(const ForestLook& look, const ForestSettings& placement,
                                   const Forest& forest, std::span<const glm::vec4> centres,
                                   const FarGround& ground) {
  std::vector<FarTree> extra;
  if (look.farCount <= 0 || ground.field == nullptr) {
    return extra;
  }
  const terrain::HeightField& field = *ground.field;
  FarTreeFieldSettings s;
  s.count = look.farCount;
  s.seed = placement.seed + 17;
  s.centre = glm::vec2(field.extentX(), field.extentZ()) * 0.5f;
  s.innerRadius = placement.regionRadius;
  s.outerRadius = 0.5f * std::hypot(field.extentX(), field.extentZ());
  s.species = static_cast<int>(std::max<std::size_t>(forest.species.size(), 1));
  s.verticalScale = 1.0f; // the field holds drawn heights
  s.firstId = static_cast<std::uint32_t>(forest.trees.size());
  if (!centres.empty()) {
    s.minHeight = s.maxHeight = centres[0].w;
    for (const glm::vec4& c : centres) {
      s.minHeight = std::min(s.minHeight, c.w);
      s.maxHeight = std::max(s.maxHeight, c.w);
    }
  }
  const float floor = ground.floor.value_or(-1e30f);
  // The placement's height band (drawn metres); without a top, no higher than the forest's highest tree: the
  // far field continues the forest and does not climb past its tree line onto snow and rock.
  const float bandLow = std::isnan(placement.minHeight) ? -1e30f : placement.minHeight;
  float bandHigh = placement.maxHeight;
  if (std::isnan(bandHigh)) {
    bandHigh = 1e30f;
    if (!forest.trees.empty()) {
      bandHigh = -1e30f;
      for (const ForestTree& tree : forest.trees) {
        bandHigh = std::max(bandHigh, tree.base[3].y);
      }
    }
  }
  // Only where trees may grow: above the sea, in the band, not steeper than the placement's max slope.
  const float maxGrade = std::tan(glm::radians(placement.maxSlope));
  auto height = [&](float x, float z) {
    return terrain::heightAt(field, std::clamp(x, 0.0f, field.extentX()),
                             std::clamp(z, 0.0f, field.extentZ()));
  };
  for (const FarTree& t : farTreeField(s, &field)) {
    const float step = 2.0f;
    const float gx = (height(t.position.x + step, t.position.z) - height(t.position.x - step, t.position.z)) /
                     (2.0f * step);
    const float gz = (height(t.position.x, t.position.z + step) - height(t.position.x, t.position.z - step)) /
                     (2.0f * step);
    if (t.position.y >= floor && t.position.y >= bandLow && t.position.y <= bandHigh &&
        std::hypot(gx, gz) <= maxGrade) {
      extra.push_back(t);
    }
  }
  return extra;
}

} // namespace sylva::trees

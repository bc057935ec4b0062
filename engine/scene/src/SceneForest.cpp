#include <sylva/scene/SceneForest.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/trees/Species.hpp>

#include <fmt/format.h>

#include <cmath>

namespace sylva::scene {

FieldName sceneForestFieldName(const std::filesystem::path& file, std::size_t index) {
  return [file = file.string(), index](std::string_view field) {
    return fmt::format("{}: /forests/{}/{}", file, index, field);
  };
}

trees::ForestSettings forestSettings(const ForestDesc& f, float exaggeration, std::optional<float> seaLevel,
                                     const FieldName& name, glm::vec2 footprint,
                                     std::optional<float> treeLine) {
  trees::ForestSettings s;
  s.species.clear();
  for (const auto& [species, weight] : f.species) {
    try {
      (void)trees::resolveSpecies(species);
    } catch (const Error& error) {
      fail("{}: {}", fieldName(name, "species/" + species), error.what());
    }
    s.species.push_back(species);
    s.speciesWeights.push_back(weight);
  }
  s.count = f.count;
  s.seed = f.seed;
  s.spacing = f.spacing;
  s.maxSlope = f.maxSlope;
  s.autumn = f.autumn;
  s.leafFall = f.leafFall;
  s.clusterSize = f.clusterSize;
  s.bare = f.bare;
  s.verticalScale = 1.0f; // placement reads the drawn (already exaggerated) heights
  if (f.minHeight) {
    s.minHeight = *f.minHeight;
  } else if (seaLevel) {
    s.minHeight = (*seaLevel + 0.5f) * exaggeration;
  }
  if (f.maxHeight) {
    s.maxHeight = *f.maxHeight;
  } else if (treeLine && (std::isnan(s.minHeight) || *treeLine * exaggeration > s.minHeight)) {
    s.maxHeight = *treeLine * exaggeration; // no trees on snow
  }
  if (f.regionCentre) {
    s.regionCentre = *f.regionCentre;
    s.regionRadius = f.regionRadius;
  } else if (f.regionAroundCentre) {
    s.regionCentre = 0.5f * footprint;
    s.regionRadius = f.regionRadius;
  } else {
    s.regionRadius = 0.0f; // no region: the whole terrain
  }
  if (!f.densityMap.empty()) {
    const Image image = loadImage(f.densityMap);
    s.densityWidth = image.width();
    s.densityHeight = image.height();
    s.densityMap.resize(static_cast<std::size_t>(image.width()) * image.height());
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) {
        s.densityMap[static_cast<std::size_t>(y) * image.width() + x] = image.get(x, y, 0);
      }
    }
  }
  const std::string where = fieldName(name, "");
  trees::validate(s, where.ends_with('/') ? where.substr(0, where.size() - 1) : where);
  return s;
}

trees::ForestLook forestLook(const ForestDesc& f, const FieldName& name) {
  if (f.look) {
    trees::check(*f.look, name);
    return *f.look;
  }
  trees::ForestLook look;
  look.bark = f.bark;
  look.foliage = f.foliage;
  look.farDistance = f.farDistance;
  look.farBand = f.farBand;
  look.farCount = f.farCount;
  trees::check(look, name);
  return look;
}

} // namespace sylva::scene

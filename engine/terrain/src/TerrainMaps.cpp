#include <sylva/terrain/TerrainMaps.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/JsonNode.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Parallel.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <utility>

namespace sylva::terrain {
namespace {

constexpr int kLayerRulesVersion = 1;

float saturate(float v) {
  return std::clamp(v, 0.0f, 1.0f);
}

float ramp(float v, float lo, float hi, float blend) {
  if (blend > 0.0f) {
    return saturate((v - lo) / blend + 0.5f) * saturate((hi - v) / blend + 0.5f);
  }
  return v >= lo && v <= hi ? 1.0f : 0.0f;
}

void validateLayer(const SplatLayer& layer, const std::string& where, std::size_t k) {
  const auto bad = [&](const char* field, const std::string& reason) {
    fail("{}: /layers/{}/{}: {}", where, k, field, reason);
  };
  if (layer.name.empty()) {
    bad("name", "must not be empty");
  }
  const std::pair<const char*, float> numbers[] = {
      {"minHeight", layer.minHeight}, {"maxHeight", layer.maxHeight},     {"minSlope", layer.minSlope},
      {"maxSlope", layer.maxSlope},   {"heightBlend", layer.heightBlend}, {"slopeBlend", layer.slopeBlend}};
  for (const auto& [field, value] : numbers) {
    if (!std::isfinite(value)) {
      bad(field, "must be finite");
    }
  }
  if (layer.maxHeight < layer.minHeight) {
    bad("maxHeight", fmt::format("{} is below minHeight {}", layer.maxHeight, layer.minHeight));
  }
  if (layer.maxSlope < layer.minSlope) {
    bad("maxSlope", fmt::format("{} is below minSlope {}", layer.maxSlope, layer.minSlope));
  }
  if (layer.heightBlend < 0.0f) {
    bad("heightBlend", fmt::format("{} must be >= 0 metres", layer.heightBlend));
  }
  if (layer.slopeBlend < 0.0f) {
    bad("slopeBlend", fmt::format("{} must be >= 0 degrees", layer.slopeBlend));
  }
}

void validateLayers(std::span<const SplatLayer> layers, const std::string& where) {
  if (layers.empty() || layers.size() > static_cast<std::size_t>(kMaxSplatLayers)) {
    fail("{}: /layers: {} layers is not in 1..{}", where, layers.size(), kMaxSplatLayers);
  }
  std::set<std::string> names;
  for (std::size_t k = 0; k < layers.size(); ++k) {
    validateLayer(layers[k], where, k);
    if (!names.insert(layers[k].name).second) {
      fail("{}: /layers/{}/name: duplicate layer name '{}'", where, k, layers[k].name);
    }
  }
}

} // namespace

Image sobelNormalMap(const HeightField& field, const SobelOptions& options) {
  const int w = field.width();
  const int h = field.height();
  if (w < 1 || h < 1) {
    fail("sobelNormalMap: empty height field");
  }
  if (!std::isfinite(field.spacingX()) || !std::isfinite(field.spacingZ()) || field.spacingX() <= 0.0f ||
      field.spacingZ() <= 0.0f) {
    fail("sobelNormalMap: spacing {} x {} must be finite and > 0 metres", field.spacingX(), field.spacingZ());
  }
  Image out(w, h, 3, PixelType::F32);
  float* normals = out.values<float>().data();
  const float invX = 1.0f / (8.0f * field.spacingX());
  const float invZ = 1.0f / (8.0f * field.spacingZ());
  parallelFor(
      static_cast<std::size_t>(h),
      [&](std::size_t begin, std::size_t end) {
        for (int j = static_cast<int>(begin); j < static_cast<int>(end); ++j) {
          for (int i = 0; i < w; ++i) {
            float* n = normals + (static_cast<std::size_t>(j) * w + i) * 3;
            const float centre = field.at(i, j);
            if (std::isnan(centre)) {
              n[0] = 0.0f;
              n[1] = 1.0f;
              n[2] = 0.0f;
              continue;
            }
            const auto s = [&](int a, int b) {
              int x = i + a;
              int y = j + b;
              if (x < 0 || x >= w || y < 0 || y >= h) {
                if (options.border == BorderMode::Constant) {
                  return options.constantHeight;
                }
                x = std::clamp(x, 0, w - 1);
                y = std::clamp(y, 0, h - 1);
              }
              const float v = field.at(x, y);
              return std::isnan(v) ? centre : v;
            };
            const float gx =
                ((s(1, -1) + 2.0f * s(1, 0) + s(1, 1)) - (s(-1, -1) + 2.0f * s(-1, 0) + s(-1, 1))) * invX;
            const float gz =
                ((s(-1, 1) + 2.0f * s(0, 1) + s(1, 1)) - (s(-1, -1) + 2.0f * s(0, -1) + s(1, -1))) * invZ;
            const float len = std::sqrt(gx * gx + 1.0f + gz * gz);
            n[0] = -gx / len;
            n[1] = 1.0f / len;
            n[2] = -gz / len;
          }
        }
      },
      std::max<std::size_t>(1, 4096 / static_cast<std::size_t>(w)));
  return out;
}

float splatWeight(const SplatLayer& layer, float height, float slopeDegrees) {
  return ramp(height, layer.minHeight, layer.maxHeight, layer.heightBlend) *
         ramp(slopeDegrees, layer.minSlope, layer.maxSlope, layer.slopeBlend);
}

std::vector<Image> splatMap(const HeightField& field, const Image& normals,
                            std::span<const SplatLayer> layers, float verticalScale) {
  validateLayers(layers, "splatMap");
  if (!std::isfinite(verticalScale) || verticalScale <= 0.0f) {
    fail("splatMap: vertical scale {} must be finite and > 0", verticalScale);
  }
  const int w = field.width();
  const int h = field.height();
  if (normals.width() != w || normals.height() != h || normals.type() != PixelType::F32 ||
      normals.channels() < 3) {
    fail("splatMap: normals must be a {}x{} RGB(A) float image (got {}x{}, {} channels, {})", w, h,
         normals.width(), normals.height(), normals.channels(), pixelTypeName(normals.type()));
  }
  const std::size_t count = layers.size();
  const std::size_t pageCount = (count + 3) / 4;
  std::vector<Image> pages;
  pages.reserve(pageCount);
  for (std::size_t k = 0; k < pageCount; ++k) {
    pages.emplace_back(w, h, 4, PixelType::F32);
  }
  std::vector<float*> pageData;
  pageData.reserve(pages.size());
  for (Image& page : pages) {
    pageData.push_back(page.values<float>().data());
  }
  const float* normalData = normals.values<float>().data();
  const auto normalChannels = static_cast<std::size_t>(normals.channels());
  parallelFor(
      static_cast<std::size_t>(h),
      [&](std::size_t begin, std::size_t end) {
        std::vector<float> weights(count);
        for (std::size_t j = begin; j < end; ++j) {
          for (std::size_t i = 0; i < static_cast<std::size_t>(w); ++i) {
            const std::size_t pixel = j * static_cast<std::size_t>(w) + i;
            float height = field.samples()[pixel];
            if (std::isnan(height)) {
              continue; // pages are zero-initialised: no terrain, no texture
            }
            const float ny = std::clamp(normalData[pixel * normalChannels + 1], -1.0f, 1.0f);
            float slope = std::acos(ny) * (180.0f / std::numbers::pi_v<float>);
            if (verticalScale != 1.0f) {
              height = height / verticalScale;
              slope = std::atan(std::sqrt(std::max(0.0f, 1.0f - ny * ny)) / (ny * verticalScale)) *
                      (180.0f / std::numbers::pi_v<float>);
            }
            float sum = 0.0f;
            for (std::size_t l = 0; l < count; ++l) {
              weights[l] = splatWeight(layers[l], height, slope);
              sum += weights[l];
            }
            for (std::size_t l = 0; l < count; ++l) {
              const float value = sum > 0.0f ? weights[l] / sum : (l == 0 ? 1.0f : 0.0f);
              pageData[l / 4][pixel * 4 + l % 4] = value;
            }
          }
        }
      },
      std::max<std::size_t>(1, 4096 / static_cast<std::size_t>(w)));
  return pages;
}

std::vector<SplatLayer> defaultSplatLayers(float minHeight, float maxHeight, std::optional<float> seaLevel) {
  float range = maxHeight - minHeight;
  if (!(range > 0.0f)) {
    range = 1.0f;
  }
  const float hb = 0.04f * range;
  const float sb = 6.0f;
  const float low = std::min(minHeight, seaLevel.value_or(minHeight)) - range;
  const float high = maxHeight + range;
  if (seaLevel) {
    const float s = *seaLevel;
    const float land = std::max(maxHeight - s, 1.0f);
    const float beach = s + std::max(2.0f, 0.02f * land);
    const float beachBlend = std::max(1.0f, 0.01f * land);
    const float snowLine = s + 0.7f * land;
    const float landBlend = 0.04f * land;
    return {
        {"sand", low, beach, 0.0f, 35.0f, beachBlend, sb},
        {"grass", beach, snowLine, 0.0f, 35.0f, beachBlend, sb},
        {"snow", snowLine, std::max(high, snowLine + 1.0f), 0.0f, 35.0f, landBlend, sb},
        {"rock", low, std::max(high, snowLine + 1.0f), 35.0f, 90.0f, landBlend, sb},
    };
  }
  return {
      {"sand", low, minHeight + 0.12f * range, 0.0f, 35.0f, hb, sb},
      {"grass", minHeight + 0.12f * range, minHeight + 0.7f * range, 0.0f, 35.0f, hb, sb},
      {"snow", minHeight + 0.7f * range, high, 0.0f, 35.0f, hb, sb},
      {"rock", low, high, 35.0f, 90.0f, hb, sb},
  };
}

std::optional<float> snowLine(std::span<const SplatLayer> layers) {
  std::optional<float> line;
  for (const SplatLayer& layer : layers) {
    if (layer.name != "snow" || layer.minSlope > 0.0f || !(layer.minHeight > -1.0e8f)) {
      continue;
    }
    const float start = layer.minHeight - 0.5f * layer.heightBlend;
    line = line ? std::min(*line, start) : start;
  }
  return line;
}

nlohmann::json splatLayersToJson(std::span<const SplatLayer> layers) {
  nlohmann::json list = nlohmann::json::array();
  for (const SplatLayer& layer : layers) {
    list.push_back({{"name", layer.name},
                    {"minHeight", layer.minHeight},
                    {"maxHeight", layer.maxHeight},
                    {"minSlope", layer.minSlope},
                    {"maxSlope", layer.maxSlope},
                    {"heightBlend", layer.heightBlend},
                    {"slopeBlend", layer.slopeBlend}});
  }
  return {{"version", kLayerRulesVersion}, {"layers", list}};
}

std::vector<SplatLayer> splatLayersFromJson(const nlohmann::json& json, const std::string& where) {
  requireJsonVersion(json, kLayerRulesVersion, where);
  const JsonNode root(json, where);
  root.object({"version", "layers"});
  const JsonNode list = root["layers"];
  const std::size_t count = list.array(1, static_cast<std::size_t>(kMaxSplatLayers));
  std::vector<SplatLayer> layers;
  for (std::size_t k = 0; k < count; ++k) {
    const JsonNode item = list[k];
    item.object({"name", "minHeight", "maxHeight", "minSlope", "maxSlope", "heightBlend", "slopeBlend"});
    SplatLayer layer;
    layer.name = item["name"].string(true);
    for (auto [key, target] : {std::pair{"minHeight", &layer.minHeight},
                               {"maxHeight", &layer.maxHeight},
                               {"minSlope", &layer.minSlope},
                               {"maxSlope", &layer.maxSlope},
                               {"heightBlend", &layer.heightBlend},
                               {"slopeBlend", &layer.slopeBlend}}) {
      if (item.has(key)) {
        *target = item[key].real(-1.0e30, 1.0e30);
      }
    }
    layers.push_back(layer);
  }
  validateLayers(layers, where);
  return layers;
}

std::vector<SplatLayer> loadSplatLayers(const std::filesystem::path& path) {
  return splatLayersFromJson(loadJsonFile(path), path.string());
}

void saveSplatLayers(const std::filesystem::path& path, std::span<const SplatLayer> layers) {
  validateLayers(layers, path.string());
  saveJsonFile(path, splatLayersToJson(layers));
}

} // namespace sylva::terrain

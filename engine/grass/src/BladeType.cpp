#include <sylva/grass/BladeType.hpp>

#include <sylva/core/Error.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::grass {
namespace {

/** A procedural blade: an arc curving towards its face by `curl` radians, widths from `profile`. */
BladeType arcBlade(const char* name, float length, float width, float curl, float (*profile)(float),
                   glm::vec3 colour, float stiffness) {
  constexpr int kSamples = 64;
  std::vector<glm::vec3> knots(kSamples);
  std::vector<float> widths(kSamples);
  glm::vec3 p(0.0f);
  const float ds = length / static_cast<float>(kSamples - 1);
  for (int i = 0; i < kSamples; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(kSamples - 1);
    if (i > 0) {
      const float angle = curl * (t - 0.5f / static_cast<float>(kSamples - 1));
      p += glm::vec3(0.0f, std::cos(angle), std::sin(angle)) * ds;
    }
    knots[i] = p;
    widths[i] = width * profile(t);
  }
  BladeType type;
  type.name = name;
  for (std::size_t l = 0; l < kLodKnots.size(); ++l) {
    type.lods[l] = resampleBlade(knots, widths, kLodKnots[l]);
  }
  type.colour = colour;
  type.stiffness = stiffness;
  return type;
}

float slimProfile(float t) {
  return 1.0f - 0.3f * t - 0.7f * std::pow(t, 6.0f);
}
float fineProfile(float t) {
  return std::pow(1.0f - t, 0.5f);
}
float broadProfile(float t) {
  return t < 0.4f ? 0.5f + 0.5f * std::sin(1.5707963f * t / 0.4f) : (1.0f - t) / 0.6f;
}

float polylineLength(const std::vector<glm::vec3>& knots) {
  float length = 0.0f;
  for (std::size_t i = 1; i < knots.size(); ++i) {
    length += glm::length(knots[i] - knots[i - 1]);
  }
  return length;
}

} // namespace

float BladeType::length() const {
  return polylineLength(lods[0].knots);
}

BladeShapeLod resampleBlade(const std::vector<glm::vec3>& knots, const std::vector<float>& widths,
                            int count) {
  if (knots.size() < 2 || widths.size() != knots.size() || count < 2) {
    fail("blade: need at least 2 knots with one width each, and at least 2 knots out");
  }
  std::vector<float> arc(knots.size(), 0.0f);
  for (std::size_t i = 1; i < knots.size(); ++i) {
    arc[i] = arc[i - 1] + glm::length(knots[i] - knots[i - 1]);
  }
  const float total = arc.back();
  BladeShapeLod out;
  out.knots.resize(static_cast<std::size_t>(count));
  out.widths.resize(static_cast<std::size_t>(count));
  std::size_t j = 0;
  for (int k = 0; k < count; ++k) {
    const float target = total * static_cast<float>(k) / static_cast<float>(count - 1);
    while (j + 2 < knots.size() && arc[j + 1] < target) {
      ++j;
    }
    const float seg = arc[j + 1] - arc[j];
    const float t = seg > 0.0f ? std::clamp((target - arc[j]) / seg, 0.0f, 1.0f) : 0.0f;
    out.knots[k] = knots[j] + t * (knots[j + 1] - knots[j]);
    out.widths[k] = widths[j] + t * (widths[j + 1] - widths[j]);
  }
  out.knots.front() = knots.front();
  out.knots.back() = knots.back();
  out.widths.front() = widths.front();
  out.widths.back() = widths.back();
  return out;
}

std::vector<BladeType> proceduralBladeTypes() {
  return {arcBlade("meadow", 0.35f, 0.007f, 0.5f, slimProfile, {0.16f, 0.42f, 0.08f}, 0.45f),
          arcBlade("fescue", 0.25f, 0.003f, 0.9f, fineProfile, {0.22f, 0.40f, 0.10f}, 0.3f),
          arcBlade("broadleaf", 0.18f, 0.018f, 0.3f, broadProfile, {0.12f, 0.36f, 0.07f}, 0.7f)};
}

BladeType bladeTypeFromModel(const blades::BladeModel& model, const glm::vec3& colour, float stiffness) {
  if (model.lods.empty() || model.lods.front().knotCount() < 2) {
    fail("blade model '{}': no level with at least 2 knots", model.name);
  }
  if (!(stiffness > 0.0f) || !std::isfinite(stiffness)) {
    fail("blade model '{}': stiffness must be > 0", model.name);
  }
  const blades::BladeLod& finest = model.lods.front();
  if (polylineLength(finest.positions) <= 0.0f) {
    fail("blade model '{}': zero length", model.name);
  }
  BladeType type;
  type.name = model.name;
  for (std::size_t l = 0; l < kLodKnots.size(); ++l) {
    type.lods[l] = resampleBlade(finest.positions, finest.widths, kLodKnots[l]);
  }
  type.colour = model.hasColour ? model.colour : colour;
  type.stiffness = std::clamp(stiffness, 0.05f, 1.0f);
  return type;
}

void checkBladeSize(const blades::BladeModel& model, const BladeSizeLimits& limits) {
  const float length = model.length();
  const float width = model.maxWidth();
  const char* allow = "; allow it with the grass layer's \"extreme_blades\": true or --grass-extreme-blades";
  if (!(length >= limits.minLength && length <= limits.maxLength)) {
    fail("blade model '{}': {:.4g} m long, outside the {:g} to {:g} m of grass blades (a unit mistake?){}",
         model.name, length, limits.minLength, limits.maxLength, allow);
  }
  if (!(width >= limits.minWidth && width <= limits.maxWidth)) {
    fail("blade model '{}': {:.4g} m at its widest, outside the {:g} to {:g} m of grass blades{}{}",
         model.name, width, limits.minWidth, limits.maxWidth,
         width < limits.minWidth ? " (it would draw nothing)" : "", allow);
  }
}

std::vector<BladeType> loadBladeTypes(const std::filesystem::path& path, const glm::vec3& colour,
                                      float stiffness, bool extreme) {
  const blades::BladeModelFile file = blades::loadBladeModels(path);
  if (file.blades.empty()) {
    fail("{}: no blades", path.string());
  }
  std::vector<BladeType> types;
  for (std::size_t i = 0; i < file.blades.size(); ++i) {
    try {
      if (!extreme) {
        checkBladeSize(file.blades[i]);
      }
      types.push_back(bladeTypeFromModel(file.blades[i], colour, stiffness));
    } catch (const Error& e) {
      fail("{}: /blades/{}: {}", path.string(), i, e.what());
    }
  }
  return types;
}

} // namespace sylva::grass

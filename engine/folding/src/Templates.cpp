// Motion templates: parameterised tool sets for common motions, applied to a zone as one edit.
#include <sylva/folding/Templates.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::folding {

namespace {

struct Box {
  Vec2 lo;
  Vec2 hi;
  Vec2 size() const { return hi - lo; }
  Vec2 centre() const { return 0.5 * (lo + hi); }
  Vec2 at(double u, double v) const { return lo + Vec2(u, v) * size(); }
};

Box boxOf(const Zone& zone) {
  Box b{Vec2(1e18), Vec2(-1e18)};
  for (const Vec2& p : zone.shape.outline()) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

std::vector<Vec2> band(const Box& b, double v0, double v1) {
  return {b.at(0.0, v0), b.at(1.0, v0), b.at(1.0, v1), b.at(0.0, v1)};
}

PositionFunction piecewise(std::vector<glm::dvec2> knots) {
  PositionFunction fn;
  fn.type = PositionFunction::Type::Piecewise;
  fn.knots = std::move(knots);
  return fn;
}

PositionFunction sine() {
  PositionFunction fn;
  fn.type = PositionFunction::Type::Sine;
  return fn;
}

/** The zone's new content and the profile it uses. */
struct Result {
  std::vector<Tool> tools;
  Folding folding;
  Interpolation interp;
  bool zeroBoundary = false;
  Vec2 phaseGradient{0.0};
  double feather = 0.0;
  PositionFunction fn;
  double periodS = 2.0;
};

Result build(const Zone& zone, MotionTemplate motion, const TemplateParams& params) {
  const Box b = boxOf(zone);
  const double w = b.size().x;
  const double h = b.size().y;
  const double small = std::min(w, h);
  Result r;
  r.interp.type = Interpolation::Type::ModifiedShepard;
  r.interp.radius = std::clamp(0.6 * std::max(w, h), 1.0, 4096.0);
  switch (motion) {
  case MotionTemplate::Blink: {
    const double s = params.strength > 0.0 ? params.strength : 0.3 * h;
    CurveTool upper;
    upper.source = {b.at(0.1, 0.45), b.at(0.25, 0.12), b.at(0.75, 0.12), b.at(0.9, 0.45)};
    upper.vectors = {{0.0, Vec2(0.0, 0.4 * s)}, {0.5, Vec2(0.0, s)}, {1.0, Vec2(0.0, 0.4 * s)}};
    upper.samples = 12;
    CurveTool lower;
    lower.source = {b.at(0.1, 0.55), b.at(0.25, 0.88), b.at(0.75, 0.88), b.at(0.9, 0.55)};
    lower.vectors = {{0.0, Vec2(0.0, -0.2 * s)}, {0.5, Vec2(0.0, -0.5 * s)}, {1.0, Vec2(0.0, -0.2 * s)}};
    lower.samples = 12;
    r.tools = {upper, lower};
    r.folding.type = Folding::Type::Polygons;
    r.folding.polygons = {band(b, 0.0, 0.3), band(b, 0.75, 1.0)};
    r.zeroBoundary = true;
    r.fn = piecewise({{0, 0}, {0.25, 1}, {0.55, 1}, {0.8, 0}, {1, 0}});
    r.periodS = 4.0;
    break;
  }
  case MotionTemplate::WaveSwash: {
    const double len = glm::length(params.direction);
    if (!(len > 0.0) || !std::isfinite(len)) {
      fail("template wave_swash: direction must be a non-zero vector");
    }
    const Vec2 d = params.direction / len;
    // Extent of the zone along d, and the water: the 40 % of the zone on the side the water comes from.
    const double extent = std::abs(d.x) * w + std::abs(d.y) * h;
    const double s = params.strength > 0.0 ? params.strength : 0.25 * extent;
    r.tools = {TranslateTool{s * d}};
    const Vec2 c = b.centre();
    const Vec2 side(-d.y, d.x);
    const double half = 0.5 * (std::abs(side.x) * w + std::abs(side.y) * h) + 1.0;
    const Vec2 back = c - 0.5 * extent * d - d; // just outside the zone, where the water comes from
    const Vec2 front = c - 0.1 * extent * d;    // 40 % into the zone
    r.folding.type = Folding::Type::Polygons;
    r.folding.polygons = {{back - half * side, back + half * side, front + half * side, front - half * side}};
    r.phaseGradient = side * (0.6 / std::max(1.0, 2.0 * half));
    r.fn = piecewise({{0, 0}, {0.35, 1}, {0.45, 1}, {1, 0}});
    r.periodS = 4.0;
    break;
  }
  case MotionTemplate::Breathing: {
    const double s = params.strength > 0.0 ? params.strength : 0.04 * small;
    r.tools = {ScaleTool{1.0 + s / std::max(1.0, 0.5 * small), b.centre()}};
    r.zeroBoundary = true;
    r.fn = sine();
    r.periodS = 3.0;
    break;
  }
  case MotionTemplate::WoundOpening: {
    // The cut runs along the long axis through the centre; skin on both sides slides over a central band.
    const bool horizontal = w >= h;
    const double across = horizontal ? h : w;
    const double s = params.strength > 0.0 ? params.strength : 0.12 * across;
    PointsTool points;
    for (int i = 1; i <= 7; ++i) {
      const double u = i / 8.0;
      const double taper = std::sin(3.14159265358979 * u); // open most in the middle of the cut
      for (double sideSign : {-1.0, 1.0}) {
        const Vec2 on = horizontal ? b.at(u, 0.5 + sideSign * 0.2) : b.at(0.5 + sideSign * 0.2, u);
        const Vec2 toward = horizontal ? Vec2(0.0, -sideSign) : Vec2(-sideSign, 0.0);
        points.pairs.push_back({on, on + s * taper * toward});
      }
    }
    r.tools = {points};
    r.folding.type = Folding::Type::Polygons;
    r.folding.polygons = horizontal ? std::vector<std::vector<Vec2>>{band(b, 0.0, 0.42), band(b, 0.58, 1.0)}
                                    : std::vector<std::vector<Vec2>>{
                                          {b.at(0.0, 0.0), b.at(0.42, 0.0), b.at(0.42, 1.0), b.at(0.0, 1.0)},
                                          {b.at(0.58, 0.0), b.at(1.0, 0.0), b.at(1.0, 1.0), b.at(0.58, 1.0)}};
    r.folding.outsideWarps = true;
    r.zeroBoundary = true;
    r.fn = sine();
    r.periodS = 3.0;
    break;
  }
  case MotionTemplate::FlagRipple: {
    const bool horizontal = w >= h;
    const double s = params.strength > 0.0 ? params.strength : 0.04 * (horizontal ? h : w);
    r.tools = {TranslateTool{horizontal ? Vec2(0.0, s) : Vec2(s, 0.0)}};
    r.phaseGradient = horizontal ? Vec2(1.5 / std::max(1.0, w), 0.0) : Vec2(0.0, 1.5 / std::max(1.0, h));
    r.feather = 0.1 * small;
    r.fn = sine();
    r.periodS = 1.5;
    break;
  }
  }
  if (params.periodS > 0.0) {
    r.periodS = params.periodS;
  }
  return r;
}

} // namespace

const std::vector<MotionTemplate>& motionTemplates() {
  static const std::vector<MotionTemplate> kAll = {MotionTemplate::Blink, MotionTemplate::WaveSwash,
                                                   MotionTemplate::Breathing, MotionTemplate::WoundOpening,
                                                   MotionTemplate::FlagRipple};
  return kAll;
}

const char* motionTemplateName(MotionTemplate motion) {
  switch (motion) {
  case MotionTemplate::Blink:
    return "blink";
  case MotionTemplate::WaveSwash:
    return "wave_swash";
  case MotionTemplate::Breathing:
    return "breathing";
  case MotionTemplate::WoundOpening:
    return "wound_opening";
  case MotionTemplate::FlagRipple:
    return "flag_ripple";
  }
  return "blink";
}

std::optional<MotionTemplate> parseMotionTemplate(std::string_view name) {
  for (MotionTemplate m : motionTemplates()) {
    if (name == motionTemplateName(m)) {
      return m;
    }
  }
  return std::nullopt;
}

void applyMotionTemplate(EditHistory& history, int zone, MotionTemplate motion,
                         const TemplateParams& params) {
  if (zone < 0 || zone >= static_cast<int>(history.project().zones.size())) {
    fail("template {}: no zone {}", motionTemplateName(motion), zone);
  }
  const Result r = build(history.project().zones[static_cast<std::size_t>(zone)], motion, params);
  history.apply(std::string("template ") + motionTemplateName(motion), zone, [&](Project& p) {
    const std::string profileId = motionTemplateName(motion);
    Profile profile;
    profile.id = profileId;
    profile.periodS = r.periodS;
    profile.fn = r.fn;
    const int existing = p.profileIndex(profileId);
    if (existing >= 0) {
      p.profiles[static_cast<std::size_t>(existing)] = profile;
    } else {
      p.profiles.push_back(profile);
    }
    Zone& z = p.zones[static_cast<std::size_t>(zone)];
    z.tools = r.tools;
    z.folding = r.folding;
    z.interp = r.interp;
    z.zeroBoundary = r.zeroBoundary;
    z.phaseGradient = r.phaseGradient;
    z.feather = r.feather;
    z.profile = profileId;
  });
}

} // namespace sylva::folding

// Motion templates: parameterised tool sets for common motions, applied to a zone as one edit.
#include <sylva/folding/Templates.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

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

/** The blink's eye opening within the zone's box (fractions of its height): corners, upper and lower apex. */
constexpr double kBlinkCorner = 0.68;
constexpr double kBlinkUpperApex = 0.45;
constexpr double kBlinkLowerApex = 0.88;

Vec2 bezierPoint(const std::array<Vec2, 4>& c, double t) {
  const double m = 1.0 - t;
  return m * m * m * c[0] + 3.0 * m * m * t * c[1] + 3.0 * m * t * t * c[2] + t * t * t * c[3];
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
    // The zone frames one eye from the brow down to just below the lower lid, its corners 10 % in from the
    // sides. The eye opening is fitted to it: cubic Béziers through the corners (68 % down), the upper lid's
    // apex 45 % down and the lower lid's 88 %; the lid's crease lies halfway between the zone's top and the
    // upper lid. The upper lid sweeps down onto the lower lid's line, as in a real blink, and stops there (a
    // larger strength is capped at closed, so the lids never cross): the lid skin between the crease and the
    // lid stretches over the eye and covers it (it is the folding region). The crease, the brow above it and
    // the lower lid (still anchors just below it) stay still.
    const auto lid = [&](double apex) -> std::array<Vec2, 4> {
      const double control = (apex - 0.25 * kBlinkCorner) / 0.75; // the Bézier's midpoint is its apex
      return {b.at(0.1, kBlinkCorner), b.at(0.2, control), b.at(0.8, control), b.at(0.9, kBlinkCorner)};
    };
    const std::array<Vec2, 4> upperLid = lid(kBlinkUpperApex);
    const std::array<Vec2, 4> lowerLid = lid(kBlinkLowerApex);
    const double full = (kBlinkLowerApex - kBlinkUpperApex) * h; // the upper lid's travel at its apex
    const double closure = params.strength > 0.0 ? std::min(params.strength / full, 1.0) : 1.0;
    // Anchors over the whole stretched band (so the interpolation keeps the stretch linear, never folding
    // the skin onto itself): the point a fraction g from the crease to where the lid stops reads the point
    // the same fraction from the crease to the lid.
    PointsTool stretch;
    ZeroTool still;
    // About one anchor every 2 pixels: Shepard's interpolation is flat around each anchor, so sparser
    // anchors would stretch the skin in visible blocks.
    const int across = std::clamp(static_cast<int>(std::lround(0.4 * w)), 8, 96);
    const int down = std::clamp(static_cast<int>(std::lround(0.33 * h)), 6, 96);
    const double below = std::max(1.5, 0.03 * h);
    for (int i = 0; i <= across; ++i) {
      const double t = static_cast<double>(i) / across;
      const Vec2 edge = bezierPoint(upperLid, t);
      const Vec2 crease(edge.x, 0.5 * (b.lo.y + edge.y));
      // Closed, the lid's edge comes to rest on the lower lid's lashes, half a still-band past its line.
      const Vec2 stop = edge + closure * (bezierPoint(lowerLid, t) + Vec2(0.0, 0.5 * below) - edge);
      for (int k = 1; k <= down; ++k) {
        const double g = static_cast<double>(k) / down;
        stretch.pairs.push_back({crease + g * (edge - crease), crease + g * (stop - crease)});
      }
      still.pts.push_back(crease);
    }
    // The lower lid stays: still anchors a little below its line (a second polyline, after the crease's).
    ZeroTool under;
    for (int i = 0; i <= across; ++i) {
      under.pts.push_back(bezierPoint(lowerLid, static_cast<double>(i) / across) + Vec2(0.0, 2.0 * below));
    }
    r.tools = {stretch, still, under};
    // Anchors this dense need no far reach: a short radius keeps the stretch exact up to the still anchors.
    r.interp.radius = std::clamp(0.25 * h, 1.0, 4096.0);
    // The folding region: the lid skin, from the crease to just past the lid's edge (its lashes), so that
    // what the stretch reads there counts as skin.
    const double lash = std::max(1.0, 0.02 * h);
    std::vector<Vec2> skin = {b.at(0.0, 0.0), b.at(1.0, 0.0), b.at(1.0, kBlinkCorner)};
    for (int i = across; i >= 0; --i) {
      skin.push_back(bezierPoint(upperLid, static_cast<double>(i) / across) + Vec2(0.0, lash));
    }
    skin.push_back(b.at(0.0, kBlinkCorner));
    r.folding.type = Folding::Type::Polygons;
    r.folding.polygons = {skin};
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
    // The sides' anchors start 20 % of the zone from the axis: a larger strength is capped where they meet on
    // it, so the two sides close the cut and never cross over each other.
    const double meet = 0.2 * across;
    const double s = std::min(params.strength > 0.0 ? params.strength : 0.12 * across, meet);
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
    // A flag flutters as a wave that runs downwind from the pole and grows towards the free end (a flag held
    // at its leading edge: the hoist barely moves, the fly swings most). The zone's long axis is the flag's
    // length; the hoist is its left end (horizontal) or top (vertical), the other end when `direction` points
    // back along that axis. The swing grows linearly from 0 at the hoist to `strength` at the fly, set by
    // anchors about every 2 pixels (Shepard's interpolation is flat around each anchor), and the phase falls
    // downwind by 1.5 waves over the length, so every crest travels from the hoist to the fly.
    const bool horizontal = w >= h;
    const double along = horizontal ? w : h;
    const double across = horizontal ? h : w;
    const double s = params.strength > 0.0 ? params.strength : 0.04 * across;
    const bool reversed = (horizontal ? params.direction.x : params.direction.y) < 0.0;
    const Vec2 swing = horizontal ? Vec2(0.0, s) : Vec2(s, 0.0);
    const auto at = [&](double u, double v) { // u from the hoist to the fly, v across, both in [0, 1]
      const double a = reversed ? 1.0 - u : u;
      return horizontal ? b.at(a, v) : b.at(v, a);
    };
    PointsTool ramp;
    ZeroTool pole;
    const int steps = std::clamp(static_cast<int>(std::lround(0.5 * along)), 8, 128);
    for (int i = 0; i <= steps; ++i) {
      const double u = static_cast<double>(i) / steps;
      for (const double v : {0.1, 0.3, 0.5, 0.7, 0.9}) {
        const Vec2 p = at(u, v);
        ramp.pairs.push_back({p + u * swing, p}); // the anchor at p swings by u · s
      }
    }
    for (const double v : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      pole.pts.push_back(at(0.0, v));
    }
    r.tools = {ramp, pole};
    r.interp.radius = std::clamp(0.25 * across, 1.0, 4096.0);
    const Vec2 downwind = (horizontal ? Vec2(1.0, 0.0) : Vec2(0.0, 1.0)) * (reversed ? -1.0 : 1.0);
    r.phaseGradient = -downwind * (1.5 / std::max(1.0, along));
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

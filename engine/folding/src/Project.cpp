// Folding project files: strict parsing (every error names the file and the JSON path), canonical writing,
// and the checks that need image sizes.
#include <sylva/folding/Project.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/JsonNode.hpp>
#include <sylva/folding/Field.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace sylva::folding {

namespace {

using nlohmann::json;

/** `[x, y]` with both coordinates in [-limit, limit]. Error: `expected [x, y]`, then those of number(). */
Vec2 vec2(const JsonNode& n, double limit = 1e6) {
  if (!n.value().is_array() || n.value().size() != 2) {
    n.error("expected [x, y]");
  }
  return {n[std::size_t{0}].number(-limit, limit), n[1].number(-limit, limit)};
}

/** An array of `minCount` … `maxCount` points `[x, y]`. */
std::vector<Vec2> points(const JsonNode& n, std::size_t minCount, std::size_t maxCount) {
  const std::size_t count = n.array(minCount, maxCount);
  std::vector<Vec2> pts;
  pts.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    pts.push_back(vec2(n[i]));
  }
  return pts;
}

/** A simple polygon: ≥ 3 vertices, non-zero area, no self-intersection. */
std::vector<Vec2> polygon(const JsonNode& n) {
  std::vector<Vec2> pts = points(n, 3, kMaxPolygonVertices);
  if (pts.front() == pts.back()) {
    pts.pop_back(); // a closed ring is accepted and stored open
  }
  bool collinear = true;
  for (std::size_t i = 2; i < pts.size(); ++i) {
    const Vec2 a = pts[1] - pts[0];
    const Vec2 b = pts[i] - pts[0];
    collinear = collinear && std::abs(a.x * b.y - a.y * b.x) < 1e-9;
  }
  if (pts.size() < 3 || collinear) {
    n.error("degenerate polygon (zero area)");
  }
  if (selfIntersects(pts)) {
    n.error("self-intersecting polygon");
  }
  return pts;
}

const char* functionName(PositionFunction::Type type) {
  switch (type) {
  case PositionFunction::Type::Linear:
    return "linear";
  case PositionFunction::Type::Piecewise:
    return "piecewise";
  case PositionFunction::Type::Exponential:
    return "exponential";
  case PositionFunction::Type::Sigmoid:
    return "sigmoid";
  case PositionFunction::Type::Sine:
    return "sine";
  }
  return "linear";
}

PositionFunction parseFunction(const JsonNode& n) {
  PositionFunction fn;
  const std::string type = n["type"].choice({"linear", "piecewise", "exponential", "sigmoid", "sine"});
  if (type == "linear") {
    n.object({"type", "slope", "delay"});
    fn.type = PositionFunction::Type::Linear;
    fn.slope = n.has("slope") ? n["slope"].number(-1e3, 1e3) : 1.0;
    fn.delay = n.has("delay") ? n["delay"].number(-1.0, 1.0) : 0.0;
  } else if (type == "piecewise") {
    n.object({"type", "knots"});
    fn.type = PositionFunction::Type::Piecewise;
    const JsonNode knots = n["knots"];
    const std::size_t count = knots.array(2, kMaxKnots);
    for (std::size_t i = 0; i < count; ++i) {
      const Vec2 k = vec2(knots[i]);
      if (k.x < 0.0 || k.x > 1.0) {
        knots[i].error("knot phase must lie in [0, 1]");
      }
      if (i > 0 && k.x <= fn.knots.back().x) {
        knots[i].error("knot phases must increase");
      }
      fn.knots.push_back(k);
    }
    if (fn.knots.front().x != 0.0 || fn.knots.back().x != 1.0) {
      knots.error("the first knot must be at phase 0 and the last at phase 1");
    }
  } else if (type == "exponential") {
    n.object({"type", "k"});
    fn.type = PositionFunction::Type::Exponential;
    fn.k = n.has("k") ? n["k"].number(-50.0, 50.0) : 4.0;
  } else if (type == "sigmoid") {
    n.object({"type", "k", "centre"});
    fn.type = PositionFunction::Type::Sigmoid;
    fn.k = n.has("k") ? n["k"].number(1e-3, 100.0) : 10.0;
    fn.centre = n.has("centre") ? n["centre"].number(0.0, 1.0) : 0.5;
  } else {
    n.object({"type", "amplitude", "frequency", "phase", "offset"});
    fn.type = PositionFunction::Type::Sine;
    fn.amplitude = n.has("amplitude") ? n["amplitude"].number(-100.0, 100.0) : 1.0;
    fn.frequency = n.has("frequency") ? n["frequency"].number(-100.0, 100.0) : 1.0;
    fn.phase = n.has("phase") ? n["phase"].number(-100.0, 100.0) : 0.0;
    fn.offset = n.has("offset") ? n["offset"].number(-100.0, 100.0) : 0.0;
  }
  return fn;
}

json functionJson(const PositionFunction& fn) {
  json j = {{"type", functionName(fn.type)}};
  switch (fn.type) {
  case PositionFunction::Type::Linear:
    j["slope"] = fn.slope;
    j["delay"] = fn.delay;
    break;
  case PositionFunction::Type::Piecewise:
    j["knots"] = json::array();
    for (const auto& k : fn.knots) {
      j["knots"].push_back({k.x, k.y});
    }
    break;
  case PositionFunction::Type::Exponential:
    j["k"] = fn.k;
    break;
  case PositionFunction::Type::Sigmoid:
    j["k"] = fn.k;
    j["centre"] = fn.centre;
    break;
  case PositionFunction::Type::Sine:
    j["amplitude"] = fn.amplitude;
    j["frequency"] = fn.frequency;
    j["phase"] = fn.phase;
    j["offset"] = fn.offset;
    break;
  }
  return j;
}

json vecJson(Vec2 v) {
  return json::array({v.x, v.y});
}
json pointsJson(const std::vector<Vec2>& pts) {
  json j = json::array();
  for (const Vec2& p : pts) {
    j.push_back(vecJson(p));
  }
  return j;
}

std::array<Vec2, 4> bezierControl(const JsonNode& n) {
  const std::vector<Vec2> pts = points(n, 4, 4);
  return {pts[0], pts[1], pts[2], pts[3]};
}

Tool parseTool(const JsonNode& n) {
  const std::string type =
      n["type"].choice({"translate", "scale", "points", "curve", "lasso", "zero", "fly_over"});
  if (type == "translate") {
    n.object({"type", "v"});
    return TranslateTool{vec2(n["v"])};
  }
  if (type == "scale") {
    n.object({"type", "factor", "centre"});
    ScaleTool tool;
    tool.factor = n["factor"].number(1e-3, 1e3);
    tool.centre = vec2(n["centre"]);
    return tool;
  }
  if (type == "points") {
    n.object({"type", "pairs"});
    PointsTool tool;
    const JsonNode pairs = n["pairs"];
    const std::size_t count = pairs.array(1, 100000);
    for (std::size_t i = 0; i < count; ++i) {
      const std::vector<Vec2> pair = points(pairs[i], 2, 2);
      tool.pairs.push_back({pair[0], pair[1]});
    }
    return tool;
  }
  if (type == "curve") {
    n.object({"type", "source", "dest", "vectors", "samples"});
    CurveTool tool;
    tool.source = bezierControl(n["source"]);
    if (n.has("dest") == n.has("vectors")) {
      n.error("a curve needs exactly one of 'dest' (a destination curve) or 'vectors' (motion along it)");
    }
    if (n.has("dest")) {
      tool.dest = bezierControl(n["dest"]);
    } else {
      const JsonNode vectors = n["vectors"];
      const std::size_t count = vectors.array(1, kMaxCurveSamples);
      for (std::size_t i = 0; i < count; ++i) {
        const JsonNode entry = vectors[i];
        if (!entry.value().is_array() || entry.value().size() != 2) {
          entry.error("expected [u, [x, y]]");
        }
        const double u = entry[std::size_t{0}].number(0.0, 1.0);
        if (i > 0 && u <= tool.vectors.back().first) {
          entry[std::size_t{0}].error("curve parameters must increase");
        }
        tool.vectors.emplace_back(u, vec2(entry[1]));
      }
    }
    tool.samples = n.has("samples") ? n["samples"].integer(2, kMaxCurveSamples) : 16;
    return tool;
  }
  if (type == "lasso") {
    n.object({"type", "from", "to", "interior"});
    LassoTool tool;
    tool.from = polygon(n["from"]);
    tool.to = points(n["to"], 3, kMaxPolygonVertices);
    if (tool.to.size() == tool.from.size() + 1 && tool.to.front() == tool.to.back()) {
      tool.to.pop_back();
    }
    if (tool.to.size() != tool.from.size()) {
      n["to"].error(fmt::format("needs as many vertices as 'from' ({})", tool.from.size()));
    }
    if (n.has("interior")) {
      tool.meanValue = n["interior"].choice({"mean_value", "shepard"}) == "mean_value";
    }
    if (tool.meanValue && selfIntersects(tool.to)) {
      n["to"].error("self-intersecting polygon");
    }
    return tool;
  }
  if (type == "zero") {
    n.object({"type", "pts"});
    return ZeroTool{points(n["pts"], 1, kMaxPolygonVertices)};
  }
  n.object({"type", "object", "from", "to"});
  FlyOverTool tool;
  tool.object = n["object"].string();
  tool.from = vec2(n["from"]);
  tool.to = vec2(n["to"]);
  return tool;
}

json toolJson(const Tool& tool) {
  return std::visit(
      [](const auto& t) -> json {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, TranslateTool>) {
          return {{"type", "translate"}, {"v", vecJson(t.v)}};
        } else if constexpr (std::is_same_v<T, ScaleTool>) {
          return {{"type", "scale"}, {"factor", t.factor}, {"centre", vecJson(t.centre)}};
        } else if constexpr (std::is_same_v<T, PointsTool>) {
          json pairs = json::array();
          for (const auto& p : t.pairs) {
            pairs.push_back({vecJson(p[0]), vecJson(p[1])});
          }
          return {{"type", "points"}, {"pairs", pairs}};
        } else if constexpr (std::is_same_v<T, CurveTool>) {
          json j = {{"type", "curve"},
                    {"source", pointsJson({t.source.begin(), t.source.end()})},
                    {"samples", t.samples}};
          if (t.dest) {
            j["dest"] = pointsJson({t.dest->begin(), t.dest->end()});
          } else {
            j["vectors"] = json::array();
            for (const auto& [u, v] : t.vectors) {
              j["vectors"].push_back({u, vecJson(v)});
            }
          }
          return j;
        } else if constexpr (std::is_same_v<T, LassoTool>) {
          return {{"type", "lasso"},
                  {"from", pointsJson(t.from)},
                  {"to", pointsJson(t.to)},
                  {"interior", t.meanValue ? "mean_value" : "shepard"}};
        } else if constexpr (std::is_same_v<T, ZeroTool>) {
          return {{"type", "zero"}, {"pts", pointsJson(t.pts)}};
        } else {
          return {
              {"type", "fly_over"}, {"object", t.object}, {"from", vecJson(t.from)}, {"to", vecJson(t.to)}};
        }
      },
      tool);
}

Interpolation parseInterpolation(const JsonNode& n) {
  Interpolation interp;
  const std::string type = n["type"].choice({"shepard", "modified_shepard", "modified_shepard_random"});
  if (type == "shepard") {
    n.object({"type", "power"});
    interp.type = Interpolation::Type::Shepard;
    interp.power = n.has("power") ? n["power"].number(0.5, 16.0) : 2.0;
  } else if (type == "modified_shepard") {
    n.object({"type", "R"});
    interp.type = Interpolation::Type::ModifiedShepard;
    interp.radius = n["R"].number(1.0, 4096.0);
  } else {
    n.object({"type", "R", "ring"});
    interp.type = Interpolation::Type::ModifiedShepardRandom;
    interp.radius = n["R"].number(1.0, 4096.0);
    interp.ring = n["ring"].number(1e-3, 4096.0);
    if (interp.ring >= interp.radius) {
      n["ring"].error("the ring must be narrower than R");
    }
  }
  return interp;
}

json interpolationJson(const Interpolation& interp) {
  switch (interp.type) {
  case Interpolation::Type::Shepard:
    return {{"type", "shepard"}, {"power", interp.power}};
  case Interpolation::Type::ModifiedShepard:
    return {{"type", "modified_shepard"}, {"R", interp.radius}};
  case Interpolation::Type::ModifiedShepardRandom:
    return {{"type", "modified_shepard_random"}, {"R", interp.radius}, {"ring", interp.ring}};
  }
  return {};
}

Shape parseShape(const JsonNode& n) {
  Shape shape;
  const std::string type = n["type"].choice({"rect", "polygon"});
  if (type == "rect") {
    n.object({"type", "min", "max"});
    shape.type = Shape::Type::Rect;
    shape.min = vec2(n["min"]);
    shape.max = vec2(n["max"]);
    if (!(shape.max.x > shape.min.x && shape.max.y > shape.min.y)) {
      n.error("a rect needs max > min on both axes");
    }
  } else {
    n.object({"type", "pts"});
    shape.type = Shape::Type::Polygon;
    shape.pts = polygon(n["pts"]);
  }
  return shape;
}

json shapeJson(const Shape& shape) {
  if (shape.type == Shape::Type::Rect) {
    return {{"type", "rect"}, {"min", vecJson(shape.min)}, {"max", vecJson(shape.max)}};
  }
  return {{"type", "polygon"}, {"pts", pointsJson(shape.pts)}};
}

Folding parseFolding(const JsonNode& n) {
  Folding folding;
  const std::string type = n["type"].choice({"polygon", "polygons", "mask", "object"});
  if (type == "polygon") {
    n.object({"type", "pts", "outside"});
    folding.type = Folding::Type::Polygons;
    folding.polygons.push_back(polygon(n["pts"]));
  } else if (type == "polygons") {
    n.object({"type", "polygons", "outside"});
    folding.type = Folding::Type::Polygons;
    const JsonNode list = n["polygons"];
    const std::size_t count = list.array(1, 256);
    for (std::size_t i = 0; i < count; ++i) {
      folding.polygons.push_back(polygon(list[i]));
    }
  } else if (type == "mask") {
    n.object({"type", "file", "outside"});
    folding.type = Folding::Type::Mask;
    folding.mask = n["file"].string();
  } else {
    n.object({"type", "outside"});
    folding.type = Folding::Type::Object;
  }
  if (n.has("outside")) {
    folding.outsideWarps = n["outside"].choice({"still", "warp"}) == "warp";
  }
  return folding;
}

json foldingJson(const Folding& folding) {
  json j;
  switch (folding.type) {
  case Folding::Type::None:
    return nullptr;
  case Folding::Type::Polygons:
    j = {{"type", "polygons"}, {"polygons", json::array()}};
    for (const auto& poly : folding.polygons) {
      j["polygons"].push_back(pointsJson(poly));
    }
    break;
  case Folding::Type::Mask:
    j = {{"type", "mask"}, {"file", folding.mask.generic_string()}};
    break;
  case Folding::Type::Object:
    j = {{"type", "object"}};
    break;
  }
  j["outside"] = folding.outsideWarps ? "warp" : "still";
  return j;
}

void requireUnique(const JsonNode& list, std::size_t count, std::set<std::string>& ids, const std::string& id,
                   std::size_t i) {
  (void)count;
  if (!ids.insert(id).second) {
    list[i]["id"].error(fmt::format("duplicate id '{}'", id));
  }
}

} // namespace

std::vector<Vec2> Shape::outline() const {
  if (type == Type::Polygon) {
    return pts;
  }
  return {min, {max.x, min.y}, max, {min.x, max.y}};
}

int Project::imageIndex(const std::string& id) const {
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (images[i].id == id) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int Project::profileIndex(const std::string& id) const {
  for (std::size_t i = 0; i < profiles.size(); ++i) {
    if (profiles[i].id == id) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int Project::canvasIndex() const {
  return canvas.empty() ? 0 : std::max(0, imageIndex(canvas));
}

std::filesystem::path Project::resolve(const std::filesystem::path& file) const {
  return file.is_absolute() ? file : baseDir / file;
}

Project parseProject(const json& root, const std::string& where) {
  const JsonNode top(root, where, "");
  top.object({"format", "version", "seed", "canvas", "jump_layers", "atlas", "profiles", "zones", "outputs"});
  if (top["format"].string() != "sylva-fold") {
    top["format"].error("expected \"sylva-fold\"");
  }
  const int version = top["version"].integer(1, 1 << 30);
  if (version > kProjectVersion) {
    top["version"].error(fmt::format("this file is version {}, newer than this sylva understands ({}); "
                                     "update sylva",
                                     version, kProjectVersion));
  }
  Project p;
  if (top.has("seed")) {
    const JsonNode seed = top["seed"];
    if (!seed.value().is_number_integer() ||
        (!seed.value().is_number_unsigned() && seed.value().get<std::int64_t>() < 0)) {
      seed.error("expected a non-negative integer");
    }
    p.seed = seed.value().get<std::uint64_t>();
  }

  const JsonNode atlas = top["atlas"].object({"gutter_px", "images"});
  p.gutter = atlas.has("gutter_px") ? atlas["gutter_px"].integer(2, 64) : 4;
  const JsonNode images = atlas["images"];
  const std::size_t imageCount = images.array(1, kMaxImages);
  std::set<std::string> ids;
  for (std::size_t i = 0; i < imageCount; ++i) {
    const JsonNode n = images[i].object({"id", "file", "crop"});
    ImageEntry entry;
    entry.id = n["id"].string();
    requireUnique(images, imageCount, ids, entry.id, i);
    entry.file = n["file"].string();
    entry.crop = n.has("crop") ? n["crop"].boolean() : true;
    p.images.push_back(std::move(entry));
  }
  if (top.has("canvas")) {
    p.canvas = top["canvas"].string();
    if (p.imageIndex(p.canvas) < 0) {
      top["canvas"].error(fmt::format("no image with id '{}'", p.canvas));
    }
  }

  if (top.has("jump_layers")) {
    const JsonNode layers = top["jump_layers"];
    const std::size_t count = layers.array(2, kMaxJumpLayers + 1);
    p.jumpLayers.clear();
    for (std::size_t i = 0; i < count; ++i) {
      const double b = layers[i].number(0.0, 1.0);
      if (i > 0 && b <= p.jumpLayers.back()) {
        layers[i].error("breakpoints must increase");
      }
      p.jumpLayers.push_back(b);
    }
    if (p.jumpLayers.front() != 0.0 || p.jumpLayers.back() != 1.0) {
      layers.error("breakpoints must start at 0 and end at 1");
    }
  }

  const JsonNode profiles = top["profiles"];
  const std::size_t profileCount = profiles.array(1, kMaxProfiles);
  ids.clear();
  for (std::size_t i = 0; i < profileCount; ++i) {
    const JsonNode n = profiles[i].object({"id", "period_s", "shift", "fn", "loop"});
    Profile profile;
    profile.id = n["id"].string();
    requireUnique(profiles, profileCount, ids, profile.id, i);
    profile.periodS = n.has("period_s") ? n["period_s"].number(1e-3, 1e6) : 2.0;
    profile.shift = n.has("shift") ? n["shift"].number(-1e3, 1e3) : 0.0;
    profile.fn = n.has("fn") ? parseFunction(n["fn"].object({"type", "slope", "delay", "knots", "k", "centre",
                                                             "amplitude", "frequency", "phase", "offset"}))
                             : PositionFunction{};
    if (n.has("loop")) {
      const std::string loop = n["loop"].choice({"none", "ping_pong", "crossfade"});
      profile.loop = loop == "ping_pong"   ? LoopMode::PingPong
                     : loop == "crossfade" ? LoopMode::Crossfade
                                           : LoopMode::None;
    }
    p.profiles.push_back(std::move(profile));
  }

  const JsonNode zones = top["zones"];
  const std::size_t zoneCount = zones.array(0, 256);
  ids.clear();
  for (std::size_t i = 0; i < zoneCount; ++i) {
    const JsonNode n =
        zones[i].object({"id", "image", "shape", "profile", "layer", "phase", "phase_gradient", "interp",
                         "zero_anchors", "zero_spacing_px", "feather_px", "freeze_mask", "tools", "folding"});
    Zone zone;
    zone.id = n["id"].string();
    requireUnique(zones, zoneCount, ids, zone.id, i);
    zone.image = n["image"].string();
    if (p.imageIndex(zone.image) < 0) {
      n["image"].error(fmt::format("no image with id '{}'", zone.image));
    }
    zone.shape = parseShape(n["shape"]);
    zone.profile = n["profile"].string();
    if (p.profileIndex(zone.profile) < 0) {
      n["profile"].error(fmt::format("no profile with id '{}'", zone.profile));
    }
    zone.layer = n.has("layer") ? n["layer"].integer(0, static_cast<int>(p.jumpLayers.size()) - 2) : 0;
    zone.phase = n.has("phase") ? n["phase"].number(-1e3, 1e3) : 0.0;
    zone.phaseGradient = n.has("phase_gradient") ? vec2(n["phase_gradient"], 1e3) : Vec2(0.0);
    zone.interp = n.has("interp") ? parseInterpolation(n["interp"]) : Interpolation{};
    if (n.has("zero_anchors")) {
      zone.zeroBoundary = n["zero_anchors"].choice({"none", "zone_boundary"}) == "zone_boundary";
    }
    zone.zeroSpacing = n.has("zero_spacing_px") ? n["zero_spacing_px"].number(0.5, 1e4) : 4.0;
    zone.feather = n.has("feather_px") ? n["feather_px"].number(0.0, 1e4) : 0.0;
    if (n.has("freeze_mask")) {
      zone.freezeMask = n["freeze_mask"].string();
    }
    if (n.has("tools")) {
      const JsonNode tools = n["tools"];
      const std::size_t toolCount = tools.array(0, 4096);
      for (std::size_t t = 0; t < toolCount; ++t) {
        Tool tool = parseTool(tools[t]);
        if (const auto* fly = std::get_if<FlyOverTool>(&tool)) {
          if (p.imageIndex(fly->object) < 0) {
            tools[t]["object"].error(fmt::format("no image with id '{}'", fly->object));
          }
          if (fly->object == zone.image) {
            tools[t]["object"].error("an object cannot fly over its own image");
          }
        }
        zone.tools.push_back(std::move(tool));
      }
    }
    if (n.has("folding") && !n["folding"].value().is_null()) {
      zone.folding = parseFolding(n["folding"]);
      if (zone.folding.type == Folding::Type::Object &&
          std::none_of(zone.tools.begin(), zone.tools.end(),
                       [](const Tool& t) { return std::holds_alternative<FlyOverTool>(t); })) {
        n["folding"].error("folding of type 'object' needs a fly_over tool in the zone");
      }
    }
    p.zones.push_back(std::move(zone));
  }

  if (top.has("outputs")) {
    const JsonNode n = top["outputs"].object({"encoding", "color", "init", "jump"});
    if (n.has("encoding")) {
      p.outputs.encoding = n["encoding"].choice({"rgba16", "exr"}) == "exr" ? Outputs::Encoding::Exr
                                                                            : Outputs::Encoding::Rgba16;
    }
    const std::string ext = p.outputs.encoding == Outputs::Encoding::Exr ? ".exr" : ".png";
    p.outputs.init = "init" + ext;
    p.outputs.jump = "jump" + ext;
    for (auto [key, field] : {std::pair{"color", &p.outputs.color}, std::pair{"init", &p.outputs.init},
                              std::pair{"jump", &p.outputs.jump}}) {
      if (n.has(key)) {
        *field = n[key].string();
        if (field->find('/') != std::string::npos || *field == "." || *field == "..") {
          n[key].error("must be a plain file name (it is written into the output directory)");
        }
      }
    }
  }
  return p;
}

Project loadProject(const std::filesystem::path& path) {
  Project project = parseProject(loadJsonFile(path), path.string());
  project.baseDir = path.parent_path();
  return project;
}

Project rebasedProject(Project project, const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  // fs::absolute("") throws: an empty directory is the working directory.
  const auto directory = [](const fs::path& dir) { return fs::absolute(dir.empty() ? fs::path(".") : dir); };
  const fs::path from = directory(project.baseDir).lexically_normal();
  const fs::path to = directory(out.parent_path()).lexically_normal();
  const auto rebase = [&](fs::path& file) {
    if (!file.empty() && file.is_relative()) {
      file = (from / file).lexically_normal().lexically_relative(to);
    }
  };
  for (ImageEntry& image : project.images) {
    rebase(image.file);
  }
  for (Zone& zone : project.zones) {
    rebase(zone.freezeMask);
    rebase(zone.folding.mask);
  }
  project.baseDir = out.parent_path();
  return project;
}

json toJson(const Project& p) {
  json images = json::array();
  for (const ImageEntry& image : p.images) {
    images.push_back({{"id", image.id}, {"file", image.file.generic_string()}, {"crop", image.crop}});
  }
  json profiles = json::array();
  for (const Profile& profile : p.profiles) {
    profiles.push_back({{"id", profile.id},
                        {"period_s", profile.periodS},
                        {"shift", profile.shift},
                        {"fn", functionJson(profile.fn)},
                        {"loop", profile.loop == LoopMode::PingPong    ? "ping_pong"
                                 : profile.loop == LoopMode::Crossfade ? "crossfade"
                                                                       : "none"}});
  }
  json zones = json::array();
  for (const Zone& zone : p.zones) {
    json tools = json::array();
    for (const Tool& tool : zone.tools) {
      tools.push_back(toolJson(tool));
    }
    json z = {{"id", zone.id},
              {"image", zone.image},
              {"shape", shapeJson(zone.shape)},
              {"profile", zone.profile},
              {"layer", zone.layer},
              {"phase", zone.phase},
              {"phase_gradient", vecJson(zone.phaseGradient)},
              {"interp", interpolationJson(zone.interp)},
              {"zero_anchors", zone.zeroBoundary ? "zone_boundary" : "none"},
              {"zero_spacing_px", zone.zeroSpacing},
              {"feather_px", zone.feather},
              {"tools", tools}};
    if (!zone.freezeMask.empty()) {
      z["freeze_mask"] = zone.freezeMask.generic_string();
    }
    if (zone.folding.type != Folding::Type::None) {
      z["folding"] = foldingJson(zone.folding);
    }
    zones.push_back(std::move(z));
  }
  json j = {{"format", "sylva-fold"},
            {"version", kProjectVersion},
            {"seed", p.seed},
            {"jump_layers", p.jumpLayers},
            {"atlas", {{"gutter_px", p.gutter}, {"images", images}}},
            {"profiles", profiles},
            {"zones", zones},
            {"outputs",
             {{"encoding", p.outputs.encoding == Outputs::Encoding::Exr ? "exr" : "rgba16"},
              {"color", p.outputs.color},
              {"init", p.outputs.init},
              {"jump", p.outputs.jump}}}};
  if (!p.canvas.empty()) {
    j["canvas"] = p.canvas;
  }
  return j;
}

void saveProject(const std::filesystem::path& path, const Project& project) {
  saveJsonFile(path, toJson(project));
}

void validateAgainstImages(const Project& project, const std::vector<glm::ivec2>& sizes,
                           const std::string& where) {
  for (std::size_t z = 0; z < project.zones.size(); ++z) {
    const Zone& zone = project.zones[z];
    const glm::ivec2 size = sizes.at(static_cast<std::size_t>(project.imageIndex(zone.image)));
    const std::vector<Vec2> outline = zone.shape.outline();
    for (std::size_t i = 0; i < outline.size(); ++i) {
      const Vec2 v = outline[i];
      if (v.x < 0.0 || v.y < 0.0 || v.x > size.x || v.y > size.y) {
        const std::string field = zone.shape.type == Shape::Type::Rect
                                      ? fmt::format("/zones/{}/shape", z)
                                      : fmt::format("/zones/{}/shape/pts/{}", z, i);
        fail("{}: {}: ({}, {}) lies outside image '{}' ({}×{} pixels)", where, field, v.x, v.y, zone.image,
             size.x, size.y);
      }
    }
  }
}

} // namespace sylva::folding

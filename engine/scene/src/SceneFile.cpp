#include <sylva/scene/SceneFile.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/JsonNode.hpp>
#include <sylva/terrain/Quadtree.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace sylva::scene {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/** Shared state of one parse: the file name for errors and the directory that resolves relative paths. */
struct Context {
  std::string file; ///< as given, for errors
  fs::path dir;     ///< absolute directory of the file
};

/**
 * One value of a scene file: core's JsonNode (JSON Pointer paths, `<file>: <pointer>: <what>` errors, key
 * suggestions) with the scene's own readers: names, seeds, vectors, points, and files relative to the scene.
 */
class Node : public JsonNode {
public:
  Node(const json& value, const Context& ctx, std::string path)
      : JsonNode(value, ctx.file, std::move(path)), mCtx(ctx) {}
  Node(const JsonNode& node, const Context& ctx) : JsonNode(node), mCtx(ctx) {}

  const Context& context() const { return mCtx; }

  const Node& object(std::initializer_list<const char*> allowed) const {
    JsonNode::object(allowed);
    return *this;
  }
  Node child(std::string_view key) const { return Node(JsonNode::child(key), mCtx); }
  Node operator[](const char* key) const { return Node(JsonNode::operator[](key), mCtx); }
  Node item(std::size_t index) const { return Node(JsonNode::operator[](index), mCtx); }

  std::uint64_t seed() const { return unsignedInteger(); }
  /** Scene strings (names, paths) are at most 4096 bytes. */
  std::string string(bool allowEmpty = false) const { return JsonNode::string(allowEmpty, 4096); }

  /** A string made of [a-z0-9_-] only (names of presets, layers). */
  std::string name() const {
    std::string s = string();
    for (char c : s) {
      const bool ok = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
      if (!ok) {
        error(fmt::format("'{}' is not a name (lower-case letters, digits, '-' and '_')", s));
      }
    }
    return s;
  }

  glm::vec3 vec3(double lo, double hi) const {
    if (!value().is_array() || value().size() != 3) {
      error("expected an array of 3 numbers");
    }
    return {item(0).real(lo, hi), item(1).real(lo, hi), item(2).real(lo, hi)};
  }

  glm::vec2 vec2(double lo, double hi) const {
    if (!value().is_array() || value().size() != 2) {
      error("expected an array of 2 numbers");
    }
    return {item(0).real(lo, hi), item(1).real(lo, hi)};
  }

  /**
   * A file path: relative paths resolve against the scene's directory; the file must exist (a regular
   * file). `extensions` (lower case, with dot) limits the kinds accepted when non-empty.
   */
  std::string file(std::initializer_list<const char*> extensions = {}) const {
    return resolveFile(string(), extensions);
  }

  /** Resolves `s` like file() does, errors at this node (used for paths held in object keys). */
  std::string resolveFile(const std::string& s, std::initializer_list<const char*> extensions) const {
    fs::path p(s);
    if (p.is_relative()) {
      p = mCtx.dir / p;
    }
    p = p.lexically_normal();
    if (extensions.size() > 0) {
      const std::string ext = lowerExtension(p);
      std::string all;
      bool ok = false;
      for (const char* e : extensions) {
        ok = ok || ext == e;
        all += all.empty() ? "" : ", ";
        all += e;
      }
      if (!ok) {
        error(fmt::format("'{}' is not a {} file", s, all));
      }
    }
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) {
      error(fmt::format("file not found: {}", p.string()));
    }
    return p.string();
  }

  /** A point: [x, y, z] (absolute) or {"at": [x, y, z], "above_ground": true|false}. */
  Vec3Ground point() const {
    Vec3Ground g;
    if (value().is_object()) {
      object({"at", "above_ground"});
      g.p = (*this)["at"].vec3(-kMaxCoord, kMaxCoord);
      if (has("above_ground")) {
        g.aboveGround = (*this)["above_ground"].boolean();
      }
      return g;
    }
    if (!value().is_array()) {
      error(fmt::format("expected [x, y, z] or {{\"at\": [x, y, z], \"above_ground\": true}}, got {}",
                        value().type_name()));
    }
    g.p = vec3(-kMaxCoord, kMaxCoord);
    return g;
  }

  static constexpr double kMaxCoord = 1e7; ///< metres; any world coordinate beyond is absurd

private:
  const Context& mCtx;
};

constexpr double kBig = 1e7; ///< generic upper bound for lengths in metres

void readTerrain(const Node& n, TerrainDesc& t) {
  n.object({"dem", "seed", "size", "spacing", "relief", "exaggeration", "sea_level", "tess_level",
            "lod_factor", "lod_error", "max_depth", "geomorph"});
  if (n.has("dem")) {
    t.dem = n["dem"].file({".png", ".exr", ".npy", ".npz", ".tif", ".tiff", ".nc", ".asc", ".hgt"});
    for (const char* proceduralOnly : {"seed", "size", "relief"}) {
      if (n.has(proceduralOnly)) {
        n[proceduralOnly].error("only for procedural terrain (remove it or 'dem')");
      }
    }
  }
  if (n.has("seed")) {
    t.seed = n["seed"].seed();
  }
  if (n.has("size")) {
    t.size = n["size"].integer(17, 8193);
  }
  if (n.has("spacing")) {
    t.spacing = n["spacing"].realAbove(0.0, 10000.0);
    t.spacingSet = true;
  }
  if (n.has("relief")) {
    t.relief = n["relief"].real(0.0, 20000.0);
  }
  if (n.has("exaggeration")) {
    t.exaggeration = n["exaggeration"].realAbove(0.0, 100.0);
  }
  if (n.has("sea_level")) {
    t.seaLevel = n["sea_level"].real(-20000.0, 20000.0);
  }
  if (n.has("tess_level")) {
    t.tessLevel = n["tess_level"].integer(1, terrain::kMaxPatchTessLevel);
  }
  if (n.has("lod_factor")) {
    t.lodFactor = n["lod_factor"].real(terrain::kMinRestrictedLodFactor, 64.0);
  }
  if (n.has("lod_error")) {
    t.lodError = n["lod_error"].real(0.0, 1000.0);
  }
  if (n.has("max_depth")) {
    t.maxDepth = n["max_depth"].integer(-1, 16);
  }
  if (n.has("geomorph")) {
    t.geomorph = n["geomorph"].boolean();
  }
}

GrassLayer readGrass(const Node& n) {
  n.object({"blades", "extreme_blades", "density", "coverage", "layer", "paint", "max_slope", "seed",
            "simulate", "distance", "near_layers", "near_distance"});
  GrassLayer g;
  if (n.has("blades")) {
    const Node b = n["blades"];
    const std::size_t count = b.array(0, 64);
    for (std::size_t i = 0; i < count; ++i) {
      g.blades.push_back(b.item(i).file({".json"}));
    }
  }
  if (n.has("extreme_blades")) {
    g.extremeBlades = n["extreme_blades"].boolean();
  }
  if (n.has("density")) {
    g.density = n["density"].real(0.0, kMaxGrassDensity);
  }
  if (n.has("coverage")) {
    g.coverage = n["coverage"].real(0.0, 1.0);
  }
  if (n.has("layer")) {
    g.layer = n["layer"].name();
  }
  if (n.has("paint")) {
    g.paint = n["paint"].file({".png"});
  }
  if (n.has("max_slope")) {
    g.maxSlope = n["max_slope"].real(0.0, 90.0);
  }
  if (n.has("seed")) {
    g.seed = n["seed"].seed();
  }
  if (n.has("simulate")) {
    g.simulate = n["simulate"].boolean();
  }
  if (n.has("distance")) {
    g.distance = n["distance"].realAbove(0.0, 1000.0);
  }
  if (n.has("near_layers")) {
    g.nearLayers = static_cast<int>(n["near_layers"].integer(1, 64));
  }
  if (n.has("near_distance")) {
    g.nearDistance = n["near_distance"].real(0.0, 1000.0);
  }
  return g;
}

ForestDesc readForest(const Node& n) {
  n.object({"species", "count", "seed", "spacing", "max_slope", "min_height", "max_height", "density_map",
            "cluster_size", "bare", "region", "bark", "foliage", "far_distance", "far_band", "far_count",
            "autumn", "leaf_fall"});
  ForestDesc f;
  {
    const Node s = n["species"];
    if (!s.value().is_object()) {
      s.error(fmt::format("expected an object of species → weight, got {}", s.value().type_name()));
    }
    if (s.value().empty()) {
      s.error("expected at least one species");
    }
    if (s.value().size() > 32) {
      s.error(fmt::format("{} species is more than 32", s.value().size()));
    }
    for (const auto& [key, v] : s.value().items()) {
      const Node w = s.child(key);
      const float weight = w.realAbove(0.0, 1e6);
      std::string species;
      if (key.find('/') != std::string::npos || lowerExtension(key) == ".json") {
        species = w.resolveFile(key, {".json"});
      } else {
        species = Node(json(key), n.context(), w.path()).name();
      }
      f.species[species] = weight;
    }
  }
  if (n.has("count")) {
    f.count = n["count"].integer(0, kMaxForestCount);
  }
  if (n.has("seed")) {
    f.seed = n["seed"].seed();
  }
  if (n.has("spacing")) {
    f.spacing = n["spacing"].realAbove(0.0, 1000.0);
  }
  if (n.has("max_slope")) {
    f.maxSlope = n["max_slope"].real(0.0, 90.0);
  }
  if (n.has("min_height")) {
    f.minHeight = n["min_height"].real(-20000.0, 20000.0);
  }
  if (n.has("max_height")) {
    f.maxHeight = n["max_height"].real(-20000.0, 20000.0);
    if (f.minHeight && *f.maxHeight <= *f.minHeight) {
      n["max_height"].error(
          fmt::format("{} is not above min_height {}", showNumber(*f.maxHeight), showNumber(*f.minHeight)));
    }
  }
  if (n.has("density_map")) {
    f.densityMap = n["density_map"].file({".png"});
  }
  if (n.has("cluster_size")) {
    f.clusterSize = n["cluster_size"].realAbove(0.0, 1e5);
  }
  if (n.has("bare")) {
    f.bare = n["bare"].real(0.0, 0.99);
  }
  if (n.has("autumn")) {
    f.autumn = static_cast<float>(n["autumn"].real(0.0, 1.0));
  }
  if (n.has("leaf_fall")) {
    f.leafFall = static_cast<float>(n["leaf_fall"].real(0.0, 1.0));
  }
  if (n.has("region")) {
    const Node r = n["region"];
    r.object({"centre", "radius"});
    f.regionCentre = r["centre"].vec2(-kBig, kBig);
    f.regionRadius = r["radius"].realAbove(0.0, kBig);
  }
  if (n.has("bark")) {
    f.bark = n["bark"].string();
    if (f.bark.find('/') != std::string::npos || lowerExtension(f.bark) == ".json") {
      f.bark = n["bark"].file({".json"});
    } else {
      f.bark = n["bark"].name();
    }
  }
  if (n.has("foliage")) {
    f.foliage = n["foliage"].boolean();
  }
  if (n.has("far_distance")) {
    f.farDistance = n["far_distance"].real(0.0, kBig);
  }
  if (n.has("far_band")) {
    f.farBand = n["far_band"].real(0.0, kBig);
  }
  if (n.has("far_count")) {
    f.farCount = n["far_count"].integer(0, kMaxForestCount);
  }
  return f;
}

WaterDesc readWater(const Node& n) {
  n.object({"level", "folding", "band", "tile"});
  WaterDesc w;
  w.level = n["level"].real(-20000.0, 20000.0);
  if (n.has("folding")) {
    w.folding = n["folding"].file({".json"});
  }
  if (n.has("band")) {
    w.band = n["band"].realAbove(0.0, 1000.0);
  }
  if (n.has("tile")) {
    w.tile = n["tile"].realAbove(0.0, 10000.0);
  }
  return w;
}

BodyDesc readBody(const Node& n) {
  n.object({"shape", "position", "velocity", "radius", "half_extents", "mass"});
  BodyDesc b;
  const std::string shape = n.has("shape") ? n["shape"].choice({"ball", "box"}) : std::string("ball");
  b.shape = shape == "box" ? BodyDesc::Shape::Box : BodyDesc::Shape::Ball;
  b.position = n["position"].point();
  if (n.has("velocity")) {
    b.velocity = n["velocity"].vec3(-1000.0, 1000.0);
  }
  if (n.has("radius")) {
    if (b.shape != BodyDesc::Shape::Ball) {
      n["radius"].error("only for shape 'ball' (a box has 'half_extents')");
    }
    b.radius = n["radius"].realAbove(0.0, 1000.0);
  }
  if (n.has("half_extents")) {
    if (b.shape != BodyDesc::Shape::Box) {
      n["half_extents"].error("only for shape 'box' (a ball has 'radius')");
    }
    b.halfExtents = n["half_extents"].vec3(1e-3, 1000.0);
  }
  if (n.has("mass")) {
    b.mass = n["mass"].realAbove(0.0, 1e9);
  }
  return b;
}

BodyDrop readDrop(const Node& n) {
  n.object({"centre", "radius", "count", "seed", "height"});
  BodyDrop d;
  d.centre = n["centre"].vec2(-kBig, kBig);
  if (n.has("radius")) {
    d.radius = n["radius"].real(0.0, 1e5);
  }
  if (n.has("count")) {
    d.count = n["count"].integer(1, kMaxBodies);
  }
  if (n.has("seed")) {
    d.seed = n["seed"].seed();
  }
  if (n.has("height")) {
    d.height = n["height"].real(0.0, 1e5);
  }
  return d;
}

CameraKey readKey(const Node& n, bool needTime) {
  n.object({"time", "position", "target", "fov"});
  CameraKey k;
  if (needTime) {
    k.time = n["time"].number(-1e9, 1e9);
  } else if (n.has("time")) {
    k.time = n["time"].number(-1e9, 1e9);
  }
  k.position = n["position"].point();
  k.target = n["target"].point();
  if (n.has("fov")) {
    k.fov = n["fov"].realAbove(0.0, 179.0);
  }
  if (k.position.aboveGround == k.target.aboveGround && k.position.p == k.target.p) {
    n["target"].error("equals the position (the camera needs a direction)");
  }
  return k;
}

/** A camera: {"keys": [...], "loop": b} or, for a still camera, one key's fields directly. */
CameraDesc readCamera(const Node& n) {
  if (!n.value().is_object()) {
    n.error(fmt::format("expected an object, got {}", n.value().type_name()));
  }
  CameraDesc c;
  if (!n.has("keys")) {
    if (n.has("loop")) {
      n["loop"].error("only for a camera with 'keys'");
    }
    c.keys.push_back(readKey(n, false));
    return c;
  }
  n.object({"keys", "loop"});
  const Node keys = n["keys"];
  const std::size_t count = keys.array(1, 100000);
  for (std::size_t i = 0; i < count; ++i) {
    c.keys.push_back(readKey(keys.item(i), count > 1));
    if (i > 0 && !(c.keys[i].time > c.keys[i - 1].time)) {
      keys.item(i)["time"].error(fmt::format("{} is not after the previous key's {}",
                                             showNumber(c.keys[i].time), showNumber(c.keys[i - 1].time)));
    }
  }
  if (n.has("loop")) {
    c.loop = n["loop"].boolean();
  }
  return c;
}

void readOutput(const Node& n, OutputDesc& o) {
  n.object({"camera", "width", "height", "fps", "first_frame", "last_frame"});
  if (n.has("camera")) {
    o.camera = n["camera"].string();
  }
  if (n.has("width")) {
    o.width = n["width"].integer(1, kMaxImageSide);
  }
  if (n.has("height")) {
    o.height = n["height"].integer(1, kMaxImageSide);
  }
  if (n.has("fps")) {
    o.fps = n["fps"].numberAbove(0.0, 1000.0);
  }
  if (n.has("first_frame")) {
    o.firstFrame = n["first_frame"].integer(0, kMaxFrames - 1);
  }
  o.lastFrame = o.firstFrame;
  if (n.has("last_frame")) {
    o.lastFrame = n["last_frame"].integer(0, kMaxFrames - 1);
    if (o.lastFrame < o.firstFrame) {
      n["last_frame"].error(fmt::format("{} is before first_frame {}", o.lastFrame, o.firstFrame));
    }
  }
}

} // namespace

glm::vec3 SunDesc::direction() const {
  const float az = glm::radians(azimuth);
  const float el = glm::radians(elevation);
  // Azimuth clockwise from north (−z) seen from above (y up): 0 → −z, 90 → +x (east), 180 → +z (south).
  return glm::normalize(glm::vec3(std::sin(az) * std::cos(el), std::sin(el), -std::cos(az) * std::cos(el)));
}

namespace {

/**
 * The scene of `text`. Without `errors` the first error throws; with it every section and list item is read
 * on its own and each error is appended (one per item: a bad grass layer does not hide a bad forest), and
 * what could be read is returned.
 */
SceneDesc parseSceneCollecting(std::string_view text, const std::filesystem::path& fileForErrorsAndPaths,
                               SceneFileErrors* errors) {
  const auto attempt = [errors](const auto& read) {
    if (errors == nullptr) {
      read();
      return true;
    }
    try {
      read();
      return true;
    } catch (const Error& e) {
      errors->messages.push_back(e.what());
      return false;
    }
  };
  // A list item that fails holds its defaults, so later checks keep the file's indices.
  const auto failedItem = [errors](const char* list, std::size_t i) {
    if (errors != nullptr) {
      errors->items.insert(fmt::format("/{}/{}", list, i));
    }
  };
  Context ctx;
  ctx.file = fileForErrorsAndPaths.string();
  std::error_code ec;
  fs::path absolute = fs::absolute(fileForErrorsAndPaths, ec);
  ctx.dir = (ec ? fileForErrorsAndPaths : absolute).parent_path();
  const json doc = parseJsonStrict(text, ctx.file);
  const Node root(doc, ctx, "");

  SceneDesc scene;
  scene.path = ctx.file;
  scene.name = fileForErrorsAndPaths.stem().string();

  // The version first, before any other check: a newer file's fields would read as unknown.
  if (!doc.is_object()) {
    root.error(fmt::format("expected an object, got {}", doc.type_name()));
  }
  const Node version = root["sylva_scene"];
  const int v = version.integer(1, std::numeric_limits<int>::max());
  if (v > kSceneVersion) {
    version.error(
        fmt::format("version {} was written by a newer Sylva (this one reads {})", v, kSceneVersion));
  }
  attempt([&] {
    root.object({"sylva_scene", "name", "terrain", "grass", "forests", "water", "bodies", "drops", "sun",
                 "sky", "fog", "wind", "shadows", "cameras", "output"});
  });
  if (root.has("name")) {
    attempt([&] { scene.name = root["name"].string(); });
  }
  if (root.has("terrain")) {
    attempt([&] { readTerrain(root["terrain"], scene.terrain); });
  }
  if (root.has("grass")) {
    const Node list = root["grass"];
    std::size_t n = 0;
    attempt([&] { n = list.array(0, 16); });
    for (std::size_t i = 0; i < n; ++i) {
      if (!attempt([&] { scene.grass.push_back(readGrass(list.item(i))); })) {
        scene.grass.emplace_back();
        failedItem("grass", i);
      }
    }
  }
  if (root.has("forests")) {
    const Node list = root["forests"];
    std::size_t n = 0;
    attempt([&] { n = list.array(0, 64); });
    for (std::size_t i = 0; i < n; ++i) {
      if (!attempt([&] { scene.forests.push_back(readForest(list.item(i))); })) {
        scene.forests.emplace_back();
        failedItem("forests", i);
      }
    }
  }
  if (root.has("water")) {
    const Node list = root["water"];
    std::size_t n = 0;
    attempt([&] { n = list.array(0, 16); });
    for (std::size_t i = 0; i < n; ++i) {
      if (!attempt([&] { scene.water.push_back(readWater(list.item(i))); })) {
        scene.water.emplace_back();
        failedItem("water", i);
      }
    }
  }
  long long bodies = 0;
  if (root.has("bodies")) {
    const Node list = root["bodies"];
    std::size_t n = 0;
    attempt([&] { n = list.array(0, kMaxBodies); });
    for (std::size_t i = 0; i < n; ++i) {
      attempt([&] { scene.bodies.push_back(readBody(list.item(i))); });
    }
    bodies = static_cast<long long>(n);
  }
  if (root.has("drops")) {
    const Node list = root["drops"];
    std::size_t n = 0;
    attempt([&] { n = list.array(0, 1000); });
    for (std::size_t i = 0; i < n; ++i) {
      attempt([&] {
        const BodyDrop drop = readDrop(list.item(i));
        bodies += drop.count;
        if (bodies > kMaxBodies) {
          list.item(i)["count"].error(fmt::format("{} bodies in all is more than {}", bodies, kMaxBodies));
        }
        scene.drops.push_back(drop);
      });
    }
  }
  if (root.has("sun")) {
    attempt([&] {
      const Node n = root["sun"];
      n.object({"azimuth", "elevation", "intensity"});
      if (n.has("azimuth")) {
        scene.sun.azimuth = n["azimuth"].real(-360.0, 360.0);
      }
      if (n.has("elevation")) {
        scene.sun.elevation = n["elevation"].real(-90.0, 90.0);
      }
      if (n.has("intensity")) {
        scene.sun.intensity = n["intensity"].real(0.0, 1000.0);
      }
    });
  }
  if (root.has("sky")) {
    attempt([&] {
      const Node n = root["sky"];
      n.object({"enabled", "turbidity", "exposure", "flare"});
      if (n.has("enabled")) {
        scene.sky.enabled = n["enabled"].boolean();
      }
      if (n.has("turbidity")) {
        scene.sky.turbidity = n["turbidity"].real(1.7, 10.0);
      }
      if (n.has("exposure")) {
        scene.sky.exposure = n["exposure"].realAbove(0.0, 1000.0);
      }
      if (n.has("flare")) {
        scene.sky.flare = n["flare"].boolean();
      }
    });
  }
  if (root.has("fog")) {
    attempt([&] {
      const Node n = root["fog"];
      n.object({"density"});
      if (n.has("density")) {
        scene.fog.density = n["density"].real(0.0, 1.0);
      }
    });
  }
  if (root.has("wind")) {
    attempt([&] {
      const Node n = root["wind"];
      n.object({"speed", "direction", "gusts", "seed"});
      if (n.has("speed")) {
        scene.wind.speed = n["speed"].real(0.0, 100.0);
      }
      if (n.has("direction")) {
        scene.wind.direction = n["direction"].real(-360.0, 360.0);
      }
      if (n.has("gusts")) {
        scene.wind.gusts = n["gusts"].real(0.0, 4.0);
      }
      if (n.has("seed")) {
        scene.wind.seed = n["seed"].seed();
      }
    });
  }
  if (root.has("shadows")) {
    attempt([&] {
      const Node n = root["shadows"];
      n.object({"cascades", "size", "distance", "lambda"});
      if (n.has("cascades")) {
        scene.shadows.cascades = n["cascades"].integer(0, 4);
      }
      if (n.has("size")) {
        scene.shadows.size = n["size"].integer(64, 8192);
      }
      if (n.has("distance")) {
        scene.shadows.distance = n["distance"].realAbove(0.0, 1e5);
      }
      if (n.has("lambda")) {
        scene.shadows.lambda = n["lambda"].real(0.0, 1.0);
      }
    });
  }
  const bool camerasRead = attempt([&] {
    const Node cams = root["cameras"];
    if (!cams.value().is_object()) {
      cams.error(fmt::format("expected an object of name → camera, got {}", cams.value().type_name()));
    }
    if (cams.value().empty()) {
      cams.error("expected at least one camera");
    }
    if (cams.value().size() > 1000) {
      cams.error(fmt::format("{} cameras is more than 1000", cams.value().size()));
    }
    for (const auto& item : cams.value().items()) {
      const std::string name = item.key(); // a copy: clang before 16 cannot capture a structured binding
      attempt([&] {
        if (name.empty()) {
          cams.child(name).error("a camera name must not be empty");
        }
        scene.cameras[name] = readCamera(cams.child(name));
      });
    }
  });
  if (root.has("output")) {
    attempt([&] { readOutput(root["output"], scene.output); });
  }
  if (camerasRead && !scene.cameras.empty() && !scene.cameras.contains(scene.output.camera)) {
    std::vector<std::string> names;
    for (const auto& [name, c] : scene.cameras) {
      names.push_back(name);
    }
    const std::string hint = closestKey(scene.output.camera, names);
    const std::string what =
        fmt::format("no camera '{}' in /cameras{}", scene.output.camera,
                    hint.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", hint));
    attempt([&] {
      if (root.has("output") && root["output"].has("camera")) {
        root["output"]["camera"].error(what);
      }
      Node(doc, ctx, "/output/camera").error(what);
    });
  }
  return scene;
}

} // namespace

SceneDesc parseScene(std::string_view text, const std::filesystem::path& fileForErrorsAndPaths) {
  return parseSceneCollecting(text, fileForErrorsAndPaths, nullptr);
}

SceneDesc parseSceneAll(std::string_view text, const std::filesystem::path& fileForErrorsAndPaths,
                        SceneFileErrors& errors) {
  return parseSceneCollecting(text, fileForErrorsAndPaths, &errors);
}

SceneDesc loadScene(const std::filesystem::path& file) {
  return parseScene(readTextFile(file), file);
}

FieldName sceneFieldName(const SceneDesc& scene, const std::string& prefix) {
  return [names = scene.fieldNames, path = scene.path, prefix](std::string_view field) {
    const std::string pointer = prefix + "/" + std::string(field);
    return names ? names(pointer) : path + ": " + pointer;
  };
}

} // namespace sylva::scene

// Blade-model files: strict parsing (every error names the file and the JSON path), canonical writing.
//
// Format, version 1 (for docs/capture.md#blade-model-files). A JSON object:
//   {
//     "version": 1,                          integer, must be 1
//     "kind": "sylva-blade-models",          must be exactly this
//     "generator": "sylva capture 0.x: …",  optional free text (may be empty)
//     "blades": [                            1 … 65,536 blade models
//       {
//         "name": "aloe-3",                  non-empty string
//         "bendAxis": [x, y, z],             unit vector (length within 1e-3 of 1), blade space
//         "colour": [r, g, b],               optional: mean linear RGB in [0, 1]
//         "source": {                        optional metadata; when present every field is required
//           "file": "aloeGT.png",            string (may be empty)
//           "kind": "middlebury",            string: depthSourceName() of the input (may be empty)
//           "frame": 0, "cluster": 0, "blade": 0,          integers ≥ 0
//           "intrinsics": {"fx": …, "fy": …, "cx": …, "cy": …},  fx, fy > 0; all finite
//           "relativeDepth": false, "medialAxis": false,    booleans
//           "motionFrames": 1,               integer ≥ 1
//           "mu": 0.5                        number in [0, 1]
//         },
//         "lods": [                          1 … 16 levels, finest first, knot counts strictly decreasing
//           {
//             "knots": N,                    integer in [2, 4096]; the length of each array below
//             "positions": [[x, y, z], …],   metres, blade space, root first; |coordinate| ≤ 1000
//             "widths": [w, …],              metres, finite and ≥ 0
//             "normals": [[x, y, z], …]      unit vectors (length within 1e-3 of 1)
//           }
//         ]
//       }
//     ]
//   }
// Unknown fields are errors at every level. Numbers are written with enough digits to round-trip floats.
// Errors read "<file>: <JSON pointer>: <reason>" (sylva::JsonNode), e.g. `grass.json:
// /blades/2/lods/0/widths/5: -0.5 is less than 0`; the envelope's are `<file>: /version: must be 1`
// (sylva::requireJsonVersion).
#include <sylva/blades/BladeModel.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/JsonNode.hpp>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <cstdlib>

#include <algorithm>
#include <cmath>

namespace sylva::blades {

namespace {

using nlohmann::json;

constexpr std::size_t kMaxBlades = 65536;
constexpr std::size_t kMaxKnots = 4096;
constexpr std::size_t kMaxLods = 16;
constexpr double kMaxCoordinate = 1000.0;
constexpr double kUnitTolerance = 1e-3;
constexpr const char* kKind = "sylva-blade-models";

/** `[x, y, z]` with every coordinate in [lo, hi]. Errors: `expected [x, y, z]`, then those of number(). */
glm::vec3 vec3(const JsonNode& n, double lo, double hi) {
  if (!n.value().is_array() || n.value().size() != 3) {
    n.error("expected [x, y, z]");
  }
  return {static_cast<float>(n[std::size_t{0}].number(lo, hi)), static_cast<float>(n[1].number(lo, hi)),
          static_cast<float>(n[2].number(lo, hi))};
}

/** A unit vector `[x, y, z]`: length within kUnitTolerance of 1. */
glm::vec3 unitVector(const JsonNode& n) {
  const glm::vec3 v = vec3(n, -2.0, 2.0);
  const double length = glm::length(glm::dvec3(v));
  if (std::abs(length - 1.0) > kUnitTolerance) {
    n.error(fmt::format("expected a unit vector (length 1 ± {}), got length {:.6g}", kUnitTolerance, length));
  }
  return v;
}

BladeLod parseLod(const JsonNode& n) {
  n.object({"knots", "positions", "widths", "normals"});
  const auto knots = static_cast<std::size_t>(n["knots"].integer(2, static_cast<int>(kMaxKnots)));
  BladeLod lod;
  const JsonNode positions = n["positions"];
  const JsonNode widths = n["widths"];
  const JsonNode normals = n["normals"];
  positions.arrayOf(knots, "'knots'");
  widths.arrayOf(knots, "'knots'");
  normals.arrayOf(knots, "'knots'");
  lod.positions.reserve(knots);
  lod.widths.reserve(knots);
  lod.normals.reserve(knots);
  for (std::size_t k = 0; k < knots; ++k) {
    lod.positions.push_back(vec3(positions[k], -kMaxCoordinate, kMaxCoordinate));
  }
  for (std::size_t k = 0; k < knots; ++k) {
    lod.widths.push_back(static_cast<float>(widths[k].nonNegative()));
    if (!std::isfinite(lod.widths.back())) {
      widths[k].error("expected a finite number ≥ 0"); // beyond float range
    }
  }
  for (std::size_t k = 0; k < knots; ++k) {
    lod.normals.push_back(unitVector(normals[k]));
  }
  return lod;
}

CameraIntrinsics parseIntrinsics(const JsonNode& n) {
  n.object({"fx", "fy", "cx", "cy"});
  CameraIntrinsics in;
  in.fx = n["fx"].number(1e-6, 1e9);
  in.fy = n["fy"].number(1e-6, 1e9);
  in.cx = n["cx"].number(-1e9, 1e9);
  in.cy = n["cy"].number(-1e9, 1e9);
  return in;
}

BladeSource parseSource(const JsonNode& n) {
  n.object({"file", "kind", "frame", "cluster", "blade", "intrinsics", "relativeDepth", "medialAxis",
            "motionFrames", "mu"});
  constexpr int kMaxIndex = 1 << 30;
  BladeSource s;
  s.file = n["file"].string(true);
  s.kind = n["kind"].string(true);
  s.frame = n["frame"].integer(0, kMaxIndex);
  s.cluster = n["cluster"].integer(0, kMaxIndex);
  s.blade = n["blade"].integer(0, kMaxIndex);
  s.intrinsics = parseIntrinsics(n["intrinsics"]);
  s.relativeDepth = n["relativeDepth"].boolean();
  s.medialAxis = n["medialAxis"].boolean();
  s.motionFrames = n["motionFrames"].integer(1, kMaxIndex);
  s.mu = n["mu"].number(0.0, 1.0);
  return s;
}

BladeModel parseBlade(const JsonNode& n) {
  n.object({"name", "bendAxis", "colour", "source", "lods"});
  BladeModel blade;
  blade.name = n["name"].string(false);
  blade.bendAxis = unitVector(n["bendAxis"]);
  if (n.has("colour")) {
    blade.hasColour = true;
    blade.colour = vec3(n["colour"], 0.0, 1.0);
  }
  if (n.has("source")) {
    blade.source = parseSource(n["source"]);
  }
  const JsonNode lods = n["lods"];
  const std::size_t count = lods.array(1, kMaxLods);
  for (std::size_t i = 0; i < count; ++i) {
    blade.lods.push_back(parseLod(lods[i]));
    if (i > 0 && blade.lods[i].knotCount() >= blade.lods[i - 1].knotCount()) {
      lods[i]["knots"].error(fmt::format("knot counts must decrease from level to level ({} after {})",
                                         blade.lods[i].knotCount(), blade.lods[i - 1].knotCount()));
    }
  }
  return blade;
}

/**
 * A float as the double of its shortest decimal form, so files hold "0.1" rather than "0.10000000149011612"
 * (a third of the size); parsing it back and casting to float gives the same float.
 */
double shortest(float f) {
  return std::strtod(fmt::format("{}", f).c_str(), nullptr);
}

/**
 * Puts arrays that hold only numbers on one line ("[0.1, 0.2, 0.3]"): 2-space JSON with one number per line
 * makes knot lists several times longer and harder to read.
 */
std::string compactNumberArrays(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '[') {
      const std::size_t close = text.find_first_of("[]", i + 1);
      if (close != std::string::npos && text[close] == ']') {
        const std::string body = text.substr(i + 1, close - i - 1);
        const bool numeric = body.find_first_not_of("0123456789.eE+-, \n") == std::string::npos &&
                             body.find_first_of("0123456789") != std::string::npos;
        if (numeric) {
          out += '[';
          bool pendingSpace = false;
          for (const char ch : body) {
            if (ch == ' ' || ch == '\n') {
              continue;
            }
            if (pendingSpace) {
              out += ' ';
              pendingSpace = false;
            }
            out += ch;
            pendingSpace = ch == ',';
          }
          out += ']';
          i = close + 1;
          continue;
        }
      }
    }
    out += text[i++];
  }
  return out;
}

json vecJson(const glm::vec3& v) {
  return json::array({shortest(v.x), shortest(v.y), shortest(v.z)});
}

json lodJson(const BladeLod& lod) {
  json positions = json::array();
  json normals = json::array();
  for (const glm::vec3& p : lod.positions) {
    positions.push_back(vecJson(p));
  }
  for (const glm::vec3& n : lod.normals) {
    normals.push_back(vecJson(n));
  }
  json widths = json::array();
  for (const float w : lod.widths) {
    widths.push_back(shortest(w));
  }
  return {{"knots", lod.knotCount()}, {"positions", positions}, {"widths", widths}, {"normals", normals}};
}

json sourceJson(const BladeSource& s) {
  return {
      {"file", s.file},
      {"kind", s.kind},
      {"frame", s.frame},
      {"cluster", s.cluster},
      {"blade", s.blade},
      {"intrinsics",
       {{"fx", s.intrinsics.fx}, {"fy", s.intrinsics.fy}, {"cx", s.intrinsics.cx}, {"cy", s.intrinsics.cy}}},
      {"relativeDepth", s.relativeDepth},
      {"medialAxis", s.medialAxis},
      {"motionFrames", s.motionFrames},
      {"mu", s.mu}};
}

} // namespace

float BladeModel::length() const {
  if (lods.empty()) {
    return 0.0f;
  }
  double total = 0.0;
  const std::vector<glm::vec3>& p = lods.front().positions;
  for (std::size_t k = 1; k < p.size(); ++k) {
    total += glm::length(glm::dvec3(p[k]) - glm::dvec3(p[k - 1]));
  }
  return static_cast<float>(total);
}

float BladeModel::maxWidth() const {
  if (lods.empty() || lods.front().widths.empty()) {
    return 0.0f;
  }
  return *std::max_element(lods.front().widths.begin(), lods.front().widths.end());
}

const BladeLod& BladeModel::lodForKnots(std::size_t knots) const {
  if (lods.empty()) {
    fail("blade '{}' has no levels of detail", name);
  }
  for (const BladeLod& lod : lods) {
    if (lod.knotCount() <= knots) {
      return lod;
    }
  }
  return lods.back();
}

nlohmann::json toJson(const BladeModelFile& file) {
  json blades = json::array();
  for (const BladeModel& blade : file.blades) {
    json b = {{"name", blade.name}, {"bendAxis", vecJson(blade.bendAxis)}};
    if (blade.hasColour) {
      b["colour"] = vecJson(blade.colour);
    }
    b["source"] = sourceJson(blade.source);
    json lods = json::array();
    for (const BladeLod& lod : blade.lods) {
      lods.push_back(lodJson(lod));
    }
    b["lods"] = std::move(lods);
    blades.push_back(std::move(b));
  }
  return {
      {"version", kBladeModelVersion}, {"kind", kKind}, {"generator", file.generator}, {"blades", blades}};
}

BladeModelFile parseBladeModels(const nlohmann::json& json, const std::string& where) {
  requireJsonVersion(json, kBladeModelVersion, where);
  const JsonNode root(json, where, "");
  root.object({"version", "kind", "generator", "blades"});
  const std::string kind = root["kind"].string(true);
  if (kind != kKind) {
    root["kind"].error(fmt::format("expected \"{}\", got \"{}\"", kKind, kind));
  }
  BladeModelFile file;
  if (root.has("generator")) {
    file.generator = root["generator"].string(true);
  }
  const JsonNode blades = root["blades"];
  const std::size_t count = blades.array(1, kMaxBlades);
  file.blades.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    file.blades.push_back(parseBlade(blades[i]));
  }
  return file;
}

BladeModelFile loadBladeModels(const std::filesystem::path& path) {
  return parseBladeModels(loadJsonFile(path), path.string());
}

void saveBladeModels(const std::filesystem::path& path, const BladeModelFile& file) {
  const json document = toJson(file);
  // Whatever is written must load again: the same checks, with the same messages, before anything is written.
  (void)parseBladeModels(document, path.string());
  writeTextFile(path, compactNumberArrays(document.dump(2)) + "\n");
}

} // namespace sylva::blades

#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sylva::folding {

/**
 * Continuous pixel coordinates of one input image: x to the right, y down, pixel (i, j) covers
 * [i, i+1) × [j, j+1) and its centre is (i + ½, j + ½). Zones, anchors, tools and folding polygons are all in
 * the coordinates of the image their zone lives on.
 */
using Vec2 = glm::dvec2;

/** Limits that keep a project within what the renderers and the encodings can carry. */
inline constexpr int kMaxImages = 16;
/** Most motion profiles. */
inline constexpr int kMaxProfiles = 16;
/** Most knots of a piecewise position function. */
inline constexpr int kMaxKnots = 16;
/** Most jump layers. */
inline constexpr int kMaxJumpLayers = 4;
/** Largest atlas side, texels. */
inline constexpr int kMaxAtlasSide = 16384;
/** Most vertices of a zone or folding polygon. */
inline constexpr int kMaxPolygonVertices = 4096;
/** Most samples of a curve tool. */
inline constexpr int kMaxCurveSamples = 4096;

/** Position function p(φ) of a motion profile (docs/folding.md, "Position functions"). */
struct PositionFunction {
  /** The function's kind. */
  enum class Type : std::uint8_t { Linear, Piecewise, Exponential, Sigmoid, Sine };
  /** The function's kind. */
  Type type = Type::Linear;
  /** linear: p = clamp(slope·(φ − delay), 0, 1); the thesis's temporal shift b = −slope·delay. */
  double slope = 1.0;
  /** linear: the delay before the ramp starts, in cycles. */
  double delay = 0.0;
  /** piecewise: knots (φ_i, p_i), φ_0 = 0 < … < φ_n = 1, at most kMaxKnots. */
  std::vector<glm::dvec2> knots;
  /** exponential: rate k (k → 0 gives φ); sigmoid: steepness k and centre c. */
  double k = 4.0;
  /** sigmoid: the centre c of the ramp, in cycles. */
  double centre = 0.5;
  /** sine: p = amplitude·(1 − cos(2π·frequency·φ + phase))/2 + offset. */
  double amplitude = 1.0;
  /** sine: cycles of the cosine per motion cycle. */
  double frequency = 1.0;
  /** sine: phase, radians. */
  double phase = 0.0;
  /** sine: offset added to p. */
  double offset = 0.0;

  /** p(φ) for φ in [0, 1), without any loop remapping. */
  double evaluate(double phi) const;

  /** Every field equal. */
  bool operator==(const PositionFunction&) const = default;
};

/** How a profile closes its loop: as is, ping-pong φ' = 1 − |1 − 2φ|, or the two-phase crossfade. */
enum class LoopMode : std::uint8_t { None, PingPong, Crossfade };

/** A motion profile: position function, period and shift, shared by the zones that name it. */
struct Profile {
  /** Unique id the zones name it by. */
  std::string id;
  double periodS = 2.0; ///< seconds per cycle, > 0
  double shift = 0.0;   ///< σ, cycles added to t / period
  /** The position function p(φ). */
  PositionFunction fn;
  /** How the loop closes. */
  LoopMode loop = LoopMode::None;

  /** Every field equal. */
  bool operator==(const Profile&) const = default;
};

/** Spatial interpolation of anchor vectors into the zone (docs/folding.md, "Interpolation"). */
struct Interpolation {
  /** The Shepard variant. */
  enum class Type : std::uint8_t { Shepard, ModifiedShepard, ModifiedShepardRandom };
  /** The Shepard variant. */
  Type type = Type::ModifiedShepard;
  double power = 2.0;   ///< Shepard exponent p
  double radius = 64.0; ///< R, pixels (modified variants)
  double ring = 8.0;    ///< τ, ring width in pixels (randomised variant), 0 < τ < R

  /** Every field equal. */
  bool operator==(const Interpolation&) const = default;
};

/** A zone shape: an axis-aligned rectangle or a simple polygon, in image pixels. */
struct Shape {
  /** Rectangle or polygon. */
  enum class Type : std::uint8_t { Rect, Polygon };
  /** Rectangle or polygon. */
  Type type = Type::Rect;
  Vec2 min{0.0};         ///< rect
  Vec2 max{0.0};         ///< rect
  std::vector<Vec2> pts; ///< polygon vertices, either winding, not closed (first ≠ last)

  /** The outline as a polygon (a rect gives its 4 corners). */
  std::vector<Vec2> outline() const;

  /** Every field equal. */
  bool operator==(const Shape&) const = default;
};

/** Tools: each turns a user's forward intent (a moves to b) into backward anchors at b with vector a − b. */
struct TranslateTool {
  Vec2 v{0.0}; ///< forward motion T (pixels); J = −T inside the zone

  /** Every field equal. */
  bool operator==(const TranslateTool&) const = default;
};
/** Scaling about a centre: the content grows (k > 1) or shrinks (k < 1). */
struct ScaleTool {
  double factor = 1.0; ///< k > 0; J(x) = (x − c)(1/k − 1)
  /** The centre, zone image pixels. */
  Vec2 centre{0.0};

  /** Every field equal. */
  bool operator==(const ScaleTool&) const = default;
};
/** Point pairs: each moves the content at a to b. */
struct PointsTool {
  std::vector<std::array<Vec2, 2>> pairs; ///< (from a, to b): anchor at b with vector a − b

  /** Every field equal. */
  bool operator==(const PointsTool&) const = default;
};
/** A curve moved to another curve, or along vectors. */
struct CurveTool {
  std::array<Vec2, 4> source{};            ///< cubic Bézier control points of the source curve S
  std::optional<std::array<Vec2, 4>> dest; ///< destination curve D; without it, `vectors` along S
  /** Without `dest`: forward motion vectors at curve parameters u ∈ [0, 1] (arc length), interpolated. */
  std::vector<std::pair<double, Vec2>> vectors;
  int samples = 16; ///< N arc-length-uniform samples, 2..kMaxCurveSamples

  /** Every field equal. */
  bool operator==(const CurveTool&) const = default;
};
/** A polygon deformed vertex by vertex; its interior follows. */
struct LassoTool {
  std::vector<Vec2> from; ///< polygon before the deform
  std::vector<Vec2> to;   ///< the same vertices after it
  bool meanValue = true;  ///< interior by mean-value coordinates (exact on the polygon), else by Shepard only

  /** Every field equal. */
  bool operator==(const LassoTool&) const = default;
};
/** Still points: anchors with a zero vector along a polyline. */
struct ZeroTool {
  std::vector<Vec2> pts; ///< a polyline of still points (sampled every zeroSpacing pixels)

  /** Every field equal. */
  bool operator==(const ZeroTool&) const = default;
};
/** Another image flying over this zone from one place to another. */
struct FlyOverTool {
  std::string object; ///< id of the image that flies over
  Vec2 from{0.0};     ///< object's top-left corner at s = 0, in this zone image's pixels
  Vec2 to{0.0};       ///< the same at s = 1; J = from − to everywhere in the zone

  /** Every field equal. */
  bool operator==(const FlyOverTool&) const = default;
};
/** One of the tools. */
using Tool = std::variant<TranslateTool, ScaleTool, PointsTool, CurveTool, LassoTool, ZeroTool, FlyOverTool>;

/** Where a fold happens: the region whose content the jump paths read (docs/folding.md, "Thresholds"). */
struct Folding {
  /** None, polygons drawn on the image, a mask image, or the flying object's own alpha. */
  enum class Type : std::uint8_t { None, Polygons, Mask, Object };
  /** Where the region comes from. */
  Type type = Type::None;
  std::vector<std::vector<Vec2>> polygons; ///< union of simple polygons, zone image pixels
  std::filesystem::path mask;              ///< grey/alpha image the size of the zone's image; ≥ ½ inside
  /** Pixels whose path never enters the region: still (the spec) or plain warp (t0 = 0, t1 = 1). */
  bool outsideWarps = false;

  /** Every field equal. */
  bool operator==(const Folding&) const = default;
};

/** A motion zone on one image. */
struct Zone {
  /** Unique id. */
  std::string id;
  std::string image; ///< id of the image it lives on
  /** The zone's outline on its image. */
  Shape shape;
  std::string profile;     ///< id of its motion profile
  int layer = 0;           ///< jump layer (multi-jump), 0..kMaxJumpLayers-1
  double phase = 0.0;      ///< dt offset in cycles
  Vec2 phaseGradient{0.0}; ///< extra dt per pixel (cycles/px), from the zone's bounding-box corner
  /** How the tools' anchors are interpolated over the zone. */
  Interpolation interp;
  bool zeroBoundary = false; ///< zero anchors along the zone border
  double zeroSpacing = 4.0;  ///< pixels between sampled zero anchors
  /** Soft edge width (pixels): J fades to 0 over this distance inside the zone border (smoothstep); 0 = hard.
   */
  double feather = 0.0;
  std::filesystem::path freezeMask; ///< optional painted freeze mask (≥ ½ = frozen), image-sized
  /** The tools, applied in order. */
  std::vector<Tool> tools;
  /** Where the zone folds. */
  Folding folding;

  /** Every field equal. */
  bool operator==(const Zone&) const = default;
};

/** One input image of the atlas. */
struct ImageEntry {
  /** Unique id the zones and tools name it by. */
  std::string id;
  std::filesystem::path file; ///< as written in the project (relative to the project file)
  bool crop = true;           ///< crop to what zones and jump paths read (the canvas is never cropped)

  /** Every field equal. */
  bool operator==(const ImageEntry&) const = default;
};

/** Names of the output files (relative to the output directory) and their encoding. */
struct Outputs {
  /** 16-bit RGBA PNGs or float OpenEXR. */
  enum class Encoding : std::uint8_t { Rgba16, Exr };
  /** How the synthesised textures are stored. */
  Encoding encoding = Encoding::Rgba16;
  /** The colour atlas's file. */
  std::string color = "color.png";
  /** The init texture's file. */
  std::string init = "init.png";
  /** The jump texture's file (later layers add 1, 2, …). */
  std::string jump = "jump.png";

  /** Every field equal. */
  bool operator==(const Outputs&) const = default;
};

/** A folding-texture project (file format "sylva-fold", version kProjectVersion). */
struct Project {
  /** Seed of the randomised interpolation and synthesis. */
  std::uint64_t seed = 7;
  int gutter = 4;     ///< pixels between packed images, ≥ 2
  std::string canvas; ///< image shown by renders and previews (default: the first image)
  std::vector<double> jumpLayers{0.0, 1.0}; ///< progress breakpoints of the K jump layers
  /** The input images, in atlas order. */
  std::vector<ImageEntry> images;
  /** The motion profiles. */
  std::vector<Profile> profiles;
  /** The motion zones. */
  std::vector<Zone> zones;
  /** Output file names and encoding. */
  Outputs outputs;
  /** Directory relative file names resolve against (the project file's directory). */
  std::filesystem::path baseDir;

  int imageIndex(const std::string& id) const;   ///< −1 when absent
  int profileIndex(const std::string& id) const; ///< −1 when absent
  int canvasIndex() const;                       ///< index of the canvas image
  /** `file` resolved against baseDir (absolute files stay as they are). */
  std::filesystem::path resolve(const std::filesystem::path& file) const;

  /** Every field equal. */
  bool operator==(const Project&) const = default;
};

/** The project file format's version this build reads and writes. */
inline constexpr int kProjectVersion = 1;

/**
 * Parses and strictly validates a project. Unknown fields, wrong types, NaN/inf, missing references,
 * degenerate or self-intersecting polygons and out-of-range values throw sylva::Error
 * "<where>: <json.path>: <reason>", e.g. "cat.json: zones[0].shape.pts[2]: expected [x, y]". A newer
 * version is refused with a message saying so. Image sizes are not checked here (see validateImages).
 */
Project parseProject(const nlohmann::json& json, const std::string& where);
/** loadJsonFile + parseProject; baseDir is the file's directory. */
Project loadProject(const std::filesystem::path& path);
/**
 * The project as it must be saved at `out` (any path, relative to the working directory or absolute):
 * relative image and mask file names, which resolve against `project.baseDir` (empty: the working directory),
 * rewritten to resolve from `out`'s directory to the same files; baseDir becomes that directory.
 */
Project rebasedProject(Project project, const std::filesystem::path& out);
/** The canonical JSON of a project (parseProject(toJson(p)) == p for every valid p). */
nlohmann::json toJson(const Project& project);
/** Saves atomically (temporary file + rename). */
void saveProject(const std::filesystem::path& path, const Project& project);
/**
 * Checks the parts that need image sizes: zones inside their image, masks the size of their image.
 * `sizes[i]` is the size of images[i]. Throws sylva::Error naming `where` and the JSON path.
 */
void validateAgainstImages(const Project& project, const std::vector<glm::ivec2>& sizes,
                           const std::string& where);

} // namespace sylva::folding

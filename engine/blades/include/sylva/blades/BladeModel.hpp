#pragma once
// Blade-model files: the captured blades, refined to a few knot counts, that the grass field instances.
// Format (docs/capture.md#blade-model-files): a versioned JSON document, validated on load with errors naming
// the file and the JSON path of the field at fault.

#include <sylva/blades/CameraIntrinsics.hpp>

#include <nlohmann/json_fwd.hpp>

#include <glm/vec3.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace sylva::blades {

/** Current version of the blade-model file format. */
inline constexpr int kBladeModelVersion = 1;

/**
 * One level of detail of a blade, in blade space (metres): the root at the origin, +Y up (against gravity),
 * +Z the side the blade faces (towards the capturing camera), +X = Y × Z to the right. Knots run root → tip.
 * The blade's surface at knot k spans positions[k] ± ½·widths[k]·side, side = normalize(cross(tangent,
 * normals[k])) with the tangent along the knot line.
 */
struct BladeLod {
  /** Knot positions, blade space (metres), root first. */
  std::vector<glm::vec3> positions;
  /** Full width at each knot, metres (≥ 0). */
  std::vector<float> widths;
  /** Unit surface normal at each knot, perpendicular to the knot line. */
  std::vector<glm::vec3> normals;
  /** Knots of this level. */
  std::size_t knotCount() const { return positions.size(); }
};

/** Where a blade came from (metadata; not needed to draw it). */
struct BladeSource {
  /** Input file or recording ("kinect" for a live capture, "synthetic:<shape>" for generated ones). */
  std::string file;
  /** depthSourceName() of the input. */
  std::string kind;
  /** Frame of the input the blade was captured in (0 for a still image). */
  int frame = 0;
  /** Index of the blade's cluster (tuft) within that frame's capture result. */
  int cluster = 0;
  /** Index of the blade within its frame's capture result. */
  int blade = 0;
  /** The capturing camera (pixels). */
  CameraIntrinsics intrinsics;
  /** Depth was only known up to scale (Middlebury without calibration): metres are nominal. */
  bool relativeDepth = false;
  /** The skeleton came from the medial axis (asymmetric blade) instead of symmetric matching. */
  bool medialAxis = false;
  /** Frames the refining measured movement over (1: a static capture, refined by distance alone). */
  int motionFrames = 1;
  /** μ used by refining. */
  double mu = 0.5;
};

/** One blade model. */
struct BladeModel {
  /** Name of the blade, unique within its file (e.g. "blade-0"). */
  std::string name;
  /** Levels of detail, finest first, strictly decreasing knot counts, each ≥ 2 knots. */
  std::vector<BladeLod> lods;
  /**
   * The axis the blade bends about most easily (unit, blade space): its mean width direction. The grass
   * solver and wind bend blades about it.
   */
  glm::vec3 bendAxis{1.0f, 0.0f, 0.0f};
  /** Whether `colour` holds the blade's measured colour (a colour frame was present). */
  bool hasColour = false;
  /** Mean colour of the blade's pixels in linear RGB [0, 1] (when hasColour). */
  glm::vec3 colour{0.0f};
  /** Where the blade came from. */
  BladeSource source;

  /** Length along the finest knot line, metres. */
  float length() const;
  /** Largest width of the finest level, metres. */
  float maxWidth() const;
  /** The finest level with at most `knots` knots (the coarsest level when all have more). */
  const BladeLod& lodForKnots(std::size_t knots) const;
};

/** A blade-model file. */
struct BladeModelFile {
  /** The blades, in capture order. */
  std::vector<BladeModel> blades;
  /** Free text: what made the file ("sylva capture 0.x: aloeGT.png"). */
  std::string generator;
};

/** JSON of a file (version kBladeModelVersion). */
nlohmann::json toJson(const BladeModelFile& file);

/**
 * Parses and validates a blade-model document. `where` names the document in errors ("<where>: <json path>:
 * reason"), e.g. `grass.json: blades[2].lods[0].widths[5]: expected a finite number ≥ 0`. Rejects unknown
 * versions, missing or mistyped fields, empty blade lists, levels with fewer than 2 knots, array length
 * mismatches, non-finite numbers, negative widths, non-unit normals, level counts that do not decrease and
 * absurd sizes (more than 65,536 blades or 4,096 knots per level).
 */
BladeModelFile parseBladeModels(const nlohmann::json& json, const std::string& where);

/** Loads and validates a blade-model file; throws sylva::Error naming the file. */
BladeModelFile loadBladeModels(const std::filesystem::path& path);

/** Saves atomically (2-space JSON); throws sylva::Error naming the file. */
void saveBladeModels(const std::filesystem::path& path, const BladeModelFile& file);

} // namespace sylva::blades

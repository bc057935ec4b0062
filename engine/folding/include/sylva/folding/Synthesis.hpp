#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/folding/Field.hpp>
#include <sylva/folding/Project.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace sylva {
class Progress;
}

namespace sylva::folding {

/** Integer pixel rectangle [min, max) (max exclusive). */
struct Rect {
  /** Top-left corner (inclusive). */
  glm::ivec2 min{0};
  /** Bottom-right corner (exclusive). */
  glm::ivec2 max{0};
  /** Columns. */
  int width() const { return max.x - min.x; }
  /** Rows. */
  int height() const { return max.y - min.y; }
  /** Whether it holds no pixel. */
  bool empty() const { return max.x <= min.x || max.y <= min.y; }
  /** Whether pixel `p` lies inside. */
  bool contains(glm::ivec2 p) const { return p.x >= min.x && p.y >= min.y && p.x < max.x && p.y < max.y; }
  /** Same corners. */
  bool operator==(const Rect&) const = default;
};

/** Where one input image lives in the atlas. */
struct AtlasEntry {
  /** The image's id. */
  std::string id;
  glm::ivec2 imageSize{0}; ///< full input image size, pixels
  Rect crop;               ///< the part kept, image pixels
  glm::ivec2 atlasPos{0};  ///< atlas texel of the crop's top-left
  /** Atlas texel of image pixel (0, 0) (may lie outside the atlas when the crop starts past it). */
  glm::ivec2 origin() const { return atlasPos - crop.min; }
  /** The crop's rectangle in the atlas. */
  Rect atlasRect() const { return {atlasPos, atlasPos + glm::ivec2(crop.width(), crop.height())}; }
  /** Every field equal. */
  bool operator==(const AtlasEntry&) const = default;
};

/** The loaded input images (RGBA8) and masks of a project, in project order. */
struct ProjectImages {
  std::vector<Image> images;                   ///< images[i] for project.images[i], RGBA8
  std::vector<std::vector<float>> freezeMasks; ///< per zone, empty when it has none
  std::vector<std::vector<float>> foldMasks;   ///< per zone, empty unless folding.type == Mask
};
/**
 * Loads every image and mask a project names (relative to its baseDir) and validates the project against
 * their sizes. Errors name the project file `where` and the JSON path, or the image file.
 */
ProjectImages loadProjectImages(const Project& project, const std::string& where);

/**
 * Algorithm 1 of the thesis: crops each image to what its zones and their jump paths read (the canvas and
 * images with crop = false stay whole; fly-over objects go where their tool puts them relative to their
 * zone's image), then packs the crops into one atlas with `gutter` pixels between them, filled by repeating
 * edge pixels. Deterministic. Throws sylva::Error when the atlas would exceed kMaxAtlasSide.
 */
struct Atlas {
  Image color;                     ///< RGBA8, width × height
  std::vector<AtlasEntry> entries; ///< per project image
};
/** Packs the project's images (cropped) into one atlas with gutters; errors name the field at fault. */
Atlas packAtlas(const Project& project, const ProjectImages& images);

/**
 * The folding textures in float (the CPU reference and the GPU renderer read these; encodings below).
 * All images are atlas-sized, 4 channels F32:
 *  init  = (x0, y0, dt, profile): base read texel (atlas pixels), phase offset (cycles, [0, 1)),
 *          profile index k, or −1 for a still texel (outside every zone);
 *  jump[k] = (Jx, Jy, t0, t1) of jump layer k: backward jump (atlas pixels), first fold interval;
 *  fold[k] = (t0, t1, t0', t1'): second and third fold intervals of layer k (empty: t0 = t1 = 1).
 */
struct Textures {
  /** The packed colour atlas and where each image is. */
  Atlas atlas;
  /** Base read texel, phase offset and profile per texel. */
  Image init;
  /** Jump vector and first fold interval per layer. */
  std::vector<Image> jump;
  /** Second and third fold intervals per layer. */
  std::vector<Image> fold;
  /** Atlas width, texels. */
  int width() const { return init.width(); }
  /** Atlas height, texels. */
  int height() const { return init.height(); }
  /** Largest |J| component over all layers (pixels): the scale of the 16-bit encoding. */
  double jumpMax() const;
};

/** Per-zone statistics of a synthesis, for reports. */
struct SynthesisStats {
  std::size_t anchors = 0;       ///< over all zones
  std::size_t zonePixels = 0;    ///< texels inside zones
  std::size_t foldedPixels = 0;  ///< texels with a fold interval other than (0, 1]
  std::size_t multiInterval = 0; ///< texels that need the extra fold layer
  /** Per project zone: the largest |J| over its texels, pixels (0: the zone does not move). */
  std::vector<double> zoneJumpMax;
};

/** Zones that move less than this many pixels at their farthest count as still (stillZoneWarnings). */
inline constexpr double kStillZonePx = 0.5;

/**
 * One line per zone whose motion its own settings undo, naming the zone and what to change: a translate with
 * zone_boundary zero anchors within R of every texel (the border anchors' residual +T cancels the translate
 * almost everywhere), or tools that move yet leave the whole zone within kStillZonePx. `stats` from a full
 * synthesis of `project`.
 */
std::vector<std::string> stillZoneWarnings(const Project& project, const SynthesisStats& stats);

/**
 * Synthesises all textures (Algorithms 1–3). Deterministic: same project, images and seed give identical
 * textures on any thread count. `progress` (optional) counts rows.
 */
Textures synthesize(const Project& project, const ProjectImages& images, Progress* progress = nullptr,
                    SynthesisStats* stats = nullptr);

/**
 * Re-synthesises the texels of `region` (atlas pixels) in place, e.g. after an edit that moved one anchor:
 * the result equals a full synthesis inside the region. The atlas layout must be unchanged (same crops).
 */
void resynthesize(const Project& project, const ProjectImages& images, Textures& textures, Rect region);

/**
 * The atlas region a change to `zone` between two project states can affect: its zone's bounding box
 * (both states), as atlas pixels. Moving one anchor is bounded tighter by anchorMoveAtlasRect.
 */
Rect zoneAtlasRect(const Project& project, const Atlas& atlas, int zone);

/**
 * The atlas rectangle (atlas pixels, [min, max)) whose texels can change when one point anchor of `zone`
 * moves from `before` to `after` (zone-image pixels; `project` is the state before or after the move, the
 * anchor sits at one of the two): the texels resynthesize() must redo so that the textures equal a full
 * synthesis of the moved project.
 *  - modified Shepard, plain and randomised: the union of the boxes of half-side R (interp.radius) around
 *    both positions, grown by one texel, intersected with zoneAtlasRect; empty ({0, 0}, {0, 0}) when that
 *    misses the zone. When `before` or `after` is not strictly inside the bounding box of the zone's other
 *    anchors, the move changes the anchor grid and so the order of floating-point sums everywhere: the whole
 *    zone rectangle then.
 *  - Shepard (global weights): the whole zone rectangle.
 * For a points tool the anchor's position is its destination b; when only the source a moves (the vector
 * changes, not the position) pass b for both. The atlas layout must stay the same (packAtlas crops images
 * by how far their jumps reach: compare the entries before reusing the textures).
 */
Rect anchorMoveAtlasRect(const Project& project, const Atlas& atlas, int zone, Vec2 before, Vec2 after);

/** 16-bit encoding (docs/folding.md "Encoding"): J ↔ 32767 + round(32767·J/jumpMax); zero is exact. */
std::uint16_t encodeJump(double j, double jumpMax);
/** The jump an encoded value stands for, pixels. */
double decodeJump(std::uint16_t v, double jumpMax);
/** Progress values in [0, 1] ↔ round(65535·t). */
std::uint16_t encodeUnit(double t);
/** The progress value an encoded value stands for. */
double decodeUnit(std::uint16_t v);
/** Which of the float textures an image is, for its 16-bit encoding. */
enum class TextureKind : std::uint8_t { Init, Jump, Fold };
/**
 * The RGBA16 encoding of one float texture (what saveTextures writes as PNG): init = (x0, y0 texel indices,
 * round(65535·dt), k + 1 with 0 = still); jump = (encodeJump(Jx), encodeJump(Jy), encodeUnit(t0),
 * encodeUnit(t1)); fold = four encodeUnit values. `jumpMax` in pixels.
 */
Image encode16(const Image& texture, TextureKind kind, double jumpMax);

/** File names and scale of an encoded set, written as `folding.json` next to the textures. */
struct EncodedInfo {
  /** How the textures are stored. */
  Outputs::Encoding encoding = Outputs::Encoding::Rgba16;
  /** The jump encoding's scale, pixels. */
  double jumpMax = 0.0;
  /** Jump layers. */
  int layers = 1;
  /** Whether fold textures are written. */
  bool foldLayer = false;
};
/**
 * Writes color (8-bit PNG), init, jump (and jump1…, fold0… when used) with the project's encoding into `dir`,
 * plus `folding.json` (format, encoding, sizes, jumpMax, profiles, atlas entries). Atomic per file.
 */
void saveTextures(const std::filesystem::path& dir, const Project& project, const Textures& textures);
/** Reads a set written by saveTextures back into float textures (decoding as documented). */
Textures loadTextures(const std::filesystem::path& dir, std::vector<Profile>* profiles = nullptr,
                      std::vector<double>* jumpLayers = nullptr);

/** Down-sampled arrows of layer `layer`'s jump field drawn over the atlas (RGBA8), every `step` texels. */
Image vectorFieldPicture(const Textures& textures, int step, int layer = 0);
/** Heat map of t0 (which = 0) or t1 (which = 1) of layer `layer` over a grey atlas (RGBA8). */
Image thresholdHeatMap(const Textures& textures, int which, int layer = 0);

} // namespace sylva::folding

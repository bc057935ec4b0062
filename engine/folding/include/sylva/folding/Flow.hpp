#pragma once
// Motion from a reference video (docs/folding.md, "Motion from a reference video"): load a short clip,
// compute dense optical flow between two of its frames, and turn the flow inside a zone into suggested point
// anchors that the user accepts (one undoable edit), edits or rejects. OpenCV does the decoding and the flow;
// it stays behind this header.

#include <sylva/core/Image.hpp>
#include <sylva/folding/Project.hpp>

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva {
class Progress;
}

namespace sylva::folding {

class EditHistory;

/** Largest frame side loadVideo accepts, pixels. */
inline constexpr int kMaxVideoSide = 8192;
/** Most bytes of decoded RGBA8 frames loadVideo keeps in memory (2 GiB). */
inline constexpr std::size_t kMaxVideoBytes = std::size_t{2} << 30;

/** Frames of a reference video, decoded to RGBA8 (alpha 255), row 0 at the top. */
struct VideoClip {
  std::vector<Image> frames;  ///< in presentation order, each size.x × size.y pixels, RGBA8
  std::vector<double> timesS; ///< presentation time of each frame, seconds (the container's, else i / fps)
  glm::ivec2 size{0};         ///< frame size, pixels
  double fps = 0.0;           ///< nominal frame rate the container states; 0 when it states none
  bool truncated = false;     ///< the video has more frames than the maxFrames that were read
};

/**
 * Decodes up to `maxFrames` (≥ 1) frames of a video file (any container and codec FFmpeg reads: AVI, MP4,
 * WebM, …) or of an image sequence given as a printf pattern (`frames/%04d.png`, numbered from 0 or 1).
 * `progress` (optional) advances once per frame; cancelling it stops the load with an error. Throws
 * sylva::Error with one line naming the file: missing file or directory, not a video, no decodable frame,
 * frames larger than kMaxVideoSide or changing size, more than kMaxVideoBytes of frames.
 */
VideoClip loadVideo(const std::filesystem::path& path, int maxFrames = 900, Progress* progress = nullptr);

/**
 * Writes a clip: `.avi` as Motion-JPEG (OpenCV's own encoder, quality 100, the clip's fps or 25), or a PNG
 * sequence when `path` holds a printf pattern (`frames/%04d.png`, numbered from 0). Each file is written
 * atomically. Throws sylva::Error naming the file.
 */
void saveVideo(const std::filesystem::path& path, const VideoClip& clip);

/** Dense optical flow between two frames of equal size. */
struct FlowField {
  int width = 0;  ///< frame width, pixels
  int height = 0; ///< frame height, pixels
  /**
   * Per texel, row-major from the top-left: the content at texel (x, y) of the first frame is found displaced
   * by v in the second frame, in frame pixels (x right, y down). Texel (x, y) is centred at (x + ½, y + ½).
   */
  std::vector<glm::vec2> v;

  /** Whether the field has no texels. */
  bool empty() const { return width <= 0 || height <= 0; }
  /** v at texel (x, y); no bounds checks. */
  glm::vec2 at(int x, int y) const {
    return v[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  }
  /** Bilinear between texel centres at continuous frame coordinates p (pixels), clamped to the frame. */
  glm::vec2 sample(Vec2 p) const;
  /** Mean and largest length of v over all texels, pixels. */
  double meanMagnitude() const;
  /** Largest length of v over all texels, pixels. */
  double maxMagnitude() const;
};

/** Optical-flow algorithm (both from OpenCV's video module). */
enum class FlowMethod : std::uint8_t {
  /** Dense Inverse Search (Kroeger et al. 2016), preset MEDIUM: fast, robust to large motion. */
  Dis,
  /**
   * Farnebäck's polynomial expansion: pyramid scale 0.5, 5 levels, 15 px window, 3 iterations per level,
   * polynomial neighbourhood 5 px with σ 1.2. Smoother, slower, weaker on large motion.
   */
  Farneback,
};
const char* flowMethodName(FlowMethod method); ///< "dis" or "farneback"

/**
 * Forward flow a → b (where a's content is in b) at every texel of a, in frame pixels. Frames are converted
 * to grey (Rec. 601 weights) first; any channel count and pixel type is accepted. Throws sylva::Error when
 * the frames differ in size or are smaller than 16×16 pixels.
 */
FlowField computeFlow(const Image& a, const Image& b, FlowMethod method);

/** A clip read up to two of its frames, with the flow between them both ways. */
struct VideoFlow {
  VideoClip clip;     ///< frames 0 … max(a, b) (the clip's first frames)
  FlowField forward;  ///< frame a → frame b
  FlowField backward; ///< frame b → frame a (for the consistency check)
};
/**
 * Reads `video` up to frame max(a, b) (a "reading video" progress line) and computes the flow between frames
 * `a` and `b` both ways. Throws sylva::Error naming --frames and the file when the clip is shorter.
 */
VideoFlow videoFlow(const std::filesystem::path& video, int a, int b, FlowMethod method);

/**
 * "VIDEO: WxH, N frames read, F fps; flow a -> b (T s apart), METHOD" and the flow's mean and largest
 * magnitude with the share of texels consistent within 1 px; two lines ending in '\n'.
 */
std::string describeVideoFlow(const std::string& video, const VideoFlow& flow, int a, int b,
                              FlowMethod method);

/**
 * Fraction of texels whose forward–backward round trip closes: |f(p) + g(p + f(p))| ≤ `tolerancePx` (frame
 * pixels), g bilinear. Texels whose content leaves the frame count as inconsistent. `backward` is the flow
 * b → a of the same frames.
 */
double consistentFraction(const FlowField& forward, const FlowField& backward, double tolerancePx);

/**
 * The flow as a picture (RGBA8, frame-sized): hue = direction (right red, down yellow-green, left cyan, up
 * violet), saturation 1, value = |v| / maxMagnitude clamped to 1 (still is black). `maxMagnitude` ≤ 0 uses
 * the field's largest length.
 */
Image flowPicture(const FlowField& flow, double maxMagnitude = 0.0);

/** How a flow field becomes point anchors (suggestAnchors). */
struct FlowSuggestOptions {
  /** Where the video frame goes on the image (stretched independently in x and y). */
  enum class Mapping : std::uint8_t {
    Zone,  ///< onto the zone's bounding box: a filmed eye drives the eye zone
    Image, ///< onto the whole image: the video was filmed from the image's viewpoint
  };
  /** Where the video frame goes on the image. */
  Mapping mapping = Mapping::Zone;
  double spacingPx = 16.0;     ///< image pixels between grid samples inside the zone, > 0
  double minMagnitudePx = 0.5; ///< image pixels: final vectors shorter than this are dropped (still parts)
  double scale = 1.0;          ///< multiplies every vector after the mapping (exaggerate > 1, tone down < 1)
  int maxAnchors = 400;        ///< most pairs kept, 1..100000; more are thinned evenly in scan order
  /** Frame pixels: a sample whose window mean fails the forward–backward check by more is dropped. */
  double maxInconsistencyPx = 1.0;
  /** Frame pixels: a sample whose flow varies more (RMS about its window mean) is dropped (edges, noise). */
  double maxDeviationPx = 1.0;
};

/** What suggestAnchors did with its grid samples. */
struct FlowSuggestStats {
  std::size_t samples = 0;         ///< grid points inside the zone
  std::size_t irregular = 0;       ///< dropped: flow varies too much around them
  std::size_t inconsistent = 0;    ///< dropped: forward–backward check failed (or content left the frame)
  std::size_t still = 0;           ///< dropped: shorter than minMagnitudePx
  std::size_t thinned = 0;         ///< dropped to respect maxAnchors
  glm::dvec2 imagePerFramePx{0.0}; ///< the mapping's scale, image pixels per frame pixel in x and y
};

/**
 * Suggested point anchors for a zone of an image of `imageSize` pixels, from the forward flow between two
 * frames. Grid points a every `spacingPx` image pixels inside the zone's outline are mapped into the frame;
 * the flow there (the mean over a window about one grid cell wide, at most 17×17 texels) is checked for
 * regularity and, when `backward` (flow b → a) is given, for forward–backward consistency, then mapped back
 * to image pixels and multiplied by `scale`. Each pair is (a, b) with b = a + vector: the forward intent "a
 * moves to b" of PointsTool (anchor at b, backward vector a − b), coordinates rounded to 1/1000 pixel.
 * Deterministic. Throws sylva::Error for an empty flow, a backward flow of another size, a degenerate zone or
 * out-of-range options.
 */
std::vector<std::array<Vec2, 2>> suggestAnchors(const FlowField& forward, const Shape& zoneShape,
                                                glm::ivec2 imageSize, const FlowSuggestOptions& options,
                                                const FlowField* backward = nullptr,
                                                FlowSuggestStats* stats = nullptr);

/** A points tool holding `pairs`; throws sylva::Error when there are none or more than 100,000. */
PointsTool pointsToolFromSuggestions(const std::vector<std::array<Vec2, 2>>& pairs);

/**
 * Accepts a suggestion: appends pointsToolFromSuggestions(pairs) to zone `zone` as one undoable edit named
 * "motion from video". Throws sylva::Error (and changes nothing) for no pairs or no such zone.
 */
void applyFlowSuggestion(EditHistory& history, int zone, const std::vector<std::array<Vec2, 2>>& pairs);

/**
 * A clip with a known motion, for tests and demonstrations: a band-limited colour texture (a sum of seeded
 * sinusoids, wavelengths 6–48 px, so sub-pixel motion is exact) whose background moves by `translation`
 * every frame, and a disc of a second texture that rotates and scales about its centre every frame.
 */
struct SyntheticMotion {
  Vec2 translation{2.5, -1.25}; ///< forward motion of the background per frame, frame pixels
  Vec2 centre{0.0};             ///< centre of the disc, frame pixels
  double radius = 0.0;          ///< disc radius, frame pixels; 0: no disc
  double rotationRad = 0.0;     ///< disc rotation per frame, radians (positive turns +x towards +y)
  double scale = 1.0;           ///< disc magnification per frame, > 0
  /**
   * The exact forward flow at frame point p between any two consecutive frames, pixels: `translation`
   * outside the disc, S(p) − p inside (S the disc's similarity). Wrong within a pixel or two of the disc's
   * rim, where content appears and disappears.
   */
  Vec2 flowAt(Vec2 p) const;
};

/** `frames` frames (≥ 1) of `size` pixels (16..kMaxVideoSide) of `motion`, RGBA8, at `fps`. Deterministic. */
VideoClip syntheticVideo(glm::ivec2 size, int frames, const SyntheticMotion& motion, std::uint64_t seed = 1,
                         double fps = 25.0);

} // namespace sylva::folding

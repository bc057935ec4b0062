#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/scene/SceneFile.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

/**
 * Frame-sequence planning for `sylva render scene.json --frames A-B --shard i/n --out DIR` (docs/scenes.md):
 * frame N is a pure function of (scene, N), so a range splits over independent runs without coordination and
 * a killed run resumes by skipping frames already written. Frames are written to a temporary name and
 * renamed, so a frame_NNNNN.png that exists is always complete.
 */
namespace sylva::scene {

/** A set of frame numbers: sorted, non-overlapping inclusive intervals. */
struct FrameRange {
  std::vector<std::pair<int, int>> spans; ///< [first, last] pairs, sorted by first, disjoint
  /** Number of frames in all spans. */
  long long count() const;
  /** The frames in order. */
  std::vector<int> frames() const;
};

/** Shard `index` of `count` (0 ≤ index < count ≤ 4096). */
struct Shard {
  /** This shard, counted from 0. */
  int index = 0;
  /** How many shards the frames are split into. */
  int count = 1;
};

/**
 * Parses "--frames": "N", "A-B" or a comma-separated list of those ("0-9,20-29"), frame numbers in [0, 1e6).
 * Errors (sylva::Error, one line starting "--frames: "): malformed text, B < A, a range that overlaps another
 * ("--frames: 10-20 overlaps 0-15"), more than 1e6 frames in total.
 */
FrameRange parseFrames(std::string_view text);

/** Parses "--shard i/n"; errors start "--shard: " (malformed, n outside [1, 4096], i outside [0, n)). */
Shard parseShard(std::string_view text);

/**
 * The frames of `range` that `shard` renders: the k-th frame of the range (k counted from 0 over all spans in
 * order) belongs to shard k % n. The shards of any n partition the range: every frame exactly once.
 */
std::vector<int> framesOf(const FrameRange& range, const Shard& shard);

/** "frame_00042.png": the number zero-padded to at least five digits. Frame must be ≥ 0. */
std::string frameName(int frame);

/**
 * Whether `path` exists and decodes completely as a PNG of width × height pixels (any channel layout). A
 * missing, truncated, corrupt or differently sized file gives false; never throws for file content.
 */
bool frameComplete(const std::filesystem::path& path, int width, int height);

/**
 * Writes `image` as a PNG to "<path>.tmp-<pid>" and renames it onto `path`, so `path` never holds a partial
 * frame. Parent directories are created. Throws sylva::Error naming the file on failure (the temporary is
 * removed).
 */
void writeFrameAtomically(const std::filesystem::path& path, const Image& image);

/**
 * Removes temporaries left in `dir` by killed runs ("frame_*.png.tmp-<pid>" whose process is no longer
 * running, or any such file when `all`); returns how many were removed. A missing dir removes nothing.
 */
int removeStaleTemporaries(const std::filesystem::path& dir, bool all = false);

/**
 * Frames that fail on purpose: the numbers in $SYLVA_FAULT_FRAMES ("5" or "5,9"), empty when it is unset. A
 * test hook for the render farm (docs/farm.md): a task that reaches such a frame fails as a crashed render
 * would, after the frames before it are written. Throws sylva::Error "SYLVA_FAULT_FRAMES: ..." when
 * malformed.
 */
std::vector<int> faultFrames();

/** What `sylva render SCENE.json` is asked for (docs/scenes.md "Sequences"); empty fields take the file's. */
struct SequenceJob {
  std::string file;          ///< the scene file
  std::string frames;        ///< "A-B[,C-D...]"; empty: a still of the output's first frame
  std::string shard = "0/1"; ///< i/n
  std::string camera;        ///< empty: the file's output camera
  std::string out;           ///< a PNG (still) or a directory (sequence); empty: `out/<name>[.png]`
  std::string gif;           ///< also write the sequence as an animated GIF here
  std::string mp4;           ///< also encode the sequence as MP4 here (the ffmpeg program)
  int width = 0;             ///< 0: the file's output width, pixels
  int height = 0;            ///< 0: the file's output height, pixels
  bool overwrite = false;    ///< render complete frames again
};

/** A job checked against its scene file, with the frames still to draw. */
struct SequencePlan {
  /** The job as asked for. */
  SequenceJob job;
  SceneDesc desc; ///< the loaded scene
  int width = 0;  ///< output size, pixels
  /** Output height, pixels. */
  int height = 0;
  std::string camera;        ///< the camera drawn
  bool sequence = false;     ///< frames to a directory (else one still to a PNG)
  FrameRange range;          ///< the whole range (every shard's frames)
  std::filesystem::path out; ///< the still's PNG or the sequence's directory
  std::vector<int> frames;   ///< this shard's frames
  std::vector<int> todo;     ///< of those, the ones not complete yet (all with overwrite)
  /** Where frame `frame` is written. */
  std::filesystem::path framePath(int frame) const;
};

/**
 * Loads the scene and checks the job before anything is drawn (one-line sylva::Error naming the option or the
 * file and field): the camera exists, the range and shard parse, a shard needs a sequence, the outputs can be
 * written. A sequence's directory is created and temporaries of killed runs in it are removed. No GL.
 */
SequencePlan planSequence(const SequenceJob& job);

/**
 * After the frames are drawn: with --gif/--mp4 encodes the whole range when every frame of it is complete
 * (other shards may still be running: then a warning and nothing is written). Returns the files written.
 */
std::vector<std::string> finishSequence(const SequencePlan& plan);

} // namespace sylva::scene

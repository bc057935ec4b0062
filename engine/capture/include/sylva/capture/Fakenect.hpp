#pragma once
// libfreenect recordings ("fakenect" folders, written by `fakenect-record DIR`): an INDEX.txt listing frame
// files in order; depth frames `d-<walltime>-<timestamp>.pgm` with header `P5 640 480 65535\n` followed by
// raw little-endian 11-bit Kinect values (not PGM's big-endian), RGB frames `r-…ppm` (P6, 8-bit RGB) and
// accelerometer states `a-…dump`. Read directly here; the same folders replay through the real libfreenect
// API under the `fakenect` wrapper (Kinect.hpp).

#include <sylva/capture/Depth.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace sylva::capture {

/** One INDEX.txt line. */
struct FakenectEntry {
  /** 'd' depth, 'r' RGB, 'a' accelerometer. */
  char kind = 'd';
  /** Wall-clock seconds of the recording machine when the frame arrived. */
  double walltime = 0.0;
  /** The device's 32-bit frame timestamp. */
  std::uint32_t timestamp = 0;
  /** File name relative to the recording folder. */
  std::string file;
  /** 1-based line in INDEX.txt, for messages. */
  int line = 0;
};

/** A decoded raw depth frame: width × height Kinect 11-bit values, row 0 at the top. */
struct RawDepth {
  /** Pixels per row. */
  int width = 0;
  /** Rows. */
  int height = 0;
  /** The raw 11-bit values, row-major. */
  std::vector<std::uint16_t> raw;
};

/**
 * Parses the bytes of a fakenect depth PGM ("P5 <w> <h> 65535" header on one line, then w·h little-endian
 * uint16). `name` is used in messages. Throws sylva::Error "<name>: …" for a wrong magic, a header that is
 * not one line, a size other than what follows, or truncated data.
 */
RawDepth decodeFakenectDepth(std::span<const std::byte> bytes, const std::string& name);

/** Parses the bytes of a fakenect RGB PPM ("P6 <w> <h> 255" then w·h·3 bytes) into an RGB8 image. */
Image decodeFakenectRgb(std::span<const std::byte> bytes, const std::string& name);

/** Converts raw Kinect values to a DepthFrame in metres (kinectRawToMetres) with Kinect v1 intrinsics. */
DepthFrame depthFromKinectRaw(const RawDepth& raw);

/**
 * A fakenect recording opened for reading. open() parses INDEX.txt (a line that does not follow
 * `<kind>-<walltime>-<timestamp>…` is an error naming INDEX.txt and the line); entries whose files are
 * missing are kept out of the frame list and reported in warnings() (naming the file and the frame), so a
 * recording cut short by a crash still replays what it has.
 */
class FakenectRecording {
public:
  /** Throws sylva::Error naming the folder when it or its INDEX.txt is missing, or INDEX.txt is malformed. */
  static FakenectRecording open(const std::filesystem::path& folder);

  /** The recording's folder. */
  const std::filesystem::path& folder() const { return mFolder; }
  /** Every parsed entry whose file exists, in INDEX order. */
  const std::vector<FakenectEntry>& entries() const { return mEntries; }
  /** Number of depth frames. */
  std::size_t depthFrameCount() const { return mDepth.size(); }
  /** Missing files and other recoverable problems, one line each. */
  const std::vector<std::string>& warnings() const { return mWarnings; }

  /**
   * Depth frame i (0-based among depth frames) in metres, with the latest RGB frame at or before it in INDEX
   * order as `colour` when there is one (RGB frames that fail to decode are skipped with a warning).
   * timestamp is walltime relative to the first entry. Throws sylva::Error naming the file and the frame for
   * a truncated or corrupt depth file.
   */
  DepthFrame depthFrame(std::size_t i) const;
  /** Raw 11-bit values of depth frame i (what libfreenect hands to a depth callback). */
  RawDepth rawDepthFrame(std::size_t i) const;

private:
  std::filesystem::path mFolder;
  std::vector<FakenectEntry> mEntries;
  std::vector<std::size_t> mDepth; ///< indices into mEntries of depth entries
  std::vector<std::string> mWarnings;
};

/**
 * Writes a fakenect recording that `fakenect` and FakenectRecording both replay. Files are named like
 * fakenect-record's (`d-<walltime %.6f>-<timestamp>.pgm`, `r-…ppm`); the timestamp stands in for the device
 * clock: 0 for the first entry, then the previous one plus the milliseconds between their walltimes (at least
 * 1), so it strictly increases. Frames go into a temporary
 * sibling folder that is renamed to `folder` by finish(), so an interrupted write never leaves a partial
 * recording; an existing `folder` is replaced only then. Not thread-safe.
 */
class FakenectWriter {
public:
  /** Throws sylva::Error naming the folder if its parent cannot be created. */
  explicit FakenectWriter(std::filesystem::path folder);
  ~FakenectWriter();
  FakenectWriter(const FakenectWriter&) = delete;
  FakenectWriter& operator=(const FakenectWriter&) = delete;

  /**
   * Adds a depth frame at `walltime` seconds (must not decrease): depth in metres is quantised through
   * metresToKinectRaw. Frames must be 640×480 (libfreenect's only depth mode): other sizes throw
   * sylva::Error.
   */
  void addDepth(const DepthFrame& frame, double walltime);
  /** Adds a raw depth frame (640×480) at `walltime` seconds. */
  void addRawDepth(const RawDepth& raw, double walltime);
  /** Adds an RGB8 frame (640×480) at `walltime` seconds. */
  void addRgb(const Image& rgb, double walltime);
  /** Writes INDEX.txt and moves the recording into place. Throws sylva::Error naming the folder. */
  void finish();

private:
  std::filesystem::path mFolder;
  std::filesystem::path mTemp;
  std::vector<std::string> mIndex;
  double mLastWalltime = -1.0;
  std::uint32_t mTimestamp = 0;
  bool mFinished = false;
};

} // namespace sylva::capture

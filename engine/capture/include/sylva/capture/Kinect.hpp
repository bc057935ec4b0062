#pragma once
// Kinect v1 depth through the real libfreenect API: a live device, or a recording replayed by the `fakenect`
// wrapper (which sets FAKENECT_PATH and puts its fake libfreenect.so first on LD_LIBRARY_PATH, so this very
// code reads the recording).

#include <sylva/capture/Depth.hpp>

#include <functional>
#include <string>

namespace sylva::capture {

/** Options of a Kinect capture. */
struct KinectOptions {
  /** Device index (0: the first Kinect). */
  int device = 0;
  /**
   * Depth frames to deliver. 0 means: under fakenect replay, the recording's depth frame count (counted from
   * the FAKENECT_PATH recording's INDEX.txt, since fakenect itself loops or stops without saying how many);
   * live, 1.
   */
  int frames = 0;
  /** Also stream RGB and attach the latest RGB frame to each depth frame (unregistered on a real device). */
  bool colour = false;
  /** Seconds to wait for a frame before giving up with an error. */
  double timeoutSeconds = 5.0;
};

/** True when running under the fakenect wrapper (FAKENECT_PATH is set). */
bool kinectReplayActive();

/**
 * Number of Kinect v1 devices libfreenect sees (1 under fakenect). Throws sylva::Error when libfreenect
 * cannot start (no USB access).
 */
int kinectDeviceCount();

/**
 * Streams depth frames (11-bit mode, converted with kinectRawToMetres, Kinect v1 intrinsics, kind Kinect,
 * source "kinect" or "fakenect:<folder>") to `onFrame` until it returns false or options.frames are
 * delivered. Throws sylva::Error "no Kinect v1 found (libfreenect sees 0 devices): …" when none is attached,
 * and on timeouts. Under fakenect the recording is checked first (FakenectRecording::open; missing or short
 * depth files are errors, since fakenect would exit or read past them). Debian's fakenect 0.5.3 does not
 * loop: after the last INDEX.txt line freenect_process_events returns -1 (printing "Warning: No more lines in
 * [DIR]" on stdout), and the capture then ends cleanly with the frames delivered so far (an error if there
 * were none).
 */
void captureKinect(const KinectOptions& options, const std::function<bool(DepthFrame&& frame)>& onFrame);

} // namespace sylva::capture

#pragma once
// The pinhole camera a blade was captured with, as blade-model files record it (BladeSource::intrinsics) and
// the capture module's depth loaders produce it.

#include <glm/vec3.hpp>

namespace sylva::blades {

/**
 * Pinhole intrinsics in pixels: a pixel (u, v) (column, row from the top-left, pixel centres at integer + 0.5
 * are not used: (u, v) is the integer index) at depth z metres is the camera-space point
 * ((u − cx)·z/fx, (v − cy)·z/fy, z), x right, y down, z forward (OpenCV convention).
 */
struct CameraIntrinsics {
  double fx = 594.21; ///< focal length along x, pixels
  double fy = 591.04; ///< focal length along y, pixels
  double cx = 339.31; ///< principal point column, pixels
  double cy = 242.74; ///< principal point row, pixels
  /** Kinect v1 depth camera at 640×480 (Nicolas Burrus' calibration, the values libfreenect users quote). */
  static CameraIntrinsics kinectV1() { return {}; }
  /** Kinect v1 intrinsics scaled to a width × height image (same field of view). */
  static CameraIntrinsics kinectV1Scaled(int width, int height);
  /** Camera-space point (metres) of pixel (u, v) at depth z (metres). */
  glm::dvec3 unproject(double u, double v, double z) const {
    return {(u - cx) * z / fx, (v - cy) * z / fy, z};
  }
  /** Exact equality of all four values. */
  bool operator==(const CameraIntrinsics&) const = default;
};

} // namespace sylva::blades

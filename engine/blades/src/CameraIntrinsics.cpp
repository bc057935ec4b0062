#include <sylva/blades/CameraIntrinsics.hpp>

namespace sylva::blades {

CameraIntrinsics CameraIntrinsics::kinectV1Scaled(int width, int height) {
  const CameraIntrinsics base = kinectV1();
  const double sx = static_cast<double>(width) / 640.0;
  const double sy = static_cast<double>(height) / 480.0;
  return {base.fx * sx, base.fy * sy, base.cx * sx, base.cy * sy};
}

} // namespace sylva::blades

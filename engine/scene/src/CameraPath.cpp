#include <sylva/scene/CameraPath.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sylva::scene {

namespace {

using dvec3 = glm::dvec3;

/** Knot interval of centripetal Catmull-Rom: |b − a|^0.5. */
double knot(const dvec3& a, const dvec3& b) {
  return std::sqrt(glm::length(b - a));
}

/** Barry–Goldman pyramid for one segment p1 → p2 at u ∈ [0, 1], alpha 0.5, in double precision. */
dvec3 segment(dvec3 p0, const dvec3& p1, const dvec3& p2, dvec3 p3, double u) {
  constexpr double kTiny = 1e-9;
  const double d12 = knot(p1, p2);
  if (d12 < kTiny) {
    return p1; // the segment does not move
  }
  // A neighbour that coincides with its end point has no direction: reflect the other end instead.
  if (knot(p0, p1) < kTiny) {
    p0 = 2.0 * p1 - p2;
  }
  if (knot(p2, p3) < kTiny) {
    p3 = 2.0 * p2 - p1;
  }
  const double t0 = 0.0;
  const double t1 = t0 + knot(p0, p1);
  const double t2 = t1 + d12;
  const double t3 = t2 + knot(p2, p3);
  const double t = t1 + u * (t2 - t1);
  const dvec3 a1 = (t1 - t) / (t1 - t0) * p0 + (t - t0) / (t1 - t0) * p1;
  const dvec3 a2 = (t2 - t) / (t2 - t1) * p1 + (t - t1) / (t2 - t1) * p2;
  const dvec3 a3 = (t3 - t) / (t3 - t2) * p2 + (t - t2) / (t3 - t2) * p3;
  const dvec3 b1 = (t2 - t) / (t2 - t0) * a1 + (t - t0) / (t2 - t0) * a2;
  const dvec3 b2 = (t3 - t) / (t3 - t1) * a2 + (t - t1) / (t3 - t1) * a3;
  return (t2 - t) / (t2 - t1) * b1 + (t - t1) / (t2 - t1) * b2;
}

CameraSample sampleOf(const WorldCameraKey& k) {
  return {k.position, k.target, k.fov};
}

} // namespace

glm::vec3 centripetalCatmullRom(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                const glm::vec3& p3, float u) {
  return glm::vec3(segment(dvec3(p0), dvec3(p1), dvec3(p2), dvec3(p3), static_cast<double>(u)));
}

glm::vec3 resolvePoint(const Vec3Ground& p, const GroundHeight& ground) {
  if (!p.aboveGround) {
    return p.p;
  }
  if (!ground) {
    fail("camera: a point 'above_ground' needs the terrain height");
  }
  return {p.p.x, ground(p.p.x, p.p.z) + p.p.y, p.p.z};
}

std::vector<WorldCameraKey> resolveKeys(const CameraDesc& camera, const GroundHeight& ground) {
  std::vector<WorldCameraKey> keys;
  keys.reserve(camera.keys.size());
  for (const CameraKey& k : camera.keys) {
    keys.push_back({k.time, resolvePoint(k.position, ground), resolvePoint(k.target, ground), k.fov});
  }
  return keys;
}

CameraSample evaluate(const std::vector<WorldCameraKey>& keys, double time, bool loop) {
  if (keys.empty()) {
    fail("camera path: no keys");
  }
  for (std::size_t i = 1; i < keys.size(); ++i) {
    if (!(keys[i].time > keys[i - 1].time)) {
      fail("camera path: key {} time {} is not after key {} time {}", i, keys[i].time, i - 1,
           keys[i - 1].time);
    }
  }
  if (!std::isfinite(time)) {
    fail("camera path: time {} is not finite", time);
  }
  const std::size_t n = keys.size();
  if (n == 1) {
    return sampleOf(keys[0]);
  }
  const double first = keys.front().time;
  const double last = keys.back().time;
  if (loop) {
    const double period = last - first;
    time = first + std::fmod(time - first, period);
    if (time < first) {
      time += period;
    }
  } else {
    time = std::clamp(time, first, last);
  }
  // The segment [keys[i], keys[i + 1]] holding `time`; a time equal to a key returns that key exactly.
  const auto it = std::upper_bound(keys.begin(), keys.end(), time,
                                   [](double t, const WorldCameraKey& k) { return t < k.time; });
  std::size_t i = static_cast<std::size_t>(std::distance(keys.begin(), it));
  i = i == 0 ? 0 : i - 1;
  if (time == keys[i].time) {
    return sampleOf(keys[i]);
  }
  if (i + 1 >= n) {
    return sampleOf(keys[n - 1]);
  }
  // Neighbours: open paths reflect the end points (phantom keys); loops wrap, taking the last key as the
  // return to the first (the key before the first is the one before the last, and after the last the second).
  auto neighbour = [&](std::ptrdiff_t j) -> const WorldCameraKey* {
    if (j >= 0 && j < static_cast<std::ptrdiff_t>(n)) {
      return &keys[static_cast<std::size_t>(j)];
    }
    if (!loop || n < 3) {
      return nullptr;
    }
    return j < 0 ? &keys[n - 2] : &keys[1];
  };
  const WorldCameraKey& k1 = keys[i];
  const WorldCameraKey& k2 = keys[i + 1];
  const WorldCameraKey* k0 = neighbour(static_cast<std::ptrdiff_t>(i) - 1);
  const WorldCameraKey* k3 = neighbour(static_cast<std::ptrdiff_t>(i) + 2);
  const double u = (time - k1.time) / (k2.time - k1.time);
  auto curve = [&](auto get) {
    const dvec3 p1 = get(k1);
    const dvec3 p2 = get(k2);
    const dvec3 p0 = k0 ? get(*k0) : 2.0 * p1 - p2;
    const dvec3 p3 = k3 ? get(*k3) : 2.0 * p2 - p1;
    return segment(p0, p1, p2, p3, u);
  };
  CameraSample s;
  s.position = glm::vec3(curve([](const WorldCameraKey& k) { return dvec3(k.position); }));
  s.target = glm::vec3(curve([](const WorldCameraKey& k) { return dvec3(k.target); }));
  s.fov = static_cast<float>(curve([](const WorldCameraKey& k) { return dvec3(k.fov, 0.0, 0.0); }).x);
  s.fov = std::clamp(s.fov, 0.1f, 179.0f);
  return s;
}

double timelineEnd(const SceneDesc& desc) {
  double end = static_cast<double>(desc.output.lastFrame + 1) / desc.output.fps;
  for (const auto& [name, camera] : desc.cameras) {
    if (!camera.keys.empty()) {
      end = std::max(end, camera.keys.back().time);
    }
  }
  return end;
}

} // namespace sylva::scene

#include <sylva/grass/Simulation.hpp>

#include "SimulationSimd.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::grass {
namespace {

// Quaternions as vec4 (xyz, w), with the operations of shaders/grass/simulate.glsl, in the same order.
using Quat = glm::vec4;

[[gnu::always_inline]] inline glm::vec3 qrotate(const Quat& q, const glm::vec3& v) {
  const glm::vec3 u(q);
  return v + 2.0f * glm::cross(u, glm::cross(u, v) + q.w * v);
}

[[gnu::always_inline]] inline Quat qconj(const Quat& q) {
  return {-q.x, -q.y, -q.z, q.w};
}

[[gnu::always_inline]] inline Quat qmul(const Quat& a, const Quat& b) {
  const glm::vec3 av(a);
  const glm::vec3 bv(b);
  const glm::vec3 v = a.w * bv + b.w * av + glm::cross(av, bv);
  return {v, a.w * b.w - glm::dot(av, bv)};
}

/** The shortest rotation taking +X to the unit vector `to`. */
[[gnu::always_inline]] inline Quat fromX(const glm::vec3& to) {
  const float d = to.x;
  if (d < -0.99999f) {
    return {0.0f, 0.0f, 1.0f, 0.0f}; // half a turn about +Z
  }
  const Quat q(0.0f, -to.z, to.y, 1.0f + d); // cross((1,0,0), to) = (0, −to.z, to.y)
  return q / glm::length(q);
}

[[gnu::always_inline]] inline glm::vec3 safeNormalize(const glm::vec3& v) {
  const float l = glm::length(v);
  return l > 1e-12f ? v / l : glm::vec3(1.0f, 0.0f, 0.0f);
}

void stepBlade(glm::vec3* x, glm::vec3* xp, const glm::vec3* rest, float& trample,
               const std::vector<BladeCollider>& colliders, glm::vec2 wind, const GroundFunction& ground,
               const SolverConstants& c) {
  constexpr int n = kSimKnots;
  trample = std::max(0.0f, trample - c.recoveryStep);
  const float soft = 1.0f - c.softening * trample;
  // 1. Verlet with damping; the root edge is pinned to the rest pose.
  const float keep = c.keep;
  for (int i = 0; i < n; ++i) {
    if (i < 2) {
      x[i] = rest[i];
      xp[i] = rest[i];
      continue;
    }
    const glm::vec3 v = x[i] - xp[i];
    xp[i] = x[i];
    x[i] = x[i] + keep * v + glm::vec3(0.0f, -c.gravityStep, 0.0f);
  }
  // 2. Global shape, lower part of the blade.
  const float global = c.global * soft;
  for (int i = 2; i < n; ++i) {
    if (static_cast<float>(i) < c.globalKnots) {
      x[i] = x[i] + global * (rest[i] - x[i]);
    }
  }
  // 3. Local shape: each edge's rest direction expressed in the previous edge's frame, frames propagated from
  // the (pinned) root edge along the current blade.
  const float share = c.localShare * soft;
  glm::vec3 restLocal[n];
  {
    Quat frame = fromX(safeNormalize(rest[1] - rest[0]));
    for (int k = 1; k < n - 1; ++k) {
      restLocal[k] = qrotate(qconj(frame), rest[k + 1] - rest[k]);
      frame = qmul(frame, fromX(safeNormalize(restLocal[k])));
    }
  }
  // The K passes are made per edge, root to tip: each edge's constraint is applied K times with s' before the
  // next edge, so its correction compounds to exactly s whatever K, and the blade's apparent stiffness does
  // not depend on the iteration count (whole sweeps repeated K times make a chain softer as K grows).
  Quat frame = fromX(safeNormalize(x[1] - x[0]));
  for (int k = 1; k < n - 1; ++k) {
    for (int pass = 0; pass < c.localPasses; ++pass) {
      const glm::vec3 goal = x[k] + qrotate(frame, restLocal[k]);
      const glm::vec3 delta = share * (goal - x[k + 1]);
      if (k >= 2) {
        x[k] = x[k] - delta;
      }
      x[k + 1] = x[k + 1] + delta;
    }
    frame = qmul(frame, fromX(safeNormalize(qrotate(qconj(frame), x[k + 1] - x[k]))));
  }
  // 4. Wind across each segment.
  if (c.windDrag > 0.0f) {
    const glm::vec3 w(wind.x, 0.0f, wind.y);
    for (int i = 2; i < n; ++i) {
      const glm::vec3 e = x[i] - x[i - 1];
      const float ee = std::max(glm::dot(e, e), 1e-12f);
      const glm::vec3 across = w - e * (glm::dot(w, e) / ee);
      x[i] = x[i] + c.windDrag * glm::length(across) * across * (c.dt * c.dt);
    }
  }
  // 5. Edge lengths, even edges then odd; an edge at the pinned root moves only its upper knot.
  for (int pass = 0; pass < c.lengthPasses; ++pass) {
    for (int parity = 0; parity < 2; ++parity) {
      for (int j = parity; j < n - 1; j += 2) {
        if (j == 0) {
          continue; // both ends pinned
        }
        const float rest_ = glm::length(rest[j + 1] - rest[j]);
        const glm::vec3 d = x[j + 1] - x[j];
        const glm::vec3 delta = (1.0f - rest_ / std::max(glm::length(d), 1e-7f)) * d;
        if (j == 1) {
          x[j + 1] = x[j + 1] - delta;
        } else {
          x[j] = x[j] + 0.5f * delta;
          x[j + 1] = x[j + 1] - 0.5f * delta;
        }
      }
    }
  }
  // 6. Collision, hard and last: bodies, then the ground. Positions are pushed out exactly; the contact is
  // inelastic (the previous position follows) in proportion to the penetration, fully from kContactDepth on,
  // so a grazing contact changes the motion by a grazing amount: the step stays a continuous function of its
  // inputs and the CPU and GPU solvers, a few ulps apart, do not drift apart through contacts that one sees
  // and the other not.
  for (const BladeCollider& body : colliders) {
    const glm::vec3 axis = body.b - body.a;
    const float aa = glm::dot(axis, axis);
    for (int i = 2; i < n; ++i) {
      const float t = aa > 1e-12f ? std::clamp(glm::dot(x[i] - body.a, axis) / aa, 0.0f, 1.0f) : 0.0f;
      const glm::vec3 p = body.a + t * axis;
      const glm::vec3 out = x[i] - p;
      const float dist = glm::length(out);
      if (dist >= body.radius) {
        continue;
      }
      const float contact = std::min((body.radius - dist) / kContactDepth, 1.0f);
      x[i] = p + (dist > 1e-9f ? out / dist : glm::vec3(0.0f, 1.0f, 0.0f)) * body.radius;
      // Keep 0.4 of the motion along a capsule's axis (sliding along it), none across.
      const glm::vec3 along = aa > 1e-12f ? axis * (glm::dot(x[i] - xp[i], axis) / aa) : glm::vec3(0.0f);
      xp[i] = xp[i] + contact * (x[i] - 0.4f * along - xp[i]);
      if (body.mass >= c.trampleMass) {
        trample = std::max(trample, contact);
      }
    }
  }
  if (ground) {
    for (int i = 2; i < n; ++i) {
      const float g = ground(x[i].x, x[i].z);
      if (!std::isnan(g) && x[i].y < g) {
        const float contact = std::min((g - x[i].y) / kContactDepth, 1.0f);
        x[i].y = g;
        xp[i] = xp[i] + contact * (x[i] - xp[i]);
      }
    }
  }
  // 7. Velocity clamp.
  const float maxStep = c.maxStep;
  for (int i = 2; i < n; ++i) {
    const glm::vec3 v = x[i] - xp[i];
    const float speed = glm::length(v);
    if (speed > maxStep) {
      xp[i] = x[i] - v * (maxStep / speed);
    }
  }
}

} // namespace

SolverConstants solverConstants(const SolverSettings& s) {
  SolverConstants c;
  c.dt = s.step();
  c.keep = std::exp(-s.damping * c.dt * 60.0f);
  c.gravityStep = s.gravity * c.dt * c.dt;
  c.maxStep = s.maxSpeed * c.dt;
  c.global = s.globalStiffness;
  c.globalKnots = s.globalRange * static_cast<float>(kSimKnots);
  const float local = s.correctStiffness
                          ? 1.0f - std::pow(1.0f - std::min(s.localStiffness, 0.999999f),
                                            1.0f / static_cast<float>(std::max(s.localIterations, 1)))
                          : s.localStiffness;
  c.localShare = 0.5f * std::min(local, 0.95f);
  c.windDrag = s.windDrag;
  c.trampleMass = s.trampleMass;
  c.softening = s.trampleSoftening;
  c.recoveryStep = c.dt / s.trampleRecovery;
  c.localPasses = s.localIterations;
  c.lengthPasses = s.lengthIterations;
  c.kernel = s.kernel;
  return c;
}

void SolverSettings::validate() const {
  const std::pair<float, const char*> values[] = {{rate, "rate"},
                                                  {damping, "damping"},
                                                  {globalStiffness, "globalStiffness"},
                                                  {globalRange, "globalRange"},
                                                  {localStiffness, "localStiffness"},
                                                  {gravity, "gravity"},
                                                  {windDrag, "windDrag"},
                                                  {maxSpeed, "maxSpeed"},
                                                  {trampleMass, "trampleMass"},
                                                  {trampleSoftening, "trampleSoftening"},
                                                  {trampleRecovery, "trampleRecovery"}};
  for (const auto& [v, name] : values) {
    if (!std::isfinite(v) || v < 0.0f) {
      fail("grass simulation: {} must be a finite number ≥ 0, got {}", name, v);
    }
  }
  if (rate < 1.0f || rate > 10000.0f) {
    fail("grass simulation: rate must be in 1..10000 steps per second, got {}", rate);
  }
  if (globalStiffness > 1.0f || localStiffness > 1.0f || globalRange > 1.0f || trampleSoftening > 1.0f) {
    fail("grass simulation: stiffness, globalRange and trampleSoftening must be in 0..1");
  }
  if (localIterations < 1 || localIterations > 64 || lengthIterations < 1 || lengthIterations > 64) {
    fail("grass simulation: localIterations and lengthIterations must be in 1..64, got {} and {}",
         localIterations, lengthIterations);
  }
  if (!(trampleRecovery > 0.0f) || !(maxSpeed > 0.0f)) {
    fail("grass simulation: trampleRecovery and maxSpeed must be > 0");
  }
}

void SimBlades::add(const std::vector<glm::vec3>& pose) {
  if (pose.size() != static_cast<std::size_t>(kSimKnots)) {
    fail("grass simulation: a blade needs {} knots, got {}", kSimKnots, pose.size());
  }
  position.insert(position.end(), pose.begin(), pose.end());
  previous.insert(previous.end(), pose.begin(), pose.end());
  rest.insert(rest.end(), pose.begin(), pose.end());
  trample.push_back(0.0f);
}

void simulateBlade(SimBlades& blades, std::size_t blade, const std::vector<BladeCollider>& colliders,
                   glm::vec2 wind, const GroundFunction& ground, const SolverConstants& constants) {
  const std::size_t k = blade * kSimKnots;
  stepBlade(&blades.position[k], &blades.previous[k], &blades.rest[k], blades.trample[blade], colliders, wind,
            ground, constants);
}

void simulateBlades(SimBlades& blades, std::span<const std::uint32_t> indices,
                    std::span<const glm::vec2> wind, const std::vector<BladeCollider>& colliders,
                    const GroundFunction& ground, const SolverConstants& constants,
                    const GroundShortcuts& shortcuts) {
  if (wind.size() != indices.size()) {
    fail("grass simulation: {} wind velocities for {} blades", wind.size(), indices.size());
  }
  if (constants.kernel == SolverKernel::Simd) {
    stepBladesSimd(blades, indices.data(), wind.data(), indices.size(), colliders, ground, constants,
                   shortcuts);
    return;
  }
  for (std::size_t i = 0; i < indices.size(); ++i) {
    simulateBlade(blades, indices[i], colliders, wind[i], ground, constants);
  }
}

void simulateStep(SimBlades& blades, std::size_t first, std::size_t count,
                  const std::vector<BladeCollider>& colliders, const std::vector<glm::vec2>& wind,
                  const GroundFunction& ground, const SolverSettings& settings) {
  if (first + count > blades.count() || first + count > std::numeric_limits<std::uint32_t>::max()) {
    fail("grass simulation: blades {}..{} outside the {} blades", first, first + count, blades.count());
  }
  const SolverConstants constants = solverConstants(settings);
  parallelFor(
      count,
      [&](std::size_t begin, std::size_t end) {
        std::vector<std::uint32_t> indices(end - begin);
        std::vector<glm::vec2> velocities(end - begin);
        for (std::size_t b = first + begin; b < first + end; ++b) {
          indices[b - first - begin] = static_cast<std::uint32_t>(b);
          velocities[b - first - begin] = b < wind.size() ? wind[b] : glm::vec2(0.0f);
        }
        simulateBlades(blades, indices, velocities, colliders, ground, constants);
      },
      16);
}

void simulateStep(SimBlades& blades, const std::vector<BladeCollider>& colliders,
                  const std::vector<glm::vec2>& wind, const GroundFunction& ground,
                  const SolverSettings& settings) {
  simulateStep(blades, 0, blades.count(), colliders, wind, ground, settings);
}

} // namespace sylva::grass

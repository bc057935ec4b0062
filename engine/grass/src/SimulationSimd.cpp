// The grass constraint solver on SIMD lanes: stepBlade of Simulation.cpp (the scalar reference, which the
// compute shader mirrors) for up to sixteen blades at once, one blade per lane, with the same operations in
// the same order, so every lane's result is bit-identical to the reference
// (tests/unit/grass/SimulationTest.cpp, "SimdLanesMatchTheScalarReference"). Both files compile without
// floating-point contraction (no fused multiply-add), and IEEE add, multiply, divide and square root round
// the same on lanes as on scalars. Highway compiles the kernel once per instruction set (SSE4, AVX2, AVX-512,
// NEON, ...) and picks the best the machine has at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "SimulationSimd.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep

#include <hwy/highway.h>

#include "SimulationSimd.hpp"

#include <sylva/core/Error.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <math.h>
#include <cstddef>
#include <limits>

HWY_BEFORE_NAMESPACE();
namespace sylva::grass::HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using D = hn::CappedTag<float, kMaxSimdLanes>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

constexpr int n = kSimKnots;
constexpr std::size_t kLanes = kMaxSimdLanes;

/** A vec3 with one blade per lane. */
struct V3 {
  V x, y, z;
};
/** A quaternion (xyz, w) with one blade per lane. */
struct Q4 {
  V x, y, z, w;
};

HWY_INLINE V3 add(const V3& a, const V3& b) {
  return {hn::Add(a.x, b.x), hn::Add(a.y, b.y), hn::Add(a.z, b.z)};
}
HWY_INLINE V3 sub(const V3& a, const V3& b) {
  return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)};
}
HWY_INLINE V3 scale(V s, const V3& v) {
  return {hn::Mul(s, v.x), hn::Mul(s, v.y), hn::Mul(s, v.z)};
}
HWY_INLINE V3 divide(const V3& v, V s) {
  return {hn::Div(v.x, s), hn::Div(v.y, s), hn::Div(v.z, s)};
}
/** glm::dot of vec3: (x·x' + y·y') + z·z'. */
HWY_INLINE V dot(const V3& a, const V3& b) {
  return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z));
}
HWY_INLINE V length(const V3& v) {
  return hn::Sqrt(dot(v, v));
}
/** glm::cross. */
HWY_INLINE V3 cross(const V3& a, const V3& b) {
  return {hn::Sub(hn::Mul(a.y, b.z), hn::Mul(b.y, a.z)), hn::Sub(hn::Mul(a.z, b.x), hn::Mul(b.z, a.x)),
          hn::Sub(hn::Mul(a.x, b.y), hn::Mul(b.x, a.y))};
}
HWY_INLINE V3 select(M m, const V3& yes, const V3& no) {
  return {hn::IfThenElse(m, yes.x, no.x), hn::IfThenElse(m, yes.y, no.y), hn::IfThenElse(m, yes.z, no.z)};
}
HWY_INLINE V3 splat(const D d, const glm::vec3& v) {
  return {hn::Set(d, v.x), hn::Set(d, v.y), hn::Set(d, v.z)};
}

// Quaternions: qrotate, qconj, qmul and fromX of Simulation.cpp.
HWY_INLINE V3 qrotate(const Q4& q, const V3& v) {
  const V3 u{q.x, q.y, q.z};
  const V two = hn::Set(D(), 2.0f);
  return add(v, scale(two, cross(u, add(cross(u, v), scale(q.w, v)))));
}
HWY_INLINE Q4 qconj(const Q4& q) {
  return {hn::Neg(q.x), hn::Neg(q.y), hn::Neg(q.z), q.w};
}
HWY_INLINE Q4 qmul(const Q4& a, const Q4& b) {
  const V3 av{a.x, a.y, a.z};
  const V3 bv{b.x, b.y, b.z};
  const V3 v = add(add(scale(a.w, bv), scale(b.w, av)), cross(av, bv));
  return {v.x, v.y, v.z, hn::Sub(hn::Mul(a.w, b.w), dot(av, bv))};
}
HWY_INLINE Q4 fromX(const V3& to) {
  const D d;
  const V x = hn::Zero(d);
  const V y = hn::Neg(to.z);
  const V z = to.y;
  const V w = hn::Add(hn::Set(d, 1.0f), to.x);
  // glm::length of vec4: (x·x + y·y) + (z·z + w·w).
  const V l = hn::Sqrt(hn::Add(hn::Add(hn::Mul(x, x), hn::Mul(y, y)), hn::Add(hn::Mul(z, z), hn::Mul(w, w))));
  const M halfTurn = hn::Lt(to.x, hn::Set(d, -0.99999f));
  // x / l with x = 0: +0 for l > 0 (l ≥ 0 as a square root), NaN for l = 0 or NaN, without a division.
  const V zeroOverL = hn::IfThenElse(hn::Gt(l, hn::Zero(d)), hn::Zero(d), hn::NaN(d));
  return {hn::IfThenElse(halfTurn, hn::Zero(d), zeroOverL),
          hn::IfThenElse(halfTurn, hn::Zero(d), hn::Div(y, l)),
          hn::IfThenElse(halfTurn, hn::Set(d, 1.0f), hn::Div(z, l)),
          hn::IfThenElse(halfTurn, hn::Zero(d), hn::Div(w, l))};
}
HWY_INLINE V3 safeNormalize(const V3& v) {
  const D d;
  const V l = length(v);
  const M ok = hn::Gt(l, hn::Set(d, 1e-12f));
  return select(ok, divide(v, l), V3{hn::Set(d, 1.0f), hn::Zero(d), hn::Zero(d)});
}

/**
 * rootHeight (Field.cpp) of the grid at world (x, z) on every lane, with the same operations: clamped to the
 * samples, bilinear between the four around; NaN where one of them is a hole. x and z must not be NaN.
 */
HWY_INLINE V gridHeight(const terrain::HeightField& grid, V x, V z) {
  const D d;
  const hn::RebindToSigned<D> di;
  const int w = grid.width();
  const int h = grid.height();
  const V gx = hn::Min(hn::Max(hn::Div(x, hn::Set(d, grid.spacingX())), hn::Zero(d)),
                       hn::Set(d, static_cast<float>(w - 1)));
  const V gz = hn::Min(hn::Max(hn::Div(z, hn::Set(d, grid.spacingZ())), hn::Zero(d)),
                       hn::Set(d, static_cast<float>(h - 1)));
  const auto i0 = hn::Min(hn::ConvertTo(di, hn::Floor(gx)), hn::Set(di, w - 2));
  const auto j0 = hn::Min(hn::ConvertTo(di, hn::Floor(gz)), hn::Set(di, h - 2));
  const auto at = hn::Add(hn::Mul(j0, hn::Set(di, w)), i0);
  const float* samples = grid.samples().data();
  const V h00 = hn::GatherIndex(d, samples, at);
  const V h10 = hn::GatherIndex(d, samples + 1, at);
  const V h01 = hn::GatherIndex(d, samples + w, at);
  const V h11 = hn::GatherIndex(d, samples + w + 1, at);
  const V fx = hn::Sub(gx, hn::ConvertTo(d, i0));
  const V fz = hn::Sub(gz, hn::ConvertTo(d, j0));
  const V one = hn::Set(d, 1.0f);
  const V top = hn::Add(hn::Mul(h00, hn::Sub(one, fx)), hn::Mul(h10, fx));
  const V bottom = hn::Add(hn::Mul(h01, hn::Sub(one, fx)), hn::Mul(h11, fx));
  return hn::Add(hn::Mul(top, hn::Sub(one, fz)), hn::Mul(bottom, fz));
}

/** Knots of a group's blades, lane-major within each coordinate: v[knot][axis][lane]. */
struct alignas(64) GroupKnots {
  float v[n][3][kLanes];
};

void gather(const std::vector<glm::vec3>& from, const std::uint32_t* blades, std::size_t lanes,
            GroupKnots& to) {
  for (std::size_t l = 0; l < kLanes; ++l) {
    // Lanes past the group's blades repeat its first blade; their results are not written back.
    const std::size_t base = static_cast<std::size_t>(blades[l < lanes ? l : 0]) * n;
    for (int i = 0; i < n; ++i) {
      const glm::vec3& p = from[base + static_cast<std::size_t>(i)];
      to.v[i][0][l] = p.x;
      to.v[i][1][l] = p.y;
      to.v[i][2][l] = p.z;
    }
  }
}

void scatter(const GroupKnots& from, const std::uint32_t* blades, std::size_t lanes,
             std::vector<glm::vec3>& to) {
  for (std::size_t l = 0; l < lanes; ++l) {
    const std::size_t base = static_cast<std::size_t>(blades[l]) * n;
    for (int i = 0; i < n; ++i) {
      to[base + static_cast<std::size_t>(i)] = {from.v[i][0][l], from.v[i][1][l], from.v[i][2][l]};
    }
  }
}

/** stepBlade of Simulation.cpp for the blades of one group (at most kLanes). */
void stepGroup(SimBlades& blades, const std::uint32_t* indices, const glm::vec2* wind, std::size_t lanes,
               const std::vector<BladeCollider>& colliders, const GroundFunction& ground,
               const SolverConstants& c, const GroundShortcuts& shortcuts) {
  const D d;
  const std::size_t width = hn::Lanes(d);
  GroupKnots x;
  GroupKnots xp;
  GroupKnots rest;
  gather(blades.position, indices, lanes, x);
  gather(blades.previous, indices, lanes, xp);
  gather(blades.rest, indices, lanes, rest);
  alignas(64) float laneTrample[kLanes];
  alignas(64) float windX[kLanes];
  alignas(64) float windZ[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) {
    const std::size_t from = l < lanes ? l : 0;
    laneTrample[l] = blades.trample[indices[from]];
    windX[l] = wind[from].x;
    windZ[l] = wind[from].y;
  }
  // The kernel runs over the group in chunks of the vector width (16 lanes on AVX-512, 8 on AVX2, 4 on SSE4
  // and NEON).
  for (std::size_t lane0 = 0; lane0 < kLanes && lane0 < lanes; lane0 += width) {
    const auto at = [&](const GroupKnots& g, int i) {
      return V3{hn::Load(d, g.v[i][0] + lane0), hn::Load(d, g.v[i][1] + lane0),
                hn::Load(d, g.v[i][2] + lane0)};
    };
    const auto put = [&](GroupKnots& g, int i, const V3& p) {
      hn::Store(p.x, d, g.v[i][0] + lane0);
      hn::Store(p.y, d, g.v[i][1] + lane0);
      hn::Store(p.z, d, g.v[i][2] + lane0);
    };
    V3 X[n];
    V3 XP[n];
    V3 R[n];
    for (int i = 0; i < n; ++i) {
      X[i] = at(x, i);
      XP[i] = at(xp, i);
      R[i] = at(rest, i);
    }
    V trample = hn::Max(hn::Zero(d), hn::Sub(hn::Load(d, laneTrample + lane0), hn::Set(d, c.recoveryStep)));
    const V soft = hn::Sub(hn::Set(d, 1.0f), hn::Mul(hn::Set(d, c.softening), trample));
    // 1. Verlet with damping; the root edge is pinned to the rest pose.
    const V keep = hn::Set(d, c.keep);
    const V3 gravity{hn::Zero(d), hn::Set(d, -c.gravityStep), hn::Zero(d)};
    for (int i = 0; i < n; ++i) {
      if (i < 2) {
        X[i] = R[i];
        XP[i] = R[i];
        continue;
      }
      const V3 v = sub(X[i], XP[i]);
      XP[i] = X[i];
      X[i] = add(add(X[i], scale(keep, v)), gravity);
    }
    // 2. Global shape, lower part of the blade.
    const V global = hn::Mul(hn::Set(d, c.global), soft);
    for (int i = 2; i < n; ++i) {
      if (static_cast<float>(i) < c.globalKnots) {
        X[i] = add(X[i], scale(global, sub(R[i], X[i])));
      }
    }
    // 3. Local shape.
    const V share = hn::Mul(hn::Set(d, c.localShare), soft);
    V3 restLocal[n];
    {
      Q4 frame = fromX(safeNormalize(sub(R[1], R[0])));
      for (int k = 1; k < n - 1; ++k) {
        restLocal[k] = qrotate(qconj(frame), sub(R[k + 1], R[k]));
        frame = qmul(frame, fromX(safeNormalize(restLocal[k])));
      }
    }
    Q4 frame = fromX(safeNormalize(sub(X[1], X[0])));
    for (int k = 1; k < n - 1; ++k) {
      for (int pass = 0; pass < c.localPasses; ++pass) {
        const V3 goal = add(X[k], qrotate(frame, restLocal[k]));
        const V3 delta = scale(share, sub(goal, X[k + 1]));
        if (k >= 2) {
          X[k] = sub(X[k], delta);
        }
        X[k + 1] = add(X[k + 1], delta);
      }
      frame = qmul(frame, fromX(safeNormalize(qrotate(qconj(frame), sub(X[k + 1], X[k])))));
    }
    // 4. Wind across each segment.
    if (c.windDrag > 0.0f) {
      const V3 w{hn::Load(d, windX + lane0), hn::Zero(d), hn::Load(d, windZ + lane0)};
      const V drag = hn::Set(d, c.windDrag);
      const V dt2 = hn::Set(d, c.dt * c.dt);
      for (int i = 2; i < n; ++i) {
        const V3 e = sub(X[i], X[i - 1]);
        const V ee = hn::Max(dot(e, e), hn::Set(d, 1e-12f));
        const V3 across = sub(w, scale(hn::Div(dot(w, e), ee), e));
        const V3 push = scale(dt2, scale(hn::Mul(drag, length(across)), across));
        X[i] = add(X[i], push);
      }
    }
    // 5. Edge lengths, even edges then odd; an edge at the pinned root moves only its upper knot.
    const V half = hn::Set(d, 0.5f);
    for (int pass = 0; pass < c.lengthPasses; ++pass) {
      for (int parity = 0; parity < 2; ++parity) {
        for (int j = parity; j < n - 1; j += 2) {
          if (j == 0) {
            continue;
          }
          const V restLength = length(sub(R[j + 1], R[j]));
          const V3 dj = sub(X[j + 1], X[j]);
          const V3 delta = scale(
              hn::Sub(hn::Set(d, 1.0f), hn::Div(restLength, hn::Max(length(dj), hn::Set(d, 1e-7f)))), dj);
          if (j == 1) {
            X[j + 1] = sub(X[j + 1], delta);
          } else {
            X[j] = add(X[j], scale(half, delta));
            X[j + 1] = sub(X[j + 1], scale(half, delta));
          }
        }
      }
    }
    // 6. Collision: bodies, then the ground.
    const V contactDepth = hn::Set(d, kContactDepth);
    const V one = hn::Set(d, 1.0f);
    for (const BladeCollider& body : colliders) {
      const glm::vec3 axisS = body.b - body.a;
      const float aaS = glm::dot(axisS, axisS);
      const V3 a = splat(d, body.a);
      const V3 axis = splat(d, axisS);
      const V aa = hn::Set(d, aaS);
      const V radius = hn::Set(d, body.radius);
      const bool tramples = body.mass >= c.trampleMass;
      for (int i = 2; i < n; ++i) {
        const V t = aaS > 1e-12f ? hn::Min(hn::Max(hn::Div(dot(sub(X[i], a), axis), aa), hn::Zero(d)), one)
                                 : hn::Zero(d);
        const V3 p = add(a, scale(t, axis));
        const V3 out = sub(X[i], p);
        const V dist = length(out);
        const M hit = hn::Lt(dist, radius);
        if (hn::AllFalse(d, hit)) {
          continue;
        }
        const V contact = hn::Min(hn::Div(hn::Sub(radius, dist), contactDepth), one);
        const V3 dir = select(hn::Gt(dist, hn::Set(d, 1e-9f)), divide(out, dist),
                              V3{hn::Zero(d), hn::Set(d, 1.0f), hn::Zero(d)});
        const V3 moved = add(p, scale(radius, dir));
        const V3 along = aaS > 1e-12f ? scale(hn::Div(dot(sub(moved, XP[i]), axis), aa), axis)
                                      : V3{hn::Zero(d), hn::Zero(d), hn::Zero(d)};
        const V3 follow = add(XP[i], scale(contact, sub(sub(moved, scale(hn::Set(d, 0.4f), along)), XP[i])));
        X[i] = select(hit, moved, X[i]);
        XP[i] = select(hit, follow, XP[i]);
        if (tramples) {
          trample = hn::IfThenElse(hit, hn::Max(trample, contact), trample);
        }
      }
    }
    if (ground) {
      // Knots inside the bound and above its ceiling cannot be below the ground: no lookup (NaN: none).
      const V ceiling = hn::Set(d, shortcuts.ceiling);
      const V lox = hn::Set(d, shortcuts.lo.x);
      const V loz = hn::Set(d, shortcuts.lo.y);
      const V hix = hn::Set(d, shortcuts.hi.x);
      const V hiz = hn::Set(d, shortcuts.hi.y);
      alignas(64) float gx[kLanes];
      alignas(64) float gz[kLanes];
      alignas(64) float gy[kLanes];
      alignas(64) float look[kLanes];
      for (int i = 2; i < n; ++i) {
        const M inside = hn::And(hn::And(hn::Ge(X[i].x, lox), hn::Le(X[i].x, hix)),
                                 hn::And(hn::Ge(X[i].z, loz), hn::Le(X[i].z, hiz)));
        const M lookup = hn::Not(hn::And(inside, hn::Ge(X[i].y, ceiling)));
        if (hn::AllFalse(d, lookup)) {
          continue;
        }
        V g;
        const M unplaced = hn::Or(hn::IsNaN(X[i].x), hn::IsNaN(X[i].z));
        if (shortcuts.grid != nullptr && hn::AllFalse(d, unplaced)) {
          g = hn::IfThenElse(lookup, gridHeight(*shortcuts.grid, X[i].x, X[i].z), hn::NaN(d));
        } else {
          hn::Store(X[i].x, d, gx);
          hn::Store(X[i].z, d, gz);
          hn::Store(hn::IfThenElseZero(lookup, one), d, look);
          for (std::size_t l = 0; l < width; ++l) {
            gy[l] = look[l] != 0.0f ? ground(gx[l], gz[l]) : std::numeric_limits<float>::quiet_NaN();
          }
          g = hn::Load(d, gy);
        }
        const M below = hn::And(hn::Not(hn::IsNaN(g)), hn::Lt(X[i].y, g));
        if (hn::AllFalse(d, below)) {
          continue;
        }
        const V contact = hn::Min(hn::Div(hn::Sub(g, X[i].y), contactDepth), one);
        const V3 lifted{X[i].x, g, X[i].z};
        X[i] = select(below, lifted, X[i]);
        XP[i] = select(below, add(XP[i], scale(contact, sub(lifted, XP[i]))), XP[i]);
      }
    }
    // 7. Velocity clamp.
    const V maxStep = hn::Set(d, c.maxStep);
    for (int i = 2; i < n; ++i) {
      const V3 v = sub(X[i], XP[i]);
      const V speed = length(v);
      const M fast = hn::Gt(speed, maxStep);
      XP[i] = select(fast, sub(X[i], scale(hn::Div(maxStep, speed), v)), XP[i]);
    }
    for (int i = 0; i < n; ++i) {
      put(x, i, X[i]);
      put(xp, i, XP[i]);
    }
    hn::Store(trample, d, laneTrample + lane0);
  }
  scatter(x, indices, lanes, blades.position);
  scatter(xp, indices, lanes, blades.previous);
  for (std::size_t l = 0; l < lanes; ++l) {
    blades.trample[indices[l]] = laneTrample[l];
  }
}

/** restPosesSimd for one group of at most kLanes blades. */
void restGroup(std::span<const RestShape> shapes, const RestInput* inputs, std::size_t lanes,
               SimBlades& blades) {
  const D d;
  const std::size_t width = hn::Lanes(d);
  GroupKnots centres;
  GroupKnots segments;
  alignas(64) float u[n][kLanes];
  alignas(64) float rotation[kLanes];
  alignas(64) float scaleOf[kLanes];
  alignas(64) float stiffness[kLanes];
  alignas(64) float root[3][kLanes];
  alignas(64) float wind[2][kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) {
    const RestInput& in = inputs[l < lanes ? l : 0];
    const RestShape& shape = shapes[in.type];
    for (int k = 0; k < n; ++k) {
      segments.v[k][0][l] = shape.segment[static_cast<std::size_t>(k)].x;
      segments.v[k][1][l] = shape.segment[static_cast<std::size_t>(k)].y;
      segments.v[k][2][l] = shape.segment[static_cast<std::size_t>(k)].z;
      u[k][l] = shape.u[static_cast<std::size_t>(k)];
    }
    rotation[l] = in.rotation;
    scaleOf[l] = in.scale;
    stiffness[l] = shape.stiffness;
    root[0][l] = in.root.x;
    root[1][l] = in.root.y;
    root[2][l] = in.root.z;
    wind[0][l] = in.wind.x;
    wind[1][l] = in.wind.y;
  }
  for (std::size_t lane0 = 0; lane0 < kLanes && lane0 < lanes; lane0 += width) {
    // Sines and cosines from the C library, lane by lane, exactly as the scalar walk takes them: the rest
    // pose is then bit for bit bladeCentreLine's (Highway's own Sin and Cos are 3 ulp off, which contacts
    // amplify to 0.1 mm within a second).
    alignas(64) float laneCos[kLanes];
    alignas(64) float laneSin[kLanes];
    for (std::size_t l = 0; l < width; ++l) {
      laneCos[l] = std::cos(rotation[lane0 + l]);
      laneSin[l] = std::sin(rotation[lane0 + l]);
    }
    const V c = hn::Load(d, laneCos);
    const V s = hn::Load(d, laneSin);
    const V bladeScale = hn::Load(d, scaleOf + lane0);
    const V wx = hn::Load(d, wind[0] + lane0);
    const V wz = hn::Load(d, wind[1] + lane0);
    const V speed = hn::Sqrt(hn::Add(hn::Mul(wx, wx), hn::Mul(wz, wz)));
    // bendAngle: min(1.3, 0.12·|speed| / max(stiffness, 0.05)).
    const V theta =
        hn::Min(hn::Set(d, 1.3f), hn::Div(hn::Mul(hn::Set(d, 0.12f), hn::Abs(speed)),
                                          hn::Max(hn::Load(d, stiffness + lane0), hn::Set(d, 0.05f))));
    // The bend axis: up × downwind, normalised; +X in calm air.
    const M windy = hn::Gt(speed, hn::Set(d, 1e-6f));
    const V3 downwind{hn::Div(wx, speed), hn::Zero(d), hn::Div(wz, speed)};
    const V3 across = cross(V3{hn::Zero(d), hn::Set(d, 1.0f), hn::Zero(d)}, downwind);
    // glm::normalize: v · (1 / sqrt(v·v)).
    const V inverse = hn::Div(hn::Set(d, 1.0f), length(across));
    const V3 axis = select(windy, scale(inverse, across), V3{hn::Set(d, 1.0f), hn::Zero(d), hn::Zero(d)});
    V3 centre{hn::Load(d, root[0] + lane0), hn::Load(d, root[1] + lane0), hn::Load(d, root[2] + lane0)};
    hn::Store(centre.x, d, centres.v[0][0] + lane0);
    hn::Store(centre.y, d, centres.v[0][1] + lane0);
    hn::Store(centre.z, d, centres.v[0][2] + lane0);
    const V one = hn::Set(d, 1.0f);
    for (int k = 1; k < n; ++k) {
      const V3 seg{hn::Load(d, segments.v[k][0] + lane0), hn::Load(d, segments.v[k][1] + lane0),
                   hn::Load(d, segments.v[k][2] + lane0)};
      // The blade's turn (Turn in Expand.cpp), then its scale.
      const V3 turned{hn::Mul(hn::Add(hn::Mul(c, seg.x), hn::Mul(s, seg.z)), bladeScale),
                      hn::Mul(seg.y, bladeScale),
                      hn::Mul(hn::Add(hn::Mul(hn::Neg(s), seg.x), hn::Mul(c, seg.z)), bladeScale)};
      const V uk = hn::Load(d, u[k] + lane0);
      const V bend = hn::Mul(hn::Mul(theta, uk), uk);
      alignas(64) float bendAngle[kLanes];
      hn::Store(bend, d, bendAngle);
      for (std::size_t l = 0; l < width; ++l) {
        ::sincosf(bendAngle[l], &laneSin[l], &laneCos[l]);
      }
      const V cb = hn::Load(d, laneCos);
      const V sb = hn::Load(d, laneSin);
      // Rodrigues: v·cos + (axis × v)·sin + axis·(axis·v)(1 − cos).
      const V3 rotated = add(add(scale(cb, turned), scale(sb, cross(axis, turned))),
                             scale(hn::Mul(dot(axis, turned), hn::Sub(one, cb)), axis));
      centre = add(centre, rotated);
      hn::Store(centre.x, d, centres.v[k][0] + lane0);
      hn::Store(centre.y, d, centres.v[k][1] + lane0);
      hn::Store(centre.z, d, centres.v[k][2] + lane0);
    }
  }
  std::uint32_t indices[kLanes];
  for (std::size_t l = 0; l < lanes; ++l) {
    indices[l] = inputs[l].blade;
  }
  scatter(centres, indices, lanes, blades.rest);
}

} // namespace

void RestPosesSimd(std::span<const RestShape> shapes, const RestInput* inputs, std::size_t count,
                   SimBlades& blades) {
  for (std::size_t first = 0; first < count; first += kLanes) {
    restGroup(shapes, inputs + first, std::min(kLanes, count - first), blades);
  }
}

void StepBladesSimd(SimBlades& blades, const std::uint32_t* indices, const glm::vec2* wind, std::size_t count,
                    const std::vector<BladeCollider>& colliders, const GroundFunction& ground,
                    const SolverConstants& constants, const GroundShortcuts& shortcuts) {
  for (std::size_t first = 0; first < count; first += kLanes) {
    stepGroup(blades, indices + first, wind + first, std::min(kLanes, count - first), colliders, ground,
              constants, shortcuts);
  }
}

} // namespace sylva::grass::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace sylva::grass {

HWY_EXPORT(StepBladesSimd);
HWY_EXPORT(RestPosesSimd);

void restPosesSimd(std::span<const RestShape> shapes, const RestInput* inputs, std::size_t count,
                   SimBlades& blades) {
  HWY_DYNAMIC_DISPATCH(RestPosesSimd)(shapes, inputs, count, blades);
}

RestShape restShape(const BladeType& type) {
  const std::vector<glm::vec3>& knots = type.lods[0].knots;
  if (knots.size() != static_cast<std::size_t>(kSimKnots)) {
    fail("grass simulation: blade type '{}' has {} knots at its finest level, the solver needs {}", type.name,
         knots.size(), kSimKnots);
  }
  // walkBlade's arc lengths, summed in the same order.
  RestShape shape;
  float total = 0.0f;
  for (std::size_t k = 1; k < knots.size(); ++k) {
    total += glm::length(knots[k] - knots[k - 1]);
  }
  total = std::max(total, 1e-9f);
  float along = 0.0f;
  for (std::size_t k = 1; k < knots.size(); ++k) {
    shape.segment[k] = knots[k] - knots[k - 1];
    along += glm::length(knots[k] - knots[k - 1]);
    shape.u[k] = along / total;
  }
  shape.stiffness = type.stiffness;
  return shape;
}

void stepBladesSimd(SimBlades& blades, const std::uint32_t* indices, const glm::vec2* wind, std::size_t count,
                    const std::vector<BladeCollider>& colliders, const GroundFunction& ground,
                    const SolverConstants& constants, const GroundShortcuts& shortcuts) {
  HWY_DYNAMIC_DISPATCH(StepBladesSimd)(blades, indices, wind, count, colliders, ground, constants, shortcuts);
}

} // namespace sylva::grass
#endif

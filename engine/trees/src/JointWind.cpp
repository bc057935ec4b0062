// Wind on the joints: rest data, the CPU reference step and frames. The step and the frames are the twins of
// shaders/trees/jointwind.glsl (wind.comp, frames.comp), written in the same order with the same float types;
// the wind comes from wind::windVelocities, bit for bit windVelocity (the twin of wind.glsl).
#include <sylva/trees/JointWind.hpp>
#include "internal/Finite.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/wind/Wind.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <utility>

namespace sylva::trees {
namespace {

using internal::finite;

constexpr double kPi = std::numbers::pi;

/** Volume (rim units³) and centroid (model space) of a piece's mesh, closed over its rims. */
struct PieceMass {
  double volume = 0.0;
  glm::dvec3 centroid{0.0};
};

PieceMass pieceMass(const Piece& piece) {
  // Divergence theorem over the quads (two triangles each) and fans closing the rims: an edge used by one
  // quad only lies on a rim, and the fan triangle traverses it the other way round the rim's centre.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& q : piece.quads) {
    for (std::size_t e = 0; e < 4; ++e) {
      edges[{q[e], q[(e + 1) % 4]}] += 1;
    }
  }
  double volume = 0.0;
  glm::dvec3 moment(0.0);
  const auto add = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double v = glm::dot(a, glm::cross(b, c)) / 6.0;
    volume += v;
    moment += v * (a + b + c) / 4.0;
  };
  const auto at = [&](std::uint32_t i) { return glm::dvec3(piece.vertices[i].position); };
  for (const auto& q : piece.quads) {
    add(at(q[0]), at(q[1]), at(q[2]));
    add(at(q[0]), at(q[2]), at(q[3]));
  }
  for (const auto& [edge, count] : edges) {
    if (edges.count({edge.second, edge.first}) != 0) {
      continue;
    }
    const int rim = piece.vertices[edge.first].rim;
    if (rim < 0 || rim >= static_cast<int>(piece.rims.size())) {
      continue;
    }
    const glm::dvec3 centre(glm::vec3(piece.rims[static_cast<std::size_t>(rim)].frame[3]));
    add(at(edge.second), at(edge.first), centre);
  }
  PieceMass out;
  out.volume = std::abs(volume);
  out.centroid = std::abs(volume) > 0.0 ? moment / volume : glm::dvec3(0.0);
  return out;
}

/** Per joint sums over its subtree's pieces (tree space relative to the base, metres, kg, m²). */
struct Sums {
  double mass = 0.0;
  glm::dvec3 massMoment{0.0}; // Σ m x
  double massSquare = 0.0;    // Σ m |x|²
  double area = 0.0;
  glm::dvec3 areaMoment{0.0}; // Σ A x
  int pieces = 0;
  bool jointless = true; // every piece of the subtree has no leaf rims

  void add(const Sums& o) {
    mass += o.mass;
    massMoment += o.massMoment;
    massSquare += o.massSquare;
    area += o.area;
    areaMoment += o.areaMoment;
    pieces += o.pieces;
    jointless = jointless && o.jointless;
  }
};

gpu::JointFrame rows(const glm::mat4& m) {
  return gpu::JointFrame{glm::vec4(m[0][0], m[1][0], m[2][0], m[3][0]),
                         glm::vec4(m[0][1], m[1][1], m[2][1], m[3][1]),
                         glm::vec4(m[0][2], m[1][2], m[2][2], m[3][2])};
}

// ---- The twins of shaders/trees/jointwind.glsl -----------------------------------------------------------

/**
 * One step of one joint (jointWindStep in GLSL) given the wind `u` (m/s, world x and z) sampled at its probe
 * at the tree's time (windVelocities computes that for a block of joints, bit for bit windVelocity).
 */
[[gnu::always_inline]] inline glm::vec4 stepJoint(const gpu::TreeJointRest& r, glm::vec4 m, glm::vec2 u,
                                                  float dt, float maxBend) {
  if ((r.info.w & SYLVA_TREE_WIND_FIXED) != 0u) {
    return glm::vec4(0.0f);
  }
  const float stop = maxBend * (static_cast<float>(r.info.w >> 16u) * (1.0f / 65535.0f));
  const float speed = std::sqrt(u.x * u.x + u.y * u.y);
  const glm::vec2 drive = u * speed;
  const glm::vec2 accel(r.torque.x * drive.x + r.torque.y * drive.y,
                        r.torque.z * drive.x + r.torque.w * drive.y);
  const float kI = r.spring.x;
  const float cI = r.spring.y;
  const glm::vec2 theta(m.x, m.y);
  const glm::vec2 omega(m.z, m.w);
  const float denom = 1.0f + dt * cI + dt * dt * kI;
  glm::vec2 omega1 = (omega + dt * (accel - kI * theta)) / denom;
  glm::vec2 theta1 = theta + dt * omega1;
  const float square = theta1.x * theta1.x + theta1.y * theta1.y;
  if (square > stop * stop) {
    // The stop: θ back onto the joint's circle, the outward part of ω lost (an inelastic stop).
    const float len = std::sqrt(square);
    const glm::vec2 dir = theta1 / len;
    theta1 = dir * stop;
    const float out = omega1.x * dir.x + omega1.y * dir.y;
    if (out > 0.0f) {
      omega1 = omega1 - dir * out;
    }
  }
  return {theta1, omega1};
}

// Frames as rows in four-lane vectors (GCC/Clang vector types: SSE on x86-64, NEON on ARM): lane for lane the
// operations of the GLSL twins, four at a time.
using V4 = float __attribute__((vector_size(16)));

[[gnu::always_inline]] inline V4 load(const glm::vec4& v) {
  V4 out;
  std::memcpy(&out, &v, sizeof out);
  return out;
}

[[gnu::always_inline]] inline glm::vec4 store(V4 v) {
  glm::vec4 out;
  std::memcpy(&out, &v, sizeof out);
  return out;
}

/** local · R(bend) · bone scale as rows (jointLocalFrame in GLSL); a base joint's is its rest frame. */
[[gnu::always_inline]] inline gpu::JointFrame localFrame(const gpu::TreeJointRest& r, glm::vec2 bend) {
  if ((r.info.w & SYLVA_TREE_WIND_FIXED) != 0u) {
    return r.local;
  }
  const float s = r.spring.z;
  V4 r0{s, 0.0f, 0.0f, 0.0f};
  V4 r1{0.0f, s, 0.0f, 0.0f};
  V4 r2{0.0f, 0.0f, s, 0.0f};
  const float angle = std::sqrt(bend.x * bend.x + bend.y * bend.y);
  if (angle > 0.0f) {
    // Rows of the rotation by |bend| about (bend.x, 0, bend.y)/|bend| (glm::rotate's formula), scaled.
    const float kx = bend.x / angle;
    const float kz = bend.y / angle;
    const float c = std::cos(angle);
    const float sn = std::sin(angle);
    const float t = 1.0f - c;
    r0 = V4{c + t * kx * kx, -sn * kz, t * kx * kz, 0.0f} * s;
    r1 = V4{sn * kz, c, -sn * kx, 0.0f} * s;
    r2 = V4{t * kx * kz, sn * kx, c + t * kz * kz, 0.0f} * s;
  }
  const auto row = [&](const glm::vec4& a) {
    V4 out = a.x * r0 + a.y * r1 + a.z * r2;
    out[3] = a.w;
    return store(out);
  };
  return {row(r.local.x), row(r.local.y), row(r.local.z)};
}

/** a · b for frames as rows (composeFrames in GLSL). */
[[gnu::always_inline]] inline gpu::JointFrame compose(const gpu::JointFrame& a, const gpu::JointFrame& b) {
  const V4 bx = load(b.x);
  const V4 by = load(b.y);
  const V4 bz = load(b.z);
  const auto row = [&](const glm::vec4& r) {
    return store(r.x * bx + r.y * by + r.z * bz + V4{0.0f, 0.0f, 0.0f, r.w});
  };
  return {row(a.x), row(a.y), row(a.z)};
}

void checkState(const JointWindRest& rest, const JointWindState& state) {
  if (state.motion.size() != rest.jointCount()) {
    fail("joint wind: the state has {} joints, the rest data {}", state.motion.size(), rest.jointCount());
  }
}

} // namespace

void validate(const JointWindSettings& s, const std::string& where) {
  const std::pair<float, const char*> positive[] = {{s.airDensity, "airDensity"},
                                                    {s.dragCoefficient, "dragCoefficient"},
                                                    {s.maxBend, "maxBend"},
                                                    {s.chainBend, "chainBend"},
                                                    {s.referenceFrequency, "referenceFrequency"},
                                                    {s.referenceCantilever, "referenceCantilever"},
                                                    {s.frequencyExponent, "frequencyExponent"}};
  for (const auto& [v, name] : positive) {
    if (!(std::isfinite(v) && v > 0.0f)) {
      fail("{}.{}: must be a positive finite number, got {}", where, name, v);
    }
  }
  if (!(std::isfinite(s.foliageArea) && s.foliageArea >= 0.0f && s.foliageArea <= 1000.0f)) {
    fail("{}.foliageArea: must be in [0, 1000] squared rim radii, got {}", where, s.foliageArea);
  }
  if (s.maxBend > 1.5f) {
    fail("{}.maxBend: must be at most 1.5 radians, got {}", where, s.maxBend);
  }
  if (s.chainBend > 3.0f) {
    fail("{}.chainBend: must be at most 3 radians, got {}", where, s.chainBend);
  }
  if (s.frequencyExponent > 1.0f) {
    fail("{}.frequencyExponent: must be in (0, 1], got {}", where, s.frequencyExponent);
  }
}

float windTimeOffset(std::uint64_t seed) {
  return static_cast<float>(hash64(seed ^ 0x77696E64ULL) >> 40) * (600.0f / 16777216.0f);
}

JointWindRest buildJointWindRest(const PieceSet& pieces, std::span<const JointWindTree> trees,
                                 const JointWindSettings& settings) {
  validate(settings);
  std::vector<PieceMass> pieceMasses;
  pieceMasses.reserve(pieces.size());
  for (const Piece& p : pieces.pieces) {
    pieceMasses.push_back(pieceMass(p));
  }
  JointWindRest rest;
  rest.maxBend = settings.maxBend;
  rest.jointOffset.assign(1, 0);
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const JointWindTree& tree = trees[t];
    const std::string where = fmt::format("joint wind: trees[{}]", t);
    if (tree.topology == nullptr || tree.species == nullptr) {
      fail("{}: needs a topology and a species", where);
    }
    const TreeTopology& topo = *tree.topology;
    if (topo.jointCount() == 0 || topo.nodes.empty() || topo.jointScale.size() != topo.jointCount() ||
        topo.jointNode.size() != topo.jointCount() || topo.jointOrder.size() != topo.jointCount()) {
      fail("{}: the topology's joints are not indexed (indexJoints)", where);
    }
    if (!tree.pose.empty() && tree.pose.size() != topo.jointCount()) {
      fail("{}: pose has {} bends for {} joints", where, tree.pose.size(), topo.jointCount());
    }
    for (const TreeNode& n : topo.nodes) {
      if (n.piece < 0 || n.piece >= static_cast<int>(pieces.size())) {
        fail("{}: unknown piece index {}", where, n.piece);
      }
    }
    for (std::size_t j = 1; j < topo.jointCount(); ++j) {
      // Subtree sums and frames run parents first.
      if (topo.jointParent[j] < 0 || static_cast<std::size_t>(topo.jointParent[j]) >= j ||
          topo.jointNode[j] < 0 || static_cast<std::size_t>(topo.jointNode[j]) >= topo.nodes.size()) {
        fail("{}: joint {} is not indexed parents first (indexJoints)", where, j);
      }
    }
    if (!finite(tree.base) || !std::isfinite(tree.timeOffset)) {
      fail("{}: base frame and time offset must be finite", where);
    }
    const std::uint64_t end = static_cast<std::uint64_t>(rest.jointOffset.back()) + topo.jointCount();
    if (end > 0xfffffff0ULL) {
      fail("{}: more than 2^32 joints", where);
    }
    rest.jointOffset.push_back(static_cast<std::uint32_t>(end));
  }
  rest.joints.resize(rest.jointOffset.back());
  rest.springs.resize(rest.jointOffset.back());

  parallelFor(
      trees.size(),
      [&](std::size_t begin, std::size_t end) {
        std::vector<glm::mat4> frames;
        std::vector<Sums> sums;
        std::vector<glm::mat4> preBend;
        for (std::size_t t = begin; t < end; ++t) {
          const JointWindTree& tree = trees[t];
          const TreeTopology& topo = *tree.topology;
          const Species& species = *tree.species;
          const std::uint32_t offset = rest.jointOffset[t];
          const std::size_t count = topo.jointCount();
          jointFrames(pieces, topo, tree.base, tree.pose, frames);
          // Joint frames before their bend (world), and each piece's mass and area on its root joint.
          preBend.assign(count, glm::mat4(1.0f));
          sums.assign(count, Sums{});
          const glm::dvec3 origin(glm::vec3(tree.base[3]));
          for (const TreeNode& node : topo.nodes) {
            const Piece& piece = pieces[static_cast<std::size_t>(node.piece)];
            const glm::mat4 model = frames[node.rootJoint] * rimRotation(node.rotation);
            for (std::size_t r = 1; r < piece.rims.size(); ++r) {
              preBend[node.jointBase + r - 1] = model * leafBind(piece, node, r);
            }
            const PieceMass& pm = pieceMasses[static_cast<std::size_t>(node.piece)];
            const double scale = glm::length(glm::dvec3(glm::vec3(model[0])));
            // A stretched piece is that much longer: volume and the centroid's height scale with it.
            const double stretch = node.stretch;
            const glm::vec3 stretched(glm::vec3(pm.centroid) * glm::vec3(1.0f, node.stretch, 1.0f));
            const glm::dvec3 centre = glm::dvec3(glm::vec3(model * glm::vec4(stretched, 1.0f))) - origin;
            Sums s;
            s.mass = static_cast<double>(species.woodDensity) * pm.volume * stretch * scale * scale * scale;
            s.massMoment = s.mass * centre;
            s.massSquare = s.mass * glm::dot(centre, centre);
            s.area = (2.0 / kPi * pm.volume * stretch + (piece.bearsFoliage ? settings.foliageArea : 0.0)) *
                     scale * scale;
            s.areaMoment = s.area * centre;
            s.pieces = 1;
            s.jointless = piece.rims.size() <= 1;
            sums[node.rootJoint].add(s);
          }
          // Subtrees: children have larger indices than their parents.
          for (std::size_t j = count; j-- > 1;) {
            const auto parent = static_cast<std::size_t>(topo.jointParent[j]);
            sums[parent].add(sums[j]);
          }
          for (std::size_t j = 0; j < count; ++j) {
            gpu::TreeJointRest& r = rest.joints[offset + j];
            JointSpring& spring = rest.springs[offset + j];
            const glm::vec2 pose = tree.pose.empty() ? glm::vec2(0.0f) : tree.pose[j];
            r.probe = glm::vec4(0.0f, 0.0f, pose.x, pose.y);
            r.spring = glm::vec4(0.0f, 0.0f, topo.jointScale[j], tree.timeOffset);
            r.torque = glm::vec4(0.0f);
            if (j == 0) {
              r.local = rows(tree.base);
              r.spring.z = 1.0f;
              r.probe.z = 0.0f;
              r.probe.w = 0.0f;
              r.info =
                  glm::uvec4(SYLVA_TREE_NO_PARENT, static_cast<std::uint32_t>(t), 0u, SYLVA_TREE_WIND_FIXED);
              continue;
            }
            const auto nodeIndex = static_cast<std::size_t>(topo.jointNode[j]);
            const TreeNode& node = topo.nodes[nodeIndex];
            const Piece& piece = pieces[static_cast<std::size_t>(node.piece)];
            const std::size_t rim = j - node.jointBase + 1;
            r.local = rows(rimRotation(node.rotation) * leafBind(piece, node, rim));
            const std::uint32_t parent = offset + static_cast<std::uint32_t>(topo.jointParent[j]);
            r.info = glm::uvec4(parent, static_cast<std::uint32_t>(t), rest.joints[parent].info.z + 1u, 0u);
            if (r.info.z + 1u > SYLVA_TREE_MAX_JOINT_CHAIN) {
              fail("joint wind: trees[{}]: joint {} lies {} joints from the base (at most {})", t, j,
                   r.info.z + 1u, SYLVA_TREE_MAX_JOINT_CHAIN);
            }

            // The literal cantilever of the spec.
            const glm::dvec3 x = glm::dvec3(glm::vec3(frames[j][3])) - origin;
            const glm::dvec3 rootCentre = glm::dvec3(glm::vec3(frames[node.rootJoint][3])) - origin;
            const double radius = glm::length(glm::dvec3(glm::vec3(frames[j][0])));
            const double length = std::max(glm::length(x - rootCentre), 1e-6);
            const Sums& s = sums[j];
            const double k =
                static_cast<double>(species.youngModulus) * kPi * std::pow(radius, 4.0) / 4.0 / length;
            const double inertia =
                std::max(s.massSquare - 2.0 * glm::dot(x, s.massMoment) + s.mass * glm::dot(x, x), 1e-12);
            const double cantilever = std::sqrt(k / inertia) / (2.0 * kPi);
            // Calibrated natural frequency (see the header): the spring and damper from it.
            const double frequency = static_cast<double>(settings.referenceFrequency) *
                                     std::pow(cantilever / static_cast<double>(settings.referenceCantilever),
                                              static_cast<double>(settings.frequencyExponent));
            const double omega = 2.0 * kPi * frequency;
            const double zeta = static_cast<double>(species.damping);
            // Aerodynamic torque per |u|u about the pre-bend local x and z axes, per unit inertia.
            const glm::dvec3 centroid = s.area > 0.0 ? s.areaMoment / s.area : x;
            const glm::dvec3 lever = centroid - x;
            const glm::dvec3 ax = glm::normalize(glm::dvec3(glm::vec3(preBend[j][0])));
            const glm::dvec3 az = glm::normalize(glm::dvec3(glm::vec3(preBend[j][2])));
            const double drag = 0.5 * static_cast<double>(settings.airDensity) *
                                static_cast<double>(settings.dragCoefficient) * s.area / inertia;
            const glm::dvec3 gx = glm::cross(ax, lever) * drag;
            const glm::dvec3 gz = glm::cross(az, lever) * drag;
            r.torque = glm::vec4(static_cast<float>(gx.x), static_cast<float>(gx.z), static_cast<float>(gz.x),
                                 static_cast<float>(gz.z));
            r.spring.x = static_cast<float>(omega * omega);
            r.spring.y = static_cast<float>(2.0 * zeta * omega);
            r.probe.x = static_cast<float>(centroid.x + origin.x);
            r.probe.y = static_cast<float>(centroid.z + origin.z);

            spring.radius = static_cast<float>(radius);
            spring.length = static_cast<float>(length);
            spring.mass = static_cast<float>(s.mass);
            spring.inertia = static_cast<float>(inertia);
            spring.area = static_cast<float>(s.area);
            spring.lever = glm::vec3(lever);
            spring.cantileverStiffness = static_cast<float>(k);
            spring.cantileverFrequency = static_cast<float>(cantilever);
            spring.frequency = static_cast<float>(frequency);
            spring.stiffness = static_cast<float>(inertia * omega * omega);
            spring.damping = static_cast<float>(2.0 * zeta * omega * inertia);
            spring.order = topo.jointOrder[j];
            spring.depth = node.depth;
            spring.tip = s.pieces == 1 && s.jointless;
          }
          // Stops: each joint's share of chainBend, its bone over the longest base-to-tip path through it.
          std::vector<double> up(count, 0.0);
          std::vector<double> down(count, 0.0);
          for (std::size_t j = 1; j < count; ++j) {
            up[j] = up[static_cast<std::size_t>(topo.jointParent[j])] + rest.springs[offset + j].length;
          }
          for (std::size_t j = count; j-- > 1;) {
            const auto parent = static_cast<std::size_t>(topo.jointParent[j]);
            down[parent] = std::max(down[parent], down[j] + rest.springs[offset + j].length);
          }
          for (std::size_t j = 1; j < count; ++j) {
            JointSpring& spring = rest.springs[offset + j];
            const double path = std::max(up[j] + down[j], 1e-9);
            const double share = std::min(static_cast<double>(settings.chainBend) * spring.length / path,
                                          static_cast<double>(settings.maxBend)) /
                                 static_cast<double>(settings.maxBend);
            // Rounded down, so the stops along a path never sum past chainBend.
            const auto bits = static_cast<std::uint32_t>(std::floor(std::clamp(share, 0.0, 1.0) * 65535.0));
            rest.joints[offset + j].info.w |= bits << 16u;
            spring.stop = settings.maxBend * (static_cast<float>(bits) * (1.0f / 65535.0f));
          }
        }
      },
      4);
  return rest;
}

void stepJointWindRange(const JointWindRest& rest, JointWindState& state, const gpu::WindUniforms& wind,
                        float dt, std::size_t begin, std::size_t end) {
  checkState(rest, state);
  if (!(std::isfinite(dt) && dt > 0.0f)) {
    fail("joint wind: the time step must be a positive number of seconds, got {}", dt);
  }
  end = std::min(end, rest.jointCount());
  const gpu::TreeJointRest* joints = rest.joints.data();
  glm::vec4* motion = state.motion.data();
  const float maxBend = rest.maxBend;
  // The wind of a block of joints at once (vectorised), then their springs.
  constexpr std::size_t kBlock = 128;
  std::array<glm::vec2, kBlock> probes{};
  std::array<float, kBlock> offsets{};
  std::array<glm::vec2, kBlock> winds{};
  for (std::size_t first = begin; first < end; first += kBlock) {
    const std::size_t n = std::min(kBlock, end - first);
    for (std::size_t i = 0; i < n; ++i) {
      const gpu::TreeJointRest& r = joints[first + i];
      probes[i] = glm::vec2(r.probe.x, r.probe.y);
      offsets[i] = r.spring.w;
    }
    wind::windVelocities(wind, std::span(probes.data(), n), std::span(offsets.data(), n),
                         std::span(winds.data(), n));
    for (std::size_t i = 0; i < n; ++i) {
      motion[first + i] = stepJoint(joints[first + i], motion[first + i], winds[i], dt, maxBend);
    }
  }
}

void stepJointWind(const JointWindRest& rest, JointWindState& state, const gpu::WindUniforms& wind,
                   float dt) {
  checkState(rest, state);
  if (!(std::isfinite(dt) && dt > 0.0f)) {
    fail("joint wind: the time step must be a positive number of seconds, got {}", dt);
  }
  parallelFor(
      rest.jointCount(),
      [&](std::size_t begin, std::size_t end) { stepJointWindRange(rest, state, wind, dt, begin, end); },
      1024);
}

int fixedSteps(double& clock, double now, double dt, int maxSteps) {
  if (!(dt > 0.0) || !std::isfinite(now) || now <= clock) {
    return 0;
  }
  // Steps whose end time is not after `now`; a tiny tolerance so 60 steps of 1/60 s reach one second.
  const double due = std::floor((now - clock) / dt + 1e-9);
  if (due > static_cast<double>(maxSteps)) {
    clock = now - std::fmod(now - clock, dt);
    return maxSteps;
  }
  const int steps = static_cast<int>(due);
  clock += steps * dt;
  return steps;
}

void forestJointFrames(const JointWindRest& rest, const JointWindState& state,
                       std::vector<gpu::JointFrame>& frames) {
  checkState(rest, state);
  frames.resize(rest.jointCount());
  parallelFor(
      rest.treeCount(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
          for (std::uint32_t j = rest.jointOffset[t]; j < rest.jointOffset[t + 1]; ++j) {
            const gpu::TreeJointRest& r = rest.joints[j];
            const glm::vec2 bend(r.probe.z + state.motion[j].x, r.probe.w + state.motion[j].y);
            const gpu::JointFrame local = localFrame(r, bend);
            frames[j] = r.info.x == SYLVA_TREE_NO_PARENT ? local : compose(frames[r.info.x], local);
          }
        }
      },
      4);
}

void forestJointFrames(const JointWindRest& rest, const JointWindState& state,
                       std::vector<glm::mat4>& frames) {
  std::vector<gpu::JointFrame> packed;
  forestJointFrames(rest, state, packed);
  frames.resize(packed.size());
  std::transform(packed.begin(), packed.end(), frames.begin(), jointFrameMatrix);
}

std::vector<glm::vec2> treeBends(const JointWindRest& rest, const JointWindState& state, std::size_t tree) {
  checkState(rest, state);
  if (tree >= rest.treeCount()) {
    fail("joint wind: tree {} of {}", tree, rest.treeCount());
  }
  std::vector<glm::vec2> bends;
  for (std::uint32_t j = rest.jointOffset[tree]; j < rest.jointOffset[tree + 1]; ++j) {
    const gpu::TreeJointRest& r = rest.joints[j];
    bends.emplace_back(r.probe.z + state.motion[j].x, r.probe.w + state.motion[j].y);
  }
  return bends;
}

glm::mat4 jointFrameMatrix(const gpu::JointFrame& f) {
  glm::mat4 m(1.0f);
  for (int c = 0; c < 4; ++c) {
    m[c][0] = f.x[c];
    m[c][1] = f.y[c];
    m[c][2] = f.z[c];
  }
  return m;
}

} // namespace sylva::trees

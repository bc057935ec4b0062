#pragma once
// Wind on the joints (docs/trees.md "Wind on joints", the paper's future work). Every terminal joint j of
// every tree is a damped angular spring: a bend θ ∈ ℝ² about the joint's local x (θ.x) and z (θ.y) axes (the
// bone is local +y; bendRotation's convention) and an angular velocity ω, driven by the shared wind field:
//   I·ω̇ = τ − k·θ − c·ω,   c = 2ζ√(kI),
//   τ = Σ_s (x_s − x_j) × ½ ρ_air C_d A_s |u| u  over the pieces s of j's subtree,
// stepped at a fixed rate by the spec's semi-implicit (backward Euler) step, unconditionally stable for the
// spring and damper:
//   ω' = (ω + dt (τ − kθ)/I) / (1 + dt c/I + dt² k/I),   θ' = θ + dt ω',   |θ'| ≤ the joint's stop (at most
// maxBend, 30°; the stops along any base-to-tip path sum to at most chainBend, 60°).
// The drawn bends are the tree's rest pose plus θ. A tree's base (its joint 0) never bends.
//
// O(1) per joint and step: everything but the wind is folded into per-joint constants at rest
// (buildJointWindRest): the subtree's frontal area A and its area-weighted centroid (the lever arm), so
// τ = (centroid − x_j) × ½ρC_d A |u| u with u = wind::windVelocity at the centroid's world (x, z). The wind
// is sampled at the tree's own time offset (a per-tree phase: no two trees see the same gusts at the same
// moment). Relative velocity: the moving wood's own velocity (ω × lever) is neglected, u_rel = u: at these
// speeds aerodynamic damping is small next to the structural damping ζ and the step's own numerical damping,
// and keeping τ independent of the state keeps the step linear and unconditionally stable.
//
// Stiffness. The spec's cantilever k = E·(π r⁴/4)/L (r: the joint's rim radius, L: the bone from the node's
// root rim centre to the joint, metres) and I = Σ_subtree m |x − x_j|² (lumped masses: wood density × the
// piece mesh's volume, at the piece's centroid) are computed for every joint (JointSpring), but the pieces
// are lumps of wood on short bones that carry no leaves: the literal cantilever puts the presets' trunk
// joints at 2–7 Hz and their twig tips at kilohertz (far above the 30 Hz a 60 Hz step can show), and no wind
// bends the twigs visibly; no per-order factor can fix that, as twig tips of one order already spread over a
// factor of 5. The natural frequency is therefore calibrated: f = f_ref · (f_cantilever / f_cref)^γ
// (JointWindSettings), which keeps the physics' ordering and its dependence on E, ρ, r, L and the subtree's
// mass (stiffer or lighter → faster) but compresses the range onto what trees do: trunks 0.2–1 Hz, twigs
// 2–6 Hz (measured on released joints: trunks 0.25–0.55 Hz, twig tips 2.19–5.80 Hz over the almond, aspen,
// oak and willow presets). The spring then uses k = I (2πf)² and c = 2ζ√(kI) with the species' damping ratio
// ζ. The 30° stop is inelastic: θ is put back on the circle and ω loses its outward part. Units: SI
// throughout (m, s, kg, rad); world space is metres with y up; wind (x, z) is world (x, z).

#include <sylva/trees/Skeleton.hpp>

#include <shared/Trees.h>
#include <shared/Wind.h>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sylva::trees {

/** Constants of the joint springs shared by all trees (the species bring E, wood density and ζ). */
struct JointWindSettings {
  /** Air density, kg/m³. */
  float airDensity = 1.2f;
  /**
   * Effective drag coefficient. A rigid cylinder has 1.0–1.2, but crowns streamline in wind (reconfiguration:
   * measured whole-tree coefficients fall to 0.2–0.5 at moderate to strong winds, Mayhead 1973, Vollsinger
   * et al. 2005); 0.3 bends a grown tree's top by 0.3–1 % of its height at 3 m/s and 10–12 % at 8 m/s.
   */
  float dragCoefficient = 0.3f;
  /**
   * Frontal area added by the foliage of each piece that bears it (caps), in squared rim radii of that piece
   * (the wood's own area is 2/π × its volume, the side of the equivalent cylinder). Leaves catch most of a
   * crown's wind; 0: bark only.
   */
  float foliageArea = 6.0f;
  /** Largest bend |θ| of a joint, radians (30°). */
  float maxBend = 0.52359878f;
  /**
   * Largest bend summed along any chain from a tree's base to a twig tip, radians (60°), so no wind folds a
   * crown over, through itself or into the ground. Each joint's own stop is its share of it: chainBend × its
   * bone length / the longest base-to-tip path through it (the shares along any one path add up to at most
   * 1), and never more than maxBend.
   */
  float chainBend = 1.0471976f;
  /**
   * Frequency calibration f = referenceFrequency · (f_cantilever / referenceCantilever)^frequencyExponent, Hz
   * (see the header comment): a joint whose literal cantilever frequency is referenceCantilever swings at
   * referenceFrequency; exponent in (0, 1], 1 = the literal physics shifted by a constant factor.
   */
  float referenceFrequency = 0.83f;
  /** The literal cantilever frequency that maps onto referenceFrequency, Hz. */
  float referenceCantilever = 60.0f;
  /** The calibration's exponent γ (0.32 with referenceFrequency 0.83 Hz: 2–7 Hz → 0.28–0.42 Hz, 10 kHz → 4.3
   * Hz). */
  float frequencyExponent = 0.32f;
};

/** Throws sylva::Error "<where>.<field>: <reason>" for non-finite, non-positive or out-of-range values. */
void validate(const JointWindSettings& settings, const std::string& where = "joint wind");

/** One tree of a forest for the wind (not owned: the pointers must outlive buildJointWindRest()). */
struct JointWindTree {
  /** The tree's topology (required). */
  const TreeTopology* topology = nullptr;
  /** Its species: Young's modulus, wood density and damping ratio (required). */
  const Species* species = nullptr;
  /** Base frame: world placement, metres per rim unit (baseFrame()). */
  glm::mat4 base{1.0f};
  /** Rest pose bends per joint of the tree, radians (randomPose()); empty: straight. */
  std::span<const glm::vec2> pose;
  /** Seconds added to the wind's clock for this tree (its phase; see windTimeOffset()). */
  float timeOffset = 0.0f;
};

/** A tree's wind time offset in [0, 600) s from a seed (e.g. the tree's index and seed hashed together). */
float windTimeOffset(std::uint64_t seed);

/** What the spring of one joint is made of (diagnostics, benchmarks, tests); zeros for base joints. */
struct JointSpring {
  /** Rim radius at the joint, metres. */
  float radius = 0.0f;
  /** Bone length from the node's root rim centre to the joint, metres. */
  float length = 0.0f;
  /** Mass of the subtree the joint carries, kg. */
  float mass = 0.0f;
  /** The subtree's moment of inertia about the joint, kg·m². */
  float inertia = 0.0f;
  /** Frontal area of the subtree, m². */
  float area = 0.0f;
  /** The lever of the wind's force: the subtree's area centroid − the joint's position, world metres. */
  glm::vec3 lever{0.0f};
  /** The literal cantilever's stiffness k = E·(πr⁴/4)/L, N·m/rad. */
  float cantileverStiffness = 0.0f;
  /** Its natural frequency √(k/I)/2π, Hz. */
  float cantileverFrequency = 0.0f;
  /** The calibrated natural frequency f, Hz. */
  float frequency = 0.0f;
  /** The spring's stiffness k = I(2πf)², N·m/rad. */
  float stiffness = 0.0f;
  /** Its damping c = 2ζ√(kI), N·m·s/rad. */
  float damping = 0.0f;
  /** Branching order of the piece the joint ends (trunk 0). */
  int order = 0;
  /** That piece's depth (pieces from the root). */
  int depth = 0;
  /** True when the joint carries a single piece without leaf rims (a cap: the tip of a twig). */
  bool tip = false;
  /** The joint's own stop, radians: its share of chainBend, at most maxBend (TreeJointRest.info.w >> 16). */
  float stop = 0.0f;
};

/**
 * Rest data of every joint of every tree, concatenated: tree t's joints are the global joints from
 * jointOffset[t] to jointOffset[t + 1] (exclusive), its joint i is global joint jointOffset[t] + i with the
 * topology's numbering (joint 0: the base; a node's root joint is its parent's terminal joint, the same
 * entry). joints[] is what the GPU reads.
 */
struct JointWindRest {
  /** Per global joint: frame, spring, torque and wind-sample constants (layout in shaders/shared/Trees.h). */
  std::vector<gpu::TreeJointRest> joints;
  /** Per global joint: the spring's physical quantities. */
  std::vector<JointSpring> springs;
  /** Per tree: its first global joint; one more entry at the end (the joint count). */
  std::vector<std::uint32_t> jointOffset{0};
  /** Largest bend, radians (the settings' maxBend). */
  float maxBend = 0.52359878f;

  /** Joints of all trees. */
  std::size_t jointCount() const { return joints.size(); }
  /** Trees. */
  std::size_t treeCount() const { return jointOffset.size() - 1; }
};

/**
 * Builds the rest data of `trees` with `pieces` (the set the topologies index). Throws sylva::Error naming
 * the tree for missing topologies or species, poses of the wrong size, unknown pieces, joints not indexed
 * parents first, chains longer than the GPU's SYLVA_TREE_MAX_JOINT_CHAIN and non-finite placements. Trees are
 * built in parallel; the result does not depend on the thread count.
 */
JointWindRest buildJointWindRest(const PieceSet& pieces, std::span<const JointWindTree> trees,
                                 const JointWindSettings& settings = {});

/** The springs' state: per global joint xy = θ (radians about local x and z), zw = ω (rad/s). */
struct JointWindState {
  /** Per global joint: xy θ (radians), zw ω (rad/s); the GPU buffer's layout. */
  std::vector<glm::vec4> motion;

  /** At rest (all zero) for `joints` joints. */
  explicit JointWindState(std::size_t joints = 0) : motion(joints, glm::vec4(0.0f)) {}
  /** Bend θ of a global joint, radians about its local x and z axes. */
  glm::vec2 theta(std::size_t joint) const { return {motion[joint].x, motion[joint].y}; }
  /** Angular velocity ω of a global joint, rad/s. */
  glm::vec2 omega(std::size_t joint) const { return {motion[joint].z, motion[joint].w}; }
};

/**
 * One step of `dt` seconds of every joint (the CPU reference of shaders/trees/wind.comp, operation for
 * operation; the wind through wind::windVelocities, bit for bit windVelocity) in the wind `wind` (its flow.w
 * is the time at the step; each tree adds its offset). Runs on parallelFor's workers; joints are independent,
 * so the result is bit-identical for any thread count. Throws sylva::Error when the state does not match the
 * rest data or dt is not a positive finite number.
 */
void stepJointWind(const JointWindRest& rest, JointWindState& state, const gpu::WindUniforms& wind, float dt);

/** The same step for the joints [begin, end) only, on the calling thread. */
void stepJointWindRange(const JointWindRest& rest, JointWindState& state, const gpu::WindUniforms& wind,
                        float dt, std::size_t begin, std::size_t end);

/**
 * Fixed-rate stepping: the number n of steps of `dt` seconds that bring `clock` (the simulated time, s) up to
 * `now` without passing it, at most `maxSteps`; advances `clock` to the end of the last of them (after a
 * stall it skips ahead instead of catching up). Step i < n runs at wind time clock − (n − 1 − i)·dt with the
 * advanced clock.
 */
int fixedSteps(double& clock, double now, double dt, int maxSteps = 8);

/**
 * Every joint's world frame (the CPU reference of shaders/trees/frames.comp): frames[j] = frames[parent] ·
 * local · R(pose + θ) · bone scale, frames[jointOffset[t]] = tree t's base frame; equal to jointFrames() of
 * each tree with treeBends() within float rounding. One entry per global joint, rows of a 3x4 matrix.
 * Parallel over trees.
 */
void forestJointFrames(const JointWindRest& rest, const JointWindState& state,
                       std::vector<gpu::JointFrame>& frames);

/** The same frames as 4x4 matrices (world ← joint frame, rim units to metres). */
void forestJointFrames(const JointWindRest& rest, const JointWindState& state,
                       std::vector<glm::mat4>& frames);

/** Tree `tree`'s bends, pose + θ per joint of the tree (radians): jointFrames()'s `bends` argument. */
std::vector<glm::vec2> treeBends(const JointWindRest& rest, const JointWindState& state, std::size_t tree);

/** A JointFrame (three rows) as a 4x4 matrix. */
glm::mat4 jointFrameMatrix(const gpu::JointFrame& frame);

} // namespace sylva::trees

#pragma once
// A rigid-body world on a terrain (Bullet): the terrain as a heightfield collider made from the same heights
// the terrain draws, and spheres, capsules and boxes with seeded initial states. Each step exports the
// bodies' collision shapes (as capsules, spheres being capsules of zero length) and bounding boxes for the
// grass.

#include <sylva/core/Geometry.hpp>
#include <sylva/terrain/HeightField.hpp>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sylva::physics {

/** Shape of a body. */
enum class Shape { Sphere, Capsule, Box };

/** A body to add: world metres, kg, m/s. */
struct BodySpec {
  /** Collision shape. */
  Shape shape = Shape::Sphere;
  /** Sphere: x = radius. Capsule (upright, along local +Y): x = radius, y = half the length of its cylinder.
   * Box: half extents. */
  glm::vec3 size{0.3f};
  /** Centre, world metres. */
  glm::vec3 position{0.0f};
  /** Initial velocity, m/s. */
  glm::vec3 velocity{0.0f};
  /** Angular velocity, rad/s (world axes). */
  glm::vec3 spin{0.0f};
  /** kg; 0 = static. */
  float mass = 20.0f;
  /** Sliding friction coefficient (Bullet multiplies it by the other surface's; the terrain's is 0.9). */
  float friction = 0.8f;
  /** Restitution coefficient (Bullet's; 0: no bounce). */
  float restitution = 0.1f;
  /** Rolling friction (Bullet): stops balls rolling forever on flat ground. */
  float rollingFriction = 0.002f;
  /** Throws sylva::Error naming `where` and the field for NaN, non-positive sizes, negative mass. */
  void validate(const std::string& where = "body") const;
};

/** A body's pose now. */
struct BodyState {
  glm::vec3 position{0.0f};                      ///< centre, world metres
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f}; ///< rotation from the body's local axes to world
  glm::vec3 velocity{0.0f};                      ///< linear velocity, m/s
};

/** A body's collision shape for the grass: a capsule from a to b (a == b: a sphere), its box and mass. */
struct ShapeExport {
  glm::vec3 a{0.0f};   ///< one end of the capsule's axis, world metres
  glm::vec3 b{0.0f};   ///< the other end (equal to a for a sphere)
  float radius = 0.0f; ///< capsule radius, metres
  float mass = 0.0f;   ///< kg (0: static)
  Aabb box;            ///< world-space bounds of the body
};

/** Most bodies a world holds. */
inline constexpr int kMaxBodies = 65536;

/** The world. Move-only. */
class World {
public:
  /**
   * The terrain `field` (heights as drawn, metres; absent samples take the lowest height) as a static
   * heightfield collider placed so that sample (i, j) is at world (i·spacingX, h, j·spacingZ); gravity along
   * −Y.
   */
  explicit World(const terrain::HeightField& field, float gravity = 9.81f);
  ~World();
  /** Moves the simulation (the source is left empty). */
  World(World&&) noexcept;
  /** Moves the simulation (the source is left empty). */
  World& operator=(World&&) noexcept;

  /** Adds a body (validated; errors name `where`); returns its index. Throws past kMaxBodies. */
  int addBody(const BodySpec& spec, const std::string& where = "body");
  /** Advances by `seconds` in fixed substeps of 1/240 s (deterministic for the same calls). */
  void step(float seconds);
  /** Bodies added so far. */
  std::size_t bodyCount() const;
  /** Pose of body `index` (from addBody) now. */
  BodyState body(int index) const;
  /** Every body's collision shape now (boxes as the capsule along their longest axis with the box's smaller
   * half extent as radius). */
  std::vector<ShapeExport> shapes() const;
  /** Simulated time, seconds. */
  double time() const;

private:
  struct Impl;
  std::unique_ptr<Impl> mImpl;
};

/**
 * `count` balls (radius 0.25..0.45 m, 15..60 kg) scattered over a disc of `radius` metres around `centre`
 * (x, z), dropped from `drop` metres above the ground there, with small seeded velocities: the demo preset.
 */
std::vector<BodySpec> seededBalls(const terrain::HeightField& field, glm::vec2 centre, float radius,
                                  int count, std::uint64_t seed, float drop = 1.0f);

} // namespace sylva::physics

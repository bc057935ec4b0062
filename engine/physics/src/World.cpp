#include <sylva/physics/World.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::physics {
namespace {

btVector3 bt(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

glm::vec3 toGlm(const btVector3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

constexpr float kSubstep = 1.0f / 240.0f;

} // namespace

void BodySpec::validate(const std::string& where) const {
  const auto finite3 = [&](const glm::vec3& v, const char* name) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      fail("{}: {} must be finite, got ({}, {}, {})", where, name, v.x, v.y, v.z);
    }
  };
  finite3(size, "size");
  finite3(position, "position");
  finite3(velocity, "velocity");
  finite3(spin, "spin");
  const float smallest = shape == Shape::Sphere    ? size.x
                         : shape == Shape::Capsule ? std::min(size.x, size.y + size.x)
                                                   : std::min({size.x, size.y, size.z});
  if (!(smallest > 0.0f) || (shape == Shape::Capsule && size.y < 0.0f)) {
    fail("{}: size must be > 0 (sphere: radius; capsule: radius, half length ≥ 0; box: half extents), got "
         "({}, "
         "{}, {})",
         where, size.x, size.y, size.z);
  }
  if (std::max({size.x, size.y, size.z}) > 1000.0f) {
    fail("{}: size ({}, {}, {}) m is absurd (at most 1000 m)", where, size.x, size.y, size.z);
  }
  const std::pair<float, const char*> values[] = {{mass, "mass"},
                                                  {friction, "friction"},
                                                  {restitution, "restitution"},
                                                  {rollingFriction, "rollingFriction"}};
  for (const auto& [v, name] : values) {
    if (!std::isfinite(v) || v < 0.0f) {
      fail("{}: {} must be a finite number ≥ 0, got {}", where, name, v);
    }
  }
}

struct World::Impl {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  std::vector<float> heights;
  std::unique_ptr<btHeightfieldTerrainShape> terrainShape;
  std::unique_ptr<btDefaultMotionState> terrainMotion;
  std::unique_ptr<btRigidBody> terrainBody;
  struct Body {
    BodySpec spec;
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btDefaultMotionState> motion;
    std::unique_ptr<btRigidBody> body;
  };
  std::vector<Body> bodies;
  double time = 0.0;
  float pending = 0.0f;

  ~Impl() {
    for (Body& b : bodies) {
      world.removeRigidBody(b.body.get());
    }
    if (terrainBody) {
      world.removeRigidBody(terrainBody.get());
    }
  }
};

World::World(const terrain::HeightField& field, float gravity) : mImpl(std::make_unique<Impl>()) {
  if (!std::isfinite(gravity) || gravity < 0.0f) {
    fail("physics: gravity must be a finite number ≥ 0, got {}", gravity);
  }
  if (field.width() < 2 || field.height() < 2) {
    fail("physics: the terrain needs at least 2x2 samples, got {}x{}", field.width(), field.height());
  }
  Impl& m = *mImpl;
  m.world.setGravity(btVector3(0.0f, -gravity, 0.0f));
  float lo = std::numeric_limits<float>::infinity();
  float hi = -std::numeric_limits<float>::infinity();
  for (const float h : field.samples()) {
    if (!std::isnan(h)) {
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
  }
  if (!(lo <= hi)) {
    fail("physics: the terrain has no valid height sample");
  }
  m.heights = field.samples();
  for (float& h : m.heights) {
    h = std::isnan(h) ? lo : h;
  }
  hi = std::max(hi, lo + 1e-3f);
  // Bullet centres a heightfield on its bounding box: place that centre where the samples belong.
  m.terrainShape = std::make_unique<btHeightfieldTerrainShape>(field.width(), field.height(),
                                                               m.heights.data(), lo, hi, 1, false);
  m.terrainShape->setLocalScaling(btVector3(field.spacingX(), 1.0f, field.spacingZ()));
  btTransform place;
  place.setIdentity();
  place.setOrigin(btVector3(0.5f * field.extentX(), 0.5f * (lo + hi), 0.5f * field.extentZ()));
  m.terrainMotion = std::make_unique<btDefaultMotionState>(place);
  btRigidBody::btRigidBodyConstructionInfo info(0.0f, m.terrainMotion.get(), m.terrainShape.get());
  info.m_friction = 0.9f;
  info.m_rollingFriction = 0.001f;
  m.terrainBody = std::make_unique<btRigidBody>(info);
  m.world.addRigidBody(m.terrainBody.get());
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

int World::addBody(const BodySpec& spec, const std::string& where) {
  spec.validate(where);
  Impl& m = *mImpl;
  if (m.bodies.size() >= static_cast<std::size_t>(kMaxBodies)) {
    fail("{}: a world holds at most {} bodies", where, kMaxBodies);
  }
  Impl::Body b;
  b.spec = spec;
  switch (spec.shape) {
  case Shape::Sphere:
    b.shape = std::make_unique<btSphereShape>(spec.size.x);
    break;
  case Shape::Capsule:
    b.shape = std::make_unique<btCapsuleShape>(spec.size.x, 2.0f * spec.size.y);
    break;
  case Shape::Box:
    b.shape = std::make_unique<btBoxShape>(bt(spec.size));
    break;
  }
  btVector3 inertia(0.0f, 0.0f, 0.0f);
  if (spec.mass > 0.0f) {
    b.shape->calculateLocalInertia(spec.mass, inertia);
  }
  btTransform start;
  start.setIdentity();
  start.setOrigin(bt(spec.position));
  b.motion = std::make_unique<btDefaultMotionState>(start);
  btRigidBody::btRigidBodyConstructionInfo info(spec.mass, b.motion.get(), b.shape.get(), inertia);
  info.m_friction = spec.friction;
  info.m_restitution = spec.restitution;
  info.m_rollingFriction = spec.rollingFriction;
  info.m_spinningFriction = spec.rollingFriction;
  b.body = std::make_unique<btRigidBody>(info);
  b.body->setLinearVelocity(bt(spec.velocity));
  b.body->setAngularVelocity(bt(spec.spin));
  b.body->setActivationState(DISABLE_DEACTIVATION);
  m.world.addRigidBody(b.body.get());
  m.bodies.push_back(std::move(b));
  return static_cast<int>(m.bodies.size()) - 1;
}

void World::step(float seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0f) {
    fail("physics: step of {} s", seconds);
  }
  Impl& m = *mImpl;
  m.pending += seconds;
  // Fixed substeps driven here (not Bullet's interpolating internal clock), so the same calls give the same
  // states whatever the frame times.
  while (m.pending >= kSubstep * 0.999f) {
    m.world.stepSimulation(kSubstep, 0, kSubstep);
    m.pending -= kSubstep;
    m.time += kSubstep;
  }
}

std::size_t World::bodyCount() const {
  return mImpl->bodies.size();
}

BodyState World::body(int index) const {
  const Impl& m = *mImpl;
  if (index < 0 || static_cast<std::size_t>(index) >= m.bodies.size()) {
    fail("physics: no body {}", index);
  }
  const btRigidBody& b = *m.bodies[static_cast<std::size_t>(index)].body;
  const btTransform& t = b.getWorldTransform();
  const btQuaternion q = t.getRotation();
  BodyState s;
  s.position = toGlm(t.getOrigin());
  s.orientation = glm::quat(static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
                            static_cast<float>(q.z()));
  s.velocity = toGlm(b.getLinearVelocity());
  return s;
}

std::vector<ShapeExport> World::shapes() const {
  std::vector<ShapeExport> out;
  out.reserve(mImpl->bodies.size());
  for (const Impl::Body& b : mImpl->bodies) {
    const btTransform& t = b.body->getWorldTransform();
    const glm::vec3 centre = toGlm(t.getOrigin());
    const auto axisWorld = [&](const glm::vec3& local) { return toGlm(t.getBasis() * bt(local)); };
    ShapeExport e;
    e.mass = b.spec.mass;
    const glm::vec3 s = b.spec.size;
    switch (b.spec.shape) {
    case Shape::Sphere:
      e.a = e.b = centre;
      e.radius = s.x;
      break;
    case Shape::Capsule:
      e.a = centre - axisWorld({0.0f, s.y, 0.0f});
      e.b = centre + axisWorld({0.0f, s.y, 0.0f});
      e.radius = s.x;
      break;
    case Shape::Box: {
      // The capsule along the longest axis whose radius is the smaller of the other two half extents.
      const int longest = s.x >= s.y && s.x >= s.z ? 0 : s.y >= s.z ? 1 : 2;
      glm::vec3 half(0.0f);
      half[longest] = s[longest];
      e.radius = std::min(s[(longest + 1) % 3], s[(longest + 2) % 3]);
      half[longest] = std::max(0.0f, s[longest] - e.radius);
      e.a = centre - axisWorld(half);
      e.b = centre + axisWorld(half);
      break;
    }
    }
    btVector3 lo;
    btVector3 hi;
    b.body->getAabb(lo, hi);
    e.box = {toGlm(lo), toGlm(hi)};
    out.push_back(e);
  }
  return out;
}

double World::time() const {
  return mImpl->time;
}

std::vector<BodySpec> seededBalls(const terrain::HeightField& field, glm::vec2 centre, float radius,
                                  int count, std::uint64_t seed, float drop) {
  if (count < 0 || count > kMaxBodies) {
    fail("physics: {} balls (expected 0..{})", count, kMaxBodies);
  }
  Rng rng(seed);
  std::vector<BodySpec> balls;
  for (int i = 0; i < count; ++i) {
    const float angle = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
    const float r = radius * std::sqrt(rng.uniform());
    const glm::vec2 xz = centre + r * glm::vec2(std::cos(angle), std::sin(angle));
    BodySpec b;
    b.shape = Shape::Sphere;
    b.size = glm::vec3(rng.uniform(0.25f, 0.45f));
    const float ground = terrain::heightAt(field, xz.x, xz.y);
    b.position = {xz.x, (std::isnan(ground) ? 0.0f : ground) + drop + b.size.x, xz.y};
    b.velocity = {rng.uniform(-0.5f, 0.5f), 0.0f, rng.uniform(-0.5f, 0.5f)};
    b.mass = rng.uniform(15.0f, 60.0f);
    balls.push_back(b);
  }
  return balls;
}

} // namespace sylva::physics

#include <sylva/scene/gpu/GrassSimulation.hpp>

#include <sylva/gl/ContextInfo.hpp>

#include <utility>
#include <vector>

namespace sylva::scene {
namespace {

template <class Settings> const Settings& checked(const Settings& s) {
  s.validate();
  return s;
}

} // namespace

GrassSimulation::GrassSimulation(const shader::Library& library, const terrain::HeightField& ground,
                                 grass::GrassRenderer& grass, std::shared_ptr<const grass::GrassField> field,
                                 const GrassSimSettings& settings)
    : mGrass(grass), mWorld(std::make_unique<physics::World>(ground)),
      mTiles(std::make_unique<grass::TileSimulation>(std::move(field), checked(settings.pool),
                                                     checked(settings.solver))),
      mBodies(library),
      mGpu(settings.solve == GrassSolve::Gpu ||
           (settings.solve == GrassSolve::Auto && gl::queryContextInfo().deviceClass() != "llvmpipe")) {
  mSimulator = std::make_unique<grass::GrassSimulator>(library, grass, *mTiles);
  if (mGpu) {
    mTiles->setBackend(mSimulator.get());
  }
  mGrass.setSimulation(mSimulator.get());
}

GrassSimulation::~GrassSimulation() {
  mGrass.setSimulation(nullptr);
}

void GrassSimulation::spawnBalls(glm::vec2 centre, float radius, int count, std::uint64_t seed, float drop) {
  int i = 0;
  for (const physics::BodySpec& b :
       physics::seededBalls(mTiles->field().terrain(), centre, radius, count, seed, drop)) {
    mWorld->addBody(b, "balls[" + std::to_string(i++) + "]");
  }
}

void GrassSimulation::addBody(const physics::BodySpec& spec, const std::string& where) {
  mWorld->addBody(spec, where);
}

void GrassSimulation::spawnBall(const glm::vec3& position, const glm::vec3& velocity, float radius,
                                float mass) {
  physics::BodySpec b;
  b.size = glm::vec3(radius);
  b.position = position;
  b.velocity = velocity;
  b.mass = mass;
  mWorld->addBody(b, "ball");
}

void GrassSimulation::advance(double seconds, const wind::WindSettings& wind) {
  if (seconds > mTime) {
    mWorld->step(static_cast<float>(seconds - mTime));
    mTime = seconds;
  }
  std::vector<grass::SimBody> bodies;
  for (const physics::ShapeExport& e : mWorld->shapes()) {
    bodies.push_back({{e.a, e.b, e.radius, e.mass}, e.box});
  }
  mTiles->advance(seconds, bodies, wind);
  if (!mGpu) {
    mSimulator->upload(*mTiles);
  }
  mSimulator->syncSlots(*mTiles);
}

void GrassSimulation::drawBodies(const render::Camera& camera, int width, int height, double time,
                                 const render::Environment& environment) {
  mBodies.draw(*mWorld, camera, width, height, time, environment);
}

void GrassSimulation::reloadShaders(const shader::Library& library) {
  mSimulator->reloadShaders(library);
  mBodies.reloadShaders(library);
}

} // namespace sylva::scene

#include <sylva/core/Geometry.hpp>
#include <sylva/core/Random.hpp>

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include <vector>

namespace {

// Box-vs-frustum throughput: the inner loop of every culling pass (terrain nodes, grass tiles, trees).
void frustumBoxTest(benchmark::State& state) {
  const glm::mat4 viewProj = glm::perspective(glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 5000.0f) *
                             glm::lookAt(glm::vec3(0, 100, 0), glm::vec3(500, 0, 500), glm::vec3(0, 1, 0));
  const sylva::Frustum frustum(viewProj);
  sylva::Rng rng(1);
  std::vector<sylva::Aabb> boxes(4096);
  for (auto& b : boxes) {
    b.min = glm::vec3(rng.uniform(-2000, 2000), rng.uniform(0, 100), rng.uniform(-2000, 2000));
    b.max = b.min + glm::vec3(rng.uniform(1, 100));
  }
  for (auto _ : state) {
    int visible = 0;
    for (const auto& b : boxes) {
      visible += frustum.intersects(b) ? 1 : 0;
    }
    benchmark::DoNotOptimize(visible);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(boxes.size()));
}
BENCHMARK(frustumBoxTest);

} // namespace

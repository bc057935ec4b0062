// Terrain LOD decisions on the CPU: quadtree selection + neighbour levels for a 16k × 16k field, and the
// min/max structures (the paper's 2D RMQ vs the min-max pyramid). Run: sylva_benchmarks
// --benchmark_filter=Terrain
#include <sylva/core/Geometry.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/terrain/MinMax.hpp>
#include <sylva/terrain/Quadtree.hpp>

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <memory>
#include <vector>

namespace {

using sylva::terrain::CrackMethod;
using sylva::terrain::HeightField;
using sylva::terrain::HeightRange;
using sylva::terrain::MinMaxPyramid;
using sylva::terrain::MinMaxRmq;
using sylva::terrain::Quadtree;
using sylva::terrain::QuadtreeConfig;
using sylva::terrain::QuadtreeSelection;

// The 16k field: 16384² samples at 1 m (16383 m across) would be 1 GiB of floats, so it is never stored.
// Heights come from an analytic function h(x, z) (metres) and each 32 m leaf block's range from h on a 5×5
// grid widened by |∇h|max · (half the grid diagonal), a conservative bound of what the 1 m samples would
// hold.
constexpr int kSamples = 16384;
constexpr int kLeafMetres = 32;
constexpr int kLeafBlocks = kSamples / kLeafMetres; // 512 per axis
constexpr float kExtent = static_cast<float>(kSamples - 1);

float height(float x, float z) {
  return 400.0f + 250.0f * std::sin(x * 0.0015340f) * std::cos(z * 0.0020944f) +
         60.0f * std::sin(x / 180.0f + z / 230.0f) + 15.0f * std::sin(x / 37.0f) * std::sin(z / 41.0f);
}
// |∂h/∂x| + |∂h/∂z| bound of the terms above.
constexpr float kSlopeBound = 250.0f * (0.0015340f + 0.0020944f) + 60.0f * (1.0f / 180.0f + 1.0f / 230.0f) +
                              15.0f * (1.0f / 37.0f + 1.0f / 41.0f);

const std::vector<HeightRange>& leafRanges() {
  static const std::vector<HeightRange> ranges = [] {
    std::vector<HeightRange> out(static_cast<std::size_t>(kLeafBlocks) * kLeafBlocks);
    sylva::parallelFor(static_cast<std::size_t>(kLeafBlocks), [&](std::size_t z0, std::size_t z1) {
      for (std::size_t bz = z0; bz < z1; ++bz) {
        for (int bx = 0; bx < kLeafBlocks; ++bx) {
          HeightRange r;
          for (int v = 0; v <= 4; ++v) {
            for (int u = 0; u <= 4; ++u) {
              r.include(height(static_cast<float>(bx * kLeafMetres + u * 8),
                               static_cast<float>(static_cast<int>(bz) * kLeafMetres + v * 8)));
            }
          }
          const float pad = kSlopeBound * 4.0f; // 8 m grid: a point is ≤ 4 m from a grid line on each axis
          out[bz * kLeafBlocks + static_cast<std::size_t>(bx)] = HeightRange{r.min - pad, r.max + pad};
        }
      }
    });
    return out;
  }();
  return ranges;
}

// A quadtree over the 16k field whose deepest nodes are the 32 m leaf blocks.
std::unique_ptr<Quadtree> makeTree(int rootsX, int rootsZ, float rootSize, int maxDepth) {
  QuadtreeConfig c;
  c.rootsX = rootsX;
  c.rootsZ = rootsZ;
  c.rootSize = rootSize;
  c.maxDepth = maxDepth;
  c.lodDistanceFactor = 2.0f;
  c.patchTessLevel = 32;
  const int nx = rootsX << maxDepth;
  const int nz = rootsZ << maxDepth;
  const auto& ranges = leafRanges();
  MinMaxPyramid pyramid = MinMaxPyramid::fromLeaves(nx, nz, [&](int x, int z) {
    return x < kLeafBlocks && z < kLeafBlocks
               ? ranges[static_cast<std::size_t>(z) * kLeafBlocks + static_cast<std::size_t>(x)]
               : HeightRange::absent();
  });
  return std::make_unique<Quadtree>(c, kExtent, kExtent, std::move(pyramid));
}

// 8×8 roots of 2048 m, depth 0..6 (2048 m … 32 m patches; tessellation 32 gives 1 m vertex spacing).
Quadtree& benchTree() {
  static const std::unique_ptr<Quadtree> tree = makeTree(8, 8, 2048.0f, 6);
  return *tree;
}

struct View {
  glm::vec3 position;
  sylva::Frustum frustum;
};

// One view: 2 m above the ground near the middle, looking across the terrain, 20 km far plane.
View benchView() {
  const glm::vec3 pos(6100.0f, height(6100.0f, 7300.0f) + 2.0f, 7300.0f);
  const glm::vec3 dir(std::cos(0.7f), -0.15f, std::sin(0.7f));
  return View{pos, sylva::Frustum(glm::perspective(glm::radians(60.0f), 16.0f / 9.0f, 0.5f, 20000.0f) *
                                  glm::lookAt(pos, pos + dir, glm::vec3(0, 1, 0)))};
}

void terrainLodSelect(benchmark::State& state, CrackMethod method, bool cull) {
  Quadtree& tree = benchTree();
  QuadtreeConfig c = tree.config();
  c.method = method;
  c.frustumCull = cull;
  tree.setConfig(c);
  const View view = benchView();
  QuadtreeSelection selection;
  for (auto _ : state) {
    tree.select(view.position, &view.frustum, selection);
    benchmark::DoNotOptimize(selection.nodes.data());
  }
  state.counters["leaves"] = selection.stats.leaves;
  state.counters["visited"] = selection.stats.nodesVisited;
  state.counters["doubled"] = selection.stats.doubledEdges;
  state.counters["neighbourSteps"] = static_cast<double>(selection.stats.neighbourSteps);
  state.counters["processedVertices"] = static_cast<double>(selection.stats.processedVertices);
  state.counters["minmaxBytes"] = static_cast<double>(tree.memoryBytes());
}
BENCHMARK_CAPTURE(terrainLodSelect, none, CrackMethod::None, true)
    ->Name("TerrainLodSelect16k/None")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(terrainLodSelect, paper, CrackMethod::PaperSearch, true)
    ->Name("TerrainLodSelect16k/PaperSearch")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(terrainLodSelect, map, CrackMethod::RestrictedLevelMap, true)
    ->Name("TerrainLodSelect16k/RestrictedLevelMap")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(terrainLodSelect, paperNoCull, CrackMethod::PaperSearch, false)
    ->Name("TerrainLodSelect16k/PaperSearch/noCull")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(terrainLodSelect, mapNoCull, CrackMethod::RestrictedLevelMap, false)
    ->Name("TerrainLodSelect16k/RestrictedLevelMap/noCull")
    ->Unit(benchmark::kMillisecond);

// The paper's Table 8 layouts (4/16/32/64 roots, LOD on/off, tessellation 32) on the 16k field: CPU selection
// cost and the processed-vertex estimate, for both crack methods. Leaves stay 32 m for every root count.
void terrainTable8(benchmark::State& state) {
  const int roots = static_cast<int>(state.range(0));
  const bool lod = state.range(1) != 0;
  const auto method = static_cast<CrackMethod>(state.range(2));
  const QuadtreeConfig layout = QuadtreeConfig::forRootCount(roots, kExtent, kExtent);
  const float rootSize =
      16384.0f / static_cast<float>(layout.rootsZ); // 2×2: 8192 m … 8×4 and 8×8: 2048/4096 m
  const int maxDepth = static_cast<int>(std::lround(std::log2(rootSize / kLeafMetres)));
  const std::unique_ptr<Quadtree> tree = makeTree(layout.rootsX, layout.rootsZ, rootSize, maxDepth);
  QuadtreeConfig c = tree->config();
  c.lodEnabled = lod;
  c.method = method;
  tree->setConfig(c);
  const View view = benchView();
  QuadtreeSelection selection;
  for (auto _ : state) {
    tree->select(view.position, &view.frustum, selection);
    benchmark::DoNotOptimize(selection.nodes.data());
  }
  state.counters["leaves"] = selection.stats.leaves;
  state.counters["processedVertices"] = static_cast<double>(selection.stats.processedVertices);
}
BENCHMARK(terrainTable8)
    ->Name("TerrainTable8")
    ->ArgNames({"roots", "lod", "method"})
    ->ArgsProduct({{4, 16, 32, 64},
                   {0, 1},
                   {static_cast<int>(CrackMethod::PaperSearch),
                    static_cast<int>(CrackMethod::RestrictedLevelMap)}})
    ->Unit(benchmark::kMicrosecond);

// Min/max structures on a 512² field (the RMQ needs ~135 MiB there; 1024² would need ~680 MiB).
constexpr int kQueryField = 512;

const HeightField& queryField() {
  static const HeightField field = [] {
    HeightField f(kQueryField, kQueryField);
    for (int j = 0; j < kQueryField; ++j) {
      for (int i = 0; i < kQueryField; ++i) {
        f.at(i, j) = height(static_cast<float>(i) * 8.0f, static_cast<float>(j) * 8.0f);
      }
    }
    return f;
  }();
  return field;
}

struct Rect {
  int i0, i1, j0, j1;
};

std::vector<Rect> randomRects() {
  sylva::Rng rng(42);
  std::vector<Rect> rects(4096);
  for (Rect& r : rects) {
    const int w = 1 + static_cast<int>(rng.below(128));
    const int h = 1 + static_cast<int>(rng.below(128));
    r.i0 = static_cast<int>(rng.below(static_cast<std::uint32_t>(kQueryField - w)));
    r.j0 = static_cast<int>(rng.below(static_cast<std::uint32_t>(kQueryField - h)));
    r.i1 = r.i0 + w;
    r.j1 = r.j0 + h;
  }
  return rects;
}

void terrainMinMaxRmqQuery(benchmark::State& state) {
  static const MinMaxRmq rmq(queryField());
  const std::vector<Rect> rects = randomRects();
  for (auto _ : state) {
    float sum = 0.0f;
    for (const Rect& r : rects) {
      sum += rmq.query(r.i0, r.i1, r.j0, r.j1).max;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rects.size()));
  state.counters["bytes"] = static_cast<double>(rmq.memoryBytes());
}
BENCHMARK(terrainMinMaxRmqQuery)->Name("TerrainMinMax/RmqQuery");

void terrainMinMaxPyramidBound(benchmark::State& state) {
  static const MinMaxPyramid pyramid(queryField(), 16);
  const std::vector<Rect> rects = randomRects();
  for (auto _ : state) {
    float sum = 0.0f;
    for (const Rect& r : rects) {
      sum += pyramid.bound(r.i0, r.i1, r.j0, r.j1).max;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rects.size()));
  state.counters["bytes"] = static_cast<double>(pyramid.memoryBytes());
}
BENCHMARK(terrainMinMaxPyramidBound)->Name("TerrainMinMax/PyramidBound");

// What the quadtree does: one node (level, bx, bz) at a time.
void terrainMinMaxPyramidNode(benchmark::State& state) {
  static const MinMaxPyramid pyramid(queryField(), 16);
  sylva::Rng rng(7);
  std::vector<Rect> nodes(4096); // (level, bx, bz) in i0, i1, j0
  for (Rect& n : nodes) {
    n.i0 = static_cast<int>(rng.below(static_cast<std::uint32_t>(pyramid.levelCount())));
    n.i1 = static_cast<int>(rng.below(static_cast<std::uint32_t>(pyramid.blocksX(n.i0))));
    n.j0 = static_cast<int>(rng.below(static_cast<std::uint32_t>(pyramid.blocksZ(n.i0))));
  }
  for (auto _ : state) {
    float sum = 0.0f;
    for (const Rect& n : nodes) {
      sum += pyramid.node(n.i0, n.i1, n.j0).max;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(nodes.size()));
  state.counters["bytes"] = static_cast<double>(pyramid.memoryBytes());
}
BENCHMARK(terrainMinMaxPyramidNode)->Name("TerrainMinMax/PyramidNode");

void terrainMinMaxBuild(benchmark::State& state) {
  const bool rmq = state.range(0) == 0;
  for (auto _ : state) {
    if (rmq) {
      const MinMaxRmq s(queryField());
      benchmark::DoNotOptimize(s.memoryBytes());
    } else {
      const MinMaxPyramid s(queryField(), 16);
      benchmark::DoNotOptimize(s.memoryBytes());
    }
  }
}
BENCHMARK(terrainMinMaxBuild)
    ->Name("TerrainMinMax/Build")
    ->ArgName("pyramid")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond);

} // namespace

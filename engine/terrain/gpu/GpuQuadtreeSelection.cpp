#include <sylva/terrain/gpu/GpuQuadtreeSelection.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/shader/Compiler.hpp>

#include <algorithm>

namespace sylva::terrain {

namespace {

void setTable(glm::uvec4 (&table)[7], int depth, std::uint32_t value) {
  table[depth / 4][depth % 4] = value;
}

} // namespace

GpuQuadtreeSelection::GpuQuadtreeSelection(const shader::Library& library, const Quadtree& quadtree)
    : mQuadtree(quadtree),
      mProgram(shader::compileProgram(library, {"terrain select", {"terrain/select.comp"}, {}})),
      mParams(sizeof(gpu::TerrainSelectParams)), mCounters(sizeof(gpu::TerrainSelectCounters)) {
  const QuadtreeConfig& c = quadtree.config();
  if (c.maxDepth > SYLVA_TERRAIN_SELECT_MAX_DEPTH) {
    fail("GPU selection: quadtree depth {} is above the shader's limit of {}", c.maxDepth,
         SYLVA_TERRAIN_SELECT_MAX_DEPTH);
  }
  std::uint64_t nodes = 0;
  std::uint64_t bits = 0;
  std::uint64_t widest = 0;
  for (int d = 0; d <= c.maxDepth; ++d) {
    const auto count = static_cast<std::uint64_t>(quadtree.gridWidth(d)) *
                       static_cast<std::uint64_t>(quadtree.gridHeight(d));
    setTable(mLayout.offsets, d, static_cast<std::uint32_t>(nodes));
    setTable(mLayout.bitOffsets, d, static_cast<std::uint32_t>(bits));
    nodes += count;
    bits += d < c.maxDepth ? count : 0;
    widest = std::max(widest, count);
  }
  if (nodes > (std::uint64_t{1} << 31)) {
    fail("GPU selection: {} quadtree nodes are too many for one buffer", nodes);
  }
  // A level's candidates are at most its node count; leaves at most the deepest level's.
  mCapacity = static_cast<std::uint32_t>(std::max<std::uint64_t>(widest, 4));
  mMaxLeaves = mCapacity;
  mTree = gl::Buffer(static_cast<std::size_t>(nodes) * sizeof(gpu::TerrainSelectNode));
  mLists = gl::Buffer(2 * static_cast<std::size_t>(mCapacity) * 2 * sizeof(std::uint32_t));
  mSplit = gl::Buffer(std::max<std::size_t>(4, static_cast<std::size_t>((bits + 31) / 32) * 4));
  mNodes = gl::Buffer(static_cast<std::size_t>(mMaxLeaves) * sizeof(gpu::TerrainNode));
  if (epoxy_has_gl_extension("GL_ARB_timer_query") || epoxy_gl_version() >= 33) {
    mTimer = gl::Query(GL_TIME_ELAPSED);
  }
  upload();
}

void GpuQuadtreeSelection::upload() {
  const QuadtreeConfig& c = mQuadtree.config();
  std::vector<gpu::TerrainSelectNode> data;
  data.reserve(mTree.size() / sizeof(gpu::TerrainSelectNode));
  for (int d = 0; d <= c.maxDepth; ++d) {
    for (int z = 0; z < mQuadtree.gridHeight(d); ++z) {
      for (int x = 0; x < mQuadtree.gridWidth(d); ++x) {
        const NodeId id{d, x, z};
        const HeightRange own = mQuadtree.nodeRange(id);
        const HeightRange lod = mQuadtree.lodBoxRange(id);
        gpu::TerrainSelectNode n{};
        // Absent nodes keep min > max, which the shader reads as absent (NaN compares false too).
        n.range =
            own.present() ? glm::vec4(own.min, own.max, lod.min, lod.max) : glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
        n.error = glm::vec4(mQuadtree.lodRuleError(id), 0.0f, 0.0f, 0.0f);
        data.push_back(n);
      }
    }
  }
  mTree.setSubData(0, data.size() * sizeof(gpu::TerrainSelectNode), data.data());
  mUploadedRestrict = c.restrictSelection;
  mUploadedErrors = mQuadtree.hasNodeErrors();
}

void GpuQuadtreeSelection::select(const glm::vec3& cameraPos, const Frustum* frustum) {
  const QuadtreeConfig& c = mQuadtree.config();
  if (c.restrictSelection != mUploadedRestrict || mQuadtree.hasNodeErrors() != mUploadedErrors) {
    upload();
  }
  mCamera = cameraPos;
  gpu::TerrainSelectParams p = mLayout;
  p.camera = glm::vec4(cameraPos, c.rootSize);
  const bool errorLod = c.lodErrorPixels > 0.0f;
  p.lod = glm::vec4(c.lodDistanceFactor, errorLod ? c.pixelsPerRadian / c.lodErrorPixels : 0.0f,
                    kErrorLodDistanceFloor, static_cast<float>(c.patchTessLevel));
  p.grid = glm::ivec4(c.rootsX, c.rootsZ, c.maxDepth, c.lodEnabled ? c.maxDepth : 0);
  const bool cull = frustum != nullptr && c.frustumCull;
  p.flags = glm::ivec4(cull ? 1 : 0, c.method != CrackMethod::None ? 1 : 0, static_cast<int>(mCapacity), 0);
  if (cull) {
    for (int i = 0; i < 6; ++i) {
      p.planes[i] = frustum->planes()[static_cast<std::size_t>(i)];
    }
  }
  mParams.setSubData(0, sizeof(p), &p);
  mSplit.clear();
  mTree.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TERRAIN_SELECT_NODE_BINDING);
  mParams.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TERRAIN_SELECT_PARAMS_BINDING);
  mLists.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TERRAIN_SELECT_LIST_BINDING);
  mSplit.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TERRAIN_SELECT_SPLIT_BINDING);
  mCounters.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TERRAIN_SELECT_COUNTER_BINDING);
  mNodes.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TERRAIN_NODE_BINDING);
  mProgram.use();
  if (mTimer) {
    mTimer.begin();
  }
  glDispatchCompute(1, 1, 1);
  if (mTimer) {
    mTimer.end();
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::uint32_t GpuQuadtreeSelection::leafCount() const {
  gpu::TerrainSelectCounters counters{};
  mCounters.getSubData(0, sizeof(counters), &counters);
  return counters.draw.y;
}

std::uint32_t GpuQuadtreeSelection::overflow() const {
  gpu::TerrainSelectCounters counters{};
  mCounters.getSubData(0, sizeof(counters), &counters);
  return counters.lists.z;
}

std::vector<gpu::TerrainNode> GpuQuadtreeSelection::readNodes() const {
  std::vector<gpu::TerrainNode> out(std::min(leafCount(), mMaxLeaves));
  if (!out.empty()) {
    mNodes.getSubData(0, out.size() * sizeof(gpu::TerrainNode), out.data());
  }
  return out;
}

double GpuQuadtreeSelection::lastGpuMs() const {
  if (!mTimer) {
    return 0.0;
  }
  const auto ns = mTimer.result(true);
  return ns ? static_cast<double>(*ns) * 1e-6 : 0.0;
}

} // namespace sylva::terrain

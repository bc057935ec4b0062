#pragma once

#include <sylva/core/Geometry.hpp>
#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Query.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/terrain/Quadtree.hpp>

#include <shared/Terrain.h>

#include <glm/glm.hpp>

#include <vector>

/**
 * Quadtree LOD selection on the GPU (shaders/terrain/select.comp): the traversal, frustum culling, the split
 * rule (distance or screen-space error) and the edge levels in one compute dispatch, writing the patch
 * records TerrainRenderer draws and their DrawArraysIndirect command. The CPU Quadtree stays the reference:
 * the GPU selects exactly its leaves with exactly its edge levels (TerrainGpuSelectionTest), in another
 * order. See docs/terrain-lod.md, "GPU selection". Spaces as in Quadtree: world metres, y up.
 */
namespace sylva::terrain {

/** GPU selection for one Quadtree. Needs a current GL context; the quadtree must outlive it. */
class GpuQuadtreeSelection {
public:
  /**
   * Uploads `quadtree`'s per-node data (height ranges, LOD box ranges, errors). Throws sylva::Error when the
   * tree is deeper than the shader's tables (SYLVA_TERRAIN_SELECT_MAX_DEPTH).
   */
  GpuQuadtreeSelection(const shader::Library& library, const Quadtree& quadtree);

  /**
   * Selects the leaves for a camera at `cameraPos` (world metres) with the quadtree's current config,
   * culling against `frustum` when it is not null and the config culls. Re-uploads the per-node data when
   * the config's restriction or errors changed. Results stay on the GPU (nodes(), command()).
   */
  void select(const glm::vec3& cameraPos, const Frustum* frustum);

  /** The quadtree whose config and node data the selection uses. */
  const Quadtree& quadtree() const { return mQuadtree; }
  /** Camera position of the last select(), world metres (geomorphing follows it). */
  const glm::vec3& camera() const { return mCamera; }
  /** The patch records of the last select(): TerrainNode per leaf, in the first leafCount() slots. */
  const gl::Buffer& nodes() const { return mNodes; }
  /** The DrawArraysIndirect command (4 control points, one instance per leaf) at offset 0 of this buffer. */
  const gl::Buffer& command() const { return mCounters; }
  /** Reads the leaf count back (waits for the GPU). */
  std::uint32_t leafCount() const;
  /** Reads the leaves' patch records back (waits for the GPU), for tests and tools. */
  std::vector<gpu::TerrainNode> readNodes() const;
  /** Candidates dropped because a level's list was full in the last select() (0: the selection is whole). */
  std::uint32_t overflow() const;
  /** GPU time of the last select(), milliseconds (waits for the query; 0 without timer queries). */
  double lastGpuMs() const;

private:
  void upload();

  const Quadtree& mQuadtree;
  gl::Program mProgram;
  gl::Buffer mTree{gl::NoCreate};
  gl::Buffer mParams;
  gl::Buffer mLists{gl::NoCreate};
  gl::Buffer mSplit{gl::NoCreate};
  gl::Buffer mCounters;
  gl::Buffer mNodes{gl::NoCreate};
  gl::Query mTimer{gl::NoCreate};
  gpu::TerrainSelectParams mLayout{};
  glm::vec3 mCamera{0.0f};
  std::uint32_t mCapacity = 0;
  std::uint32_t mMaxLeaves = 0;
  bool mUploadedRestrict = true;
  bool mUploadedErrors = false;
};

} // namespace sylva::terrain

#pragma once
// Foliage on the GPU (seed 000 §6, docs/trees.md "Foliage"): 2.5D leaf-cloud impostors in two passes.
// Pass 1 (bake) renders the leaf cloud (and the needle cloud when a species is a conifer: FoliageKind)
// orthographically along the camera's view direction into an RGBA8 texture each: lit colour in RGB, the depth
// across the cloud's unit sphere in A (Foliage.hpp: encodeFoliageDepth; the nearest leaf wins through the
// bake's own depth buffer); it runs again only when the view direction (or the sun) changes. Pass 2 (draw)
// draws one camera-facing billboard per anchor, instanced, on the front plane of the anchor's sphere,
// positioned from the joint frames the trees draw with (so it moves in the wind); each fragment writes the
// depth of the leaf its texel shows (layout(depth_greater)), so billboards are depth-tested against each
// other and against the bark, and dissolves in the far field exactly like its tree's pieces. Needs a current
// GL context.

#include <sylva/core/Image.hpp>
#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/trees/Foliage.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>

#include <cstddef>
#include <memory>
#include <vector>

namespace sylva::trees {

/** Counts for stats panels and benchmarks. */
struct FoliageStats {
  /** Billboards drawn per frame (one per foliage-bearing piece instance). */
  std::size_t anchors = 0;
  /** Side of the cloud texture, texels. */
  int textureSize = 0;
  /** Triangles of the leaf cloud baked. */
  std::size_t leafTriangles = 0;
  /** Times pass 1 has run since construction. */
  std::size_t bakes = 0;
};

/** A forest's foliage on the GPU. */
class FoliageRenderer {
public:
  /**
   * Anchors from `forest` (foliageAnchors), the procedural cloud of settings.cloud and the procedural leaf
   * image (makeLeafImage); throws sylva::Error for invalid settings or too many species colours.
   */
  FoliageRenderer(const shader::Library& library, std::shared_ptr<const Forest> forest,
                  const FoliageSettings& settings = {});

  /** Recompiles the programs (viewer hot reload); keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);

  /** Replaces the leaf image (RGBA8, sRGB colour, alpha-tested at 0.5); the next bake() redraws. */
  void setLeafTexture(const Image& image);
  /** Replaces the leaf cloud (validated: inside the unit sphere); the next bake() redraws. */
  void setLeafCloud(const LeafCloud& cloud);

  /**
   * Pass 1: re-renders the cloud texture when `camera`'s view direction or up vector or the sun differs from
   * the last bake (or something changed); returns whether it did. Restores the framebuffer binding, viewport
   * and the depth, blend and cull state it changes. Throws sylva::Error for a camera whose target is its
   * position.
   */
  bool bake(const render::Camera& camera, const render::Environment& environment = {},
            render::GpuTimers* timers = nullptr);

  /**
   * Pass 2: draws every billboard into the bound framebuffer (depth test on, depth written) with the joint
   * frames and tree centres of `trees` (the same frames its pieces use: wind moves both), fog from
   * `environment`, the far-field dissolve of `lod.farRange`. The billboards face the direction of the last
   * bake; call bake(camera) first (draw bakes itself only when nothing is baked yet or something changed).
   */
  void draw(const render::Camera& camera, int width, int height, double time, const TreeRenderer& trees,
            const TreeLod& lod, render::GpuTimers* timers = nullptr,
            const render::Environment& environment = {});

  /** The cloud texture (rgb: lit colour code, a: depth code; nearest filtering), e.g. for tests and panels.
   */
  const gl::Texture& cloudTexture() const { return mLeaves.colour; }
  /** The needle cloud's texture, the same way (1 × 1 and never baked when no species has needles). */
  const gl::Texture& needleTexture() const { return mNeedles.colour; }
  /** The basis of the last bake. */
  const FoliageBasis& basis() const { return mBasis; }
  /** The billboards, one per foliage-bearing piece instance. */
  const std::vector<FoliageAnchor>& anchors() const { return mAnchors; }
  /** The settings the foliage was made with. */
  const FoliageSettings& settings() const { return mSettings; }
  /** Counts for stats panels and benchmarks. */
  FoliageStats stats() const;
  /** Bytes of GPU memory held. */
  std::size_t gpuBytes() const;

private:
  void uploadUniforms(const render::Environment& environment, const TreeLod& lod, bool leafImage = true);

  /** A cloud's baked texture and the target it is baked in. */
  struct CloudTarget {
    CloudTarget() = default;
    CloudTarget(int size, const char* label);
    gl::Texture colour{gl::NoCreate};
    gl::Texture depth{gl::NoCreate};
    gl::Framebuffer target{gl::NoCreate};
  };

  std::shared_ptr<const Forest> mForest;
  FoliageSettings mSettings;
  std::vector<FoliageAnchor> mAnchors;
  gl::Program mBake{gl::NoCreate};
  gl::Program mDraw{gl::NoCreate};
  gl::Buffer mVertices{gl::NoCreate};
  std::size_t mVertexCount = 0;
  gl::Buffer mAnchorBuffer{gl::NoCreate};
  gl::Buffer mUniforms;
  gl::Texture mLeaf{gl::NoCreate};
  std::size_t mLeafTexels = 0;
  glm::vec3 mLeafMean{1.0f};
  CloudTarget mLeaves;
  CloudTarget mNeedles;
  gl::Buffer mNeedleVertices{gl::NoCreate};
  std::size_t mNeedleCount = 0;
  gl::VertexArray mNeedleVao;
  bool mHasLeaves = false;
  bool mHasNeedles = false;
  gl::VertexArray mCloudVao;
  gl::VertexArray mEmptyVao;
  render::FrameBinding mFrame; ///< the frame path's block, or its own when drawn alone
  FoliageBasis mBasis;
  glm::vec3 mBakedSun{0.0f};
  float mBakedSunIntensity = -1.0f;
  bool mDirty = true;
  std::size_t mBakes = 0;
  gpu::FoliageUniforms mLast{};
};

} // namespace sylva::trees

#pragma once
// Far-field octahedral impostors (docs/trees.md "Far field"): every species is baked once from views × views
// directions over the upper hemisphere (hemi-octahedral grid, sylva/trees/FarField.hpp) into one layer of two
// texture arrays: albedo + coverage, and object-space normal + depth. Far trees are then drawn as one
// instanced draw of camera-facing billboards that blend the three nearest baked views per pixel (each sampled
// where the pixel's ray meets its own view plane, refined by the baked depth), write the baked depth, are lit
// like the pieces and dissolve with the complement of the pieces' screen-door mask in the far range's band.
// Needs a current GL context.

#include <sylva/core/Image.hpp>
#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/Export.hpp>
#include <sylva/trees/FarField.hpp>
#include <sylva/trees/Foliage.hpp>
#include <sylva/trees/Forest.hpp>

#include <shared/Trees.h>

#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace sylva::trees {

class TreeRenderer;

/** Atlas and draw settings. */
struct ImpostorSettings {
  /** Views per side and cell pixels (the atlas layer is views · cell square). */
  ImpostorLayout layout{};
  /** Blended coverage below this is discarded. */
  float alphaThreshold = 0.35f;
  /** Refine each view's sample by its baked depth (parallax); false: one sample on the view plane. */
  bool depthParallax = true;
  /** The bounding sphere is grown by this factor, so nothing of the tree touches a cell's edge. */
  float sphereMargin = 1.05f;
  /** Fixed tessellation level of the pieces in the bake (≤ 8 on llvmpipe). */
  float bakeLevel = 4.0f;
};

/** Optional hooks of a bake. */
struct ImpostorBakeOptions {
  /** Called once per species on the one-tree renderer before its views are drawn (e.g. setBark). */
  std::function<void(TreeRenderer&)> prepare;
  /**
   * Draws more of the tree (foliage) into each view after the pieces: the view's camera and size; draw with
   * impostorBakeEnvironment() so the albedo can be recovered.
   */
  std::function<void(const render::Camera&, int width, int height)> extra;
};

/** The light of a bake: no sun, no fog (the colour is albedo times the sky light of the normal). */
render::Environment impostorBakeEnvironment();

/**
 * Bake hooks that draw each species' tree as a scene does: with `bark` (one set per source, `speciesSet` per
 * species; empty: flat colours) and, with `foliage`, leaf-cloud impostors of `leafImage` / `cloud` (null:
 * procedural). The hooks own copies of everything they need.
 */
ImpostorBakeOptions sceneBakeOptions(const shader::Library& library, std::vector<BarkSet> bark,
                                     std::vector<int> speciesSet, bool foliage,
                                     const Image* leafImage = nullptr, const LeafCloud* cloud = nullptr);

/** What bakeTreeImpostor() bakes (`tree export --impostor`). */
struct TreeImpostorBake {
  int views = 8;  ///< views per side of the hemi-octahedral grid
  int cell = 128; ///< pixels per view
  /** Bake the foliage into the views. */
  bool foliage = true;
  /** The bark tiles the tree is drawn with; none: flat bark colour. */
  std::optional<BarkSet> bark;
  /** The leaf picture of the foliage (null: the procedural leaf). */
  const Image* leafImage = nullptr;
};

/**
 * Bakes the impostor atlas of exactly one tree (its topology and pose, metres per rim unit `scale`) as a
 * scene bakes a species: hemi-octahedral views with bark tiles and foliage. Needs a current GL context.
 * Returns the atlas (RGBA8, file order) with the sphere its views frame, in metres.
 */
ImpostorAtlas bakeTreeImpostor(const shader::Library& library, const PieceSet& pieces, const Species& species,
                               const TreeTopology& topology, const std::vector<glm::vec2>& pose, float scale,
                               const TreeImpostorBake& bake);

/** Far trees as hemi-octahedral impostors: bakes each species' views into a texture array, culls and draws
 * the far trees in one indirect draw, leaning in the wind. */
class ImpostorRenderer {
public:
  /** The renderer's programs and its atlas array sized by `settings`; needs a current context. */
  ImpostorRenderer(const shader::Library& library, const ImpostorSettings& settings = {});

  /** Recompiles the programs (keeps the old ones and throws on error); later bakes use this library. */
  void reloadShaders(const shader::Library& library);

  /**
   * Bakes every species of `forest` (at most SYLVA_TREE_MAX_SPECIES): species s from the forest's first tree
   * of that species (re-placed at the origin, unturned), or from a generated tree when it has none. Replaces
   * the atlas. Leaves the default framebuffer bound with the viewport unchanged.
   */
  void bake(const Forest& forest, const ImpostorBakeOptions& options = {});

  /** The far trees to draw (instance buffer; grows as needed). */
  void setTrees(std::span<const FarTree> trees);
  /** Far trees set. */
  std::size_t treeCount() const { return mTreeCount; }

  /**
   * Culls the far trees on the GPU (a compute pass writing the visible list and the instance count of one
   * indirect draw) and draws them into the bound framebuffer (depth test and writes on): trees with pieces
   * from farRange.x on (dissolving in until farRange.y), far-only trees at any distance (impostorVisible()).
   */
  void draw(const render::Camera& camera, int width, int height, double time, glm::vec2 farRange,
            render::GpuTimers* timers = nullptr, const render::Environment& environment = {});

  /**
   * The wind the far trees lean in from the next draw on (its flow.w: the wind's clock, s; flow.z 0: upright,
   * the default). Each species leans by its ImpostorSway, calibrated at bake() on the tree it bakes.
   */
  void setWind(const gpu::WindUniforms& wind) { mWind = wind; }
  /** Species s's sway (ImpostorSway; zeros before bake()). */
  ImpostorSway speciesSway(int species) const;

  /** Trees the last draw's cull kept (synchronous readback). */
  std::uint32_t readVisibleCount() const;

  /** The settings the renderer was made with. */
  const ImpostorSettings& settings() const { return mSettings; }
  /** Species baked. */
  int speciesCount() const { return mSpecies; }
  /** Species s's bounding sphere: centre relative to the base (xyz) and radius (w), in crown heights. */
  glm::vec4 speciesSphere(int species) const;
  /** Albedo (sRGB, premultiplied by coverage) + coverage, one layer per species. */
  const gl::Texture& atlasColour() const { return mColour; }
  /** Object-space normal (0.5 + 0.5 n) + depth (0.5 + 0.5 · offset / radius), premultiplied by coverage. */
  const gl::Texture& atlasNormal() const { return mNormal; }
  /** Species s's colour atlas (RGBA8, file order: top row first) for export and pictures. */
  Image readAtlas(int species) const;
  /** Species s's normal + depth atlas (RGBA8, file order). */
  Image readAtlasNormal(int species) const;
  /** Bytes of GPU memory held (atlas with mips, instances, uniforms). */
  std::size_t gpuBytes() const;

private:
  void bakeSpecies(const Forest& forest, int species, const ImpostorBakeOptions& options);

  const shader::Library* mLibrary;
  ImpostorSettings mSettings;
  gl::Program mDraw{gl::NoCreate};
  gl::Program mResolve{gl::NoCreate};
  gl::Program mCull{gl::NoCreate};
  gl::Buffer mVisible{gl::NoCreate};
  gl::Buffer mCommand;
  gl::Texture mColour{gl::NoCreate};
  gl::Texture mNormal{gl::NoCreate};
  int mLevels = 1;
  int mSpecies = 0;
  std::vector<glm::vec4> mSpheres;
  std::vector<ImpostorSway> mSway;
  gpu::WindUniforms mWind{};
  gl::Buffer mInstances{gl::NoCreate};
  std::size_t mTreeCount = 0;
  gl::Buffer mUniforms;
  gl::VertexArray mVao;
  render::FrameBinding mFrame; ///< the frame path's block, or its own when drawn alone
};

/** Packs far trees as the GPU reads them. */
std::vector<gpu::ImpostorInstanceGpu> packImpostors(std::span<const FarTree> trees);

} // namespace sylva::trees

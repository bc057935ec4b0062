#include <sylva/trees/gpu/FoliageRenderer.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/shader/Compiler.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sylva::trees {
namespace {

/** Lit leaf colours reach about 2 (albedo × (sun + sky)); the bake stores srgb(lit · 0.5). */
constexpr float kColourScale = 0.5f;

/** GL state the passes change and give back. */
class SavedState {
public:
  SavedState() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &mFramebuffer);
    glGetIntegerv(GL_VIEWPORT, mViewport);
    mDepthTest = glIsEnabled(GL_DEPTH_TEST);
    mBlend = glIsEnabled(GL_BLEND);
    mCull = glIsEnabled(GL_CULL_FACE);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &mDepthMask);
    glGetIntegerv(GL_DEPTH_FUNC, &mDepthFunc);
    glGetBooleanv(GL_COLOR_WRITEMASK, mColourMask);
  }
  ~SavedState() {
    glColorMask(mColourMask[0], mColourMask[1], mColourMask[2], mColourMask[3]);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(mFramebuffer));
    glViewport(mViewport[0], mViewport[1], mViewport[2], mViewport[3]);
    set(GL_DEPTH_TEST, mDepthTest);
    set(GL_BLEND, mBlend);
    set(GL_CULL_FACE, mCull);
    glDepthMask(mDepthMask);
    glDepthFunc(static_cast<GLenum>(mDepthFunc));
  }
  SavedState(const SavedState&) = delete;
  SavedState& operator=(const SavedState&) = delete;

private:
  static void set(GLenum cap, GLboolean on) {
    if (on == GL_TRUE) {
      glEnable(cap);
    } else {
      glDisable(cap);
    }
  }
  GLint mFramebuffer = 0;
  GLint mViewport[4] = {0, 0, 0, 0};
  GLboolean mDepthTest = GL_FALSE;
  GLboolean mBlend = GL_FALSE;
  GLboolean mCull = GL_FALSE;
  GLboolean mDepthMask = GL_TRUE;
  GLint mDepthFunc = GL_LESS;
  GLboolean mColourMask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
};

/** Points `vao` at a buffer of LeafVertex. */
void formatCloud(const gl::VertexArray& vao, const gl::Buffer& vertices) {
  const GLuint id = vao.id();
  glVertexArrayVertexBuffer(id, 0, vertices.id(), 0, sizeof(LeafVertex));
  glVertexArrayAttribFormat(id, 0, 3, GL_FLOAT, GL_FALSE, offsetof(LeafVertex, position));
  glVertexArrayAttribFormat(id, 1, 3, GL_FLOAT, GL_FALSE, offsetof(LeafVertex, normal));
  glVertexArrayAttribFormat(id, 2, 2, GL_FLOAT, GL_FALSE, offsetof(LeafVertex, uv));
  glVertexArrayAttribFormat(id, 3, 3, GL_FLOAT, GL_FALSE, offsetof(LeafVertex, tint));
  for (GLuint a = 0; a < 4; ++a) {
    glVertexArrayAttribBinding(id, a, 0);
    glEnableVertexArrayAttrib(id, a);
  }
}

} // namespace

FoliageRenderer::CloudTarget::CloudTarget(int size, const char* label) {
  colour = gl::Texture::create2D(GL_RGBA8, size, size);
  // Nearest texels: the alpha is a depth code, and blending codes of neighbours (or with empty texels) would
  // invent depths no leaf has.
  colour.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
  depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, size, size);
  target = gl::Framebuffer{};
  target.attachColor(0, colour);
  target.attachDepth(depth);
  target.checkComplete();
  gl::setLabel(GL_TEXTURE, colour.id(), label);
}

FoliageRenderer::FoliageRenderer(const shader::Library& library, std::shared_ptr<const Forest> forest,
                                 const FoliageSettings& settings)
    : mForest(std::move(forest)), mSettings(settings), mUniforms(sizeof(gpu::FoliageUniforms)) {
  validate(mSettings, "foliage");
  mAnchors = foliageAnchors(*mForest, mSettings);
  std::vector<gpu::FoliageAnchorGpu> packed;
  packed.reserve(std::max<std::size_t>(mAnchors.size(), 1));
  for (const FoliageAnchor& a : mAnchors) {
    packed.push_back(packAnchor(a));
  }
  if (packed.empty()) {
    packed.push_back(gpu::FoliageAnchorGpu{});
  }
  mAnchorBuffer = gl::Buffer{std::span<const gpu::FoliageAnchorGpu>(packed)};
  gl::setLabel(GL_BUFFER, mAnchorBuffer.id(), "foliage anchors");

  for (const Species& species : mForest->species) {
    (species.foliage == FoliageKind::Needles ? mHasNeedles : mHasLeaves) = true;
  }
  mHasLeaves = mHasLeaves || mForest->species.empty();
  const int size = mSettings.textureSize;
  mLeaves = CloudTarget(size, "foliage cloud");
  // Conifers' needle sprays: baked only when a species has them (the texture stays for the sampler).
  mNeedles = CloudTarget(mHasNeedles ? size : 1, "foliage needles");
  const LeafCloud needles = makeNeedleCloud(mSettings.needles);
  mNeedleVertices = gl::Buffer{std::span<const LeafVertex>(needles.vertices)};
  mNeedleCount = needles.vertices.size();
  formatCloud(mNeedleVao, mNeedleVertices);

  setLeafCloud(makeLeafCloud(mSettings.cloud));
  setLeafTexture(makeLeafImage(128));
  reloadShaders(library);
}

void FoliageRenderer::reloadShaders(const shader::Library& library) {
  gl::Program bake =
      shader::compileProgram(library, {"foliage bake", {"trees/leafcloud.vert", "trees/leafcloud.frag"}, {}});
  gl::Program draw =
      shader::compileProgram(library, {"foliage draw", {"trees/foliage.vert", "trees/foliage.frag"}, {}});
  mBake = std::move(bake);
  mDraw = std::move(draw);
  mDirty = true;
}

void FoliageRenderer::setLeafTexture(const Image& image) {
  const glm::vec3 mean = leafImageMean(image); // checks the format
  const int levels =
      static_cast<int>(std::floor(std::log2(static_cast<float>(std::max(image.width(), image.height()))))) +
      1;
  gl::Texture leaf = gl::Texture::create2D(GL_SRGB8_ALPHA8, image.width(), image.height(), levels);
  leaf.upload(image);
  leaf.setSampler({GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE});
  leaf.generateMipmaps();
  gl::setLabel(GL_TEXTURE, leaf.id(), "foliage leaf");
  mLeaf = std::move(leaf);
  mLeafTexels = static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height());
  // Every channel at least a little: the species colour is divided by it.
  mLeafMean = glm::max(mean, glm::vec3(1e-3f));
  mDirty = true;
}

void FoliageRenderer::setLeafCloud(const LeafCloud& cloud) {
  validate(cloud, "leaf cloud");
  mVertices = gl::Buffer{std::span<const LeafVertex>(cloud.vertices)};
  mVertexCount = cloud.vertices.size();
  formatCloud(mCloudVao, mVertices);
  mDirty = true;
}

void FoliageRenderer::uploadUniforms(const render::Environment& environment, const TreeLod& lod,
                                     bool leafImage) {
  gpu::FoliageUniforms& u = mLast;
  u.bake = foliageBakeMatrix(mBasis);
  u.forward = glm::vec4(mBasis.forward, static_cast<float>(mAnchors.size()));
  u.right = glm::vec4(mBasis.right, kColourScale);
  u.up = glm::vec4(mBasis.up, leafImage ? 1.0f : 0.0f);
  u.sun = glm::vec4(glm::normalize(environment.sunDirection), environment.sunIntensity);
  u.far = glm::vec4(lod.farRange, lod.drawDistance, 0.0f);
  const std::vector<Species>& species = mForest->species;
  for (std::size_t k = 0; k < SYLVA_TREE_MAX_SPECIES; ++k) {
    // Species beyond the table share its last colour (the shader clamps the index the same way).
    const Species& s = species.empty() ? Species{} : species[std::min(k, species.size() - 1)];
    // Needles are cards of their own (no leaf image to divide out); w tells the draw which cloud to read.
    const bool needles = s.foliage == FoliageKind::Needles;
    u.leafColours[k] = glm::vec4(needles ? s.leafColour : s.leafColour / mLeafMean, needles ? 1.0f : 0.0f);
  }
  mUniforms.setSubData(0, sizeof(u), &u);
}

bool FoliageRenderer::bake(const render::Camera& camera, const render::Environment& environment,
                           render::GpuTimers* timers) {
  const glm::vec3 view = camera.target - camera.position;
  if (!(glm::length(view) > 0.0f) || !std::isfinite(glm::length(view))) {
    fail("foliage: the camera has no view direction (target equals position)");
  }
  const FoliageBasis basis = foliageBasis(view, camera.up);
  const glm::vec3 sun = glm::normalize(environment.sunDirection);
  if (!mDirty && basis.forward == mBasis.forward && basis.up == mBasis.up && sun == mBakedSun &&
      environment.sunIntensity == mBakedSunIntensity) {
    return false;
  }
  const render::GpuTimerScope timed(timers, "foliage bake");
  mBasis = basis;
  mBakedSun = sun;
  mBakedSunIntensity = environment.sunIntensity;
  {
    const SavedState saved;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE); // leaves are two-sided
    // A bake can run inside a depth-only pass (a shadow cascade turns colour writes off): the cloud texture
    // must be written whatever the caller's mask, or it keeps an older view's leaves.
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_TREE_FOLIAGE_UNIFORM_BINDING);
    mLeaf.bind(SYLVA_TREE_LEAF_UNIT);
    mBake.use();
    auto pass = [&](CloudTarget& cloud, const gl::VertexArray& vao, std::size_t vertices, bool leafImage) {
      uploadUniforms(environment, TreeLod{}, leafImage);
      cloud.target.bindForDraw(mSettings.textureSize, mSettings.textureSize);
      cloud.target.clearColor(0, glm::vec4(0.0f));
      cloud.target.clearDepth(1.0f);
      vao.bind();
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices));
    };
    if (mHasLeaves) {
      pass(mLeaves, mCloudVao, mVertexCount, true);
    }
    if (mHasNeedles) {
      pass(mNeedles, mNeedleVao, mNeedleCount, false);
    }
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  mDirty = false;
  ++mBakes;
  return true;
}

void FoliageRenderer::draw(const render::Camera& camera, int width, int height, double time,
                           const TreeRenderer& trees, const TreeLod& lod, render::GpuTimers* timers,
                           const render::Environment& environment) {
  if (&trees.forest() != mForest.get()) {
    fail("foliage: drawn with the tree renderer of another forest");
  }
  if (mAnchors.empty()) {
    return;
  }
  if (mBakes == 0 || mDirty) {
    // Never draw an unbaked (undefined) texture.
    bake(camera, environment, timers);
  }
  const render::GpuTimerScope timed(timers, "foliage");
  uploadUniforms(environment, lod);
  {
    const SavedState saved;
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND); // alpha is the depth code, never coverage
    glDisable(GL_CULL_FACE);
    mFrame.bind(camera, width, height, time, environment);
    mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_TREE_FOLIAGE_UNIFORM_BINDING);
    trees.framesBuffer().bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_JOINT_BINDING);
    trees.centresBuffer().bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_CENTRE_BINDING);
    mAnchorBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_FOLIAGE_BINDING);
    mLeaves.colour.bind(SYLVA_TREE_FOLIAGE_UNIT);
    mNeedles.colour.bind(SYLVA_TREE_NEEDLE_UNIT);
    mDraw.use();
    mEmptyVao.bind();
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(mAnchors.size()));
  }
}

FoliageStats FoliageRenderer::stats() const {
  return FoliageStats{mAnchors.size(), mSettings.textureSize,
                      (mHasLeaves ? mVertexCount / 3 : 0) + (mHasNeedles ? mNeedleCount / 3 : 0), mBakes};
}

std::size_t FoliageRenderer::gpuBytes() const {
  const auto side = static_cast<std::size_t>(mSettings.textureSize);
  // Cloud colour and its depth buffer; the leaf image with its mip chain (4/3 of the base level).
  const std::size_t leaf = mLeafTexels * 4 * 4 / 3;
  return side * side * 8 * (mHasNeedles ? 2 : 1) + leaf + (mVertexCount + mNeedleCount) * sizeof(LeafVertex) +
         std::max<std::size_t>(mAnchors.size(), 1) * sizeof(gpu::FoliageAnchorGpu) +
         sizeof(gpu::FoliageUniforms);
}

} // namespace sylva::trees

#include <sylva/trees/gpu/ImpostorRenderer.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/shader/Compiler.hpp>
#include <sylva/trees/gpu/FoliageRenderer.hpp>
#include <sylva/trees/Tree.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>

namespace sylva::trees {
namespace {

/** The bake camera stands this many bounding radii away: a field of view of 0.57°, nearly orthographic (the
 * far side of the sphere is drawn 1 % smaller than the near side). */
constexpr float kBakeDistance = 200.0f;

} // namespace

render::Environment impostorBakeEnvironment() {
  render::Environment e;
  e.sunIntensity = 0.0f;
  e.fogDensity = 0.0f;
  return e;
}

std::vector<gpu::ImpostorInstanceGpu> packImpostors(std::span<const FarTree> trees) {
  std::vector<gpu::ImpostorInstanceGpu> out(trees.size());
  for (std::size_t i = 0; i < trees.size(); ++i) {
    const FarTree& t = trees[i];
    out[i].placement = glm::vec4(t.position, t.height);
    out[i].info =
        glm::uvec4(t.id, static_cast<std::uint32_t>(std::max(t.species, 0)),
                   std::bit_cast<std::uint32_t>(t.yaw), t.farOnly ? SYLVA_TREE_IMPOSTOR_FAR_ONLY : 0u);
  }
  return out;
}

ImpostorRenderer::ImpostorRenderer(const shader::Library& library, const ImpostorSettings& settings)
    : mLibrary(&library), mSettings(settings), mCommand(4 * sizeof(std::uint32_t)),
      mUniforms(sizeof(gpu::ImpostorUniforms)) {
  if (settings.layout.views < 2 || settings.layout.views > 64 || settings.layout.cell < 8 ||
      settings.layout.cell > 1024 || settings.layout.side() > 8192) {
    fail("impostors: {} views of {} pixels (2 … 64 views, 8 … 1024 pixels, at most 8192 per side)",
         settings.layout.views, settings.layout.cell);
  }
  reloadShaders(library);
}

void ImpostorRenderer::reloadShaders(const shader::Library& library) {
  gl::Program draw =
      shader::compileProgram(library, {"tree impostors", {"trees/impostor.vert", "trees/impostor.frag"}, {}});
  gl::Program resolve =
      shader::compileProgram(library, {"tree impostor resolve", {"trees/impostor_bake.comp"}, {}});
  gl::Program cull =
      shader::compileProgram(library, {"tree impostor cull", {"trees/impostor_cull.comp"}, {}});
  mDraw = std::move(draw);
  mResolve = std::move(resolve);
  mCull = std::move(cull);
  mLibrary = &library;
}

ImpostorSway ImpostorRenderer::speciesSway(int species) const {
  return species >= 0 && static_cast<std::size_t>(species) < mSway.size()
             ? mSway[static_cast<std::size_t>(species)]
             : ImpostorSway{};
}

glm::vec4 ImpostorRenderer::speciesSphere(int species) const {
  return species >= 0 && static_cast<std::size_t>(species) < mSpheres.size()
             ? mSpheres[static_cast<std::size_t>(species)]
             : glm::vec4(0.0f);
}

ImpostorBakeOptions sceneBakeOptions(const shader::Library& library, std::vector<BarkSet> bark,
                                     std::vector<int> speciesSet, bool foliage, const Image* leafImage,
                                     const LeafCloud* cloud) {
  struct State {
    shader::Library library;
    std::vector<BarkSet> bark;
    std::vector<int> speciesSet;
    bool foliage = false;
    std::optional<Image> leaf;
    std::optional<LeafCloud> cloud;
    TreeRenderer* trees = nullptr;
    std::unique_ptr<FoliageRenderer> leaves;
  };
  auto state = std::make_shared<State>();
  state->library = library;
  state->bark = std::move(bark);
  state->speciesSet = std::move(speciesSet);
  state->foliage = foliage;
  if (leafImage != nullptr) {
    state->leaf = *leafImage;
  }
  if (cloud != nullptr) {
    state->cloud = *cloud;
  }
  ImpostorBakeOptions options;
  options.prepare = [state](TreeRenderer& r) {
    state->trees = &r;
    if (!state->bark.empty()) {
      r.setBark(state->bark, state->speciesSet);
    }
    state->leaves.reset();
    if (state->foliage) {
      state->leaves = std::make_unique<FoliageRenderer>(state->library, r.sharedForest());
      if (state->leaf) {
        state->leaves->setLeafTexture(*state->leaf);
      }
      if (state->cloud) {
        state->leaves->setLeafCloud(*state->cloud);
      }
    }
  };
  options.extra = [state](const render::Camera& camera, int width, int height) {
    if (state->leaves && state->trees != nullptr) {
      const render::Environment environment = impostorBakeEnvironment();
      state->leaves->bake(camera, environment);
      state->leaves->draw(camera, width, height, 0.0, *state->trees, TreeLod{}, nullptr, environment);
    }
  };
  return options;
}

void ImpostorRenderer::bake(const Forest& forest, const ImpostorBakeOptions& options) {
  if (forest.species.empty()) {
    fail("impostors: the forest has no species to bake");
  }
  const int species = static_cast<int>(std::min<std::size_t>(forest.species.size(), SYLVA_TREE_MAX_SPECIES));
  const int side = mSettings.layout.side();
  // Mips down to 4-pixel cells: below that, neighbouring views would bleed into each other.
  mLevels = std::max(1, static_cast<int>(std::log2(static_cast<float>(mSettings.layout.cell))) - 1);
  mColour = gl::Texture::create2DArray(GL_SRGB8_ALPHA8, side, side, species, mLevels);
  mNormal = gl::Texture::create2DArray(GL_RGBA8, side, side, species, mLevels);
  gl::setLabel(GL_TEXTURE, mColour.id(), "impostor colour atlas");
  gl::setLabel(GL_TEXTURE, mNormal.id(), "impostor normal atlas");
  mSpecies = species;
  mSpheres.assign(SYLVA_TREE_MAX_SPECIES, glm::vec4(0.0f, 0.5f, 0.0f, 0.6f));
  mSway.assign(SYLVA_TREE_MAX_SPECIES, ImpostorSway{});
  for (int s = 0; s < species; ++s) {
    bakeSpecies(forest, s, options);
  }
  const gl::SamplerState sampler{GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE};
  mColour.setSampler(sampler);
  mNormal.setSampler(sampler);
  mColour.generateMipmaps();
  mNormal.generateMipmaps();
}

void ImpostorRenderer::bakeSpecies(const Forest& forest, int s, const ImpostorBakeOptions& options) {
  const Species& sp = forest.species[static_cast<std::size_t>(s)];
  auto one = std::make_shared<Forest>();
  one->pieces = forest.pieces;
  one->species = forest.species;
  ForestTree tree;
  const auto it = std::find_if(forest.trees.begin(), forest.trees.end(),
                               [&](const ForestTree& t) { return t.species == s; });
  float scale = sp.trunkRadius;
  if (it != forest.trees.end()) {
    tree = *it;
    scale = glm::length(glm::vec3(it->base[0]));
  } else {
    const std::uint64_t seed = 1000u + static_cast<std::uint64_t>(s);
    tree.topology = generateTree(forest.pieces, sp, seed);
    tree.pose = randomPose(tree.topology, sp, seed);
  }
  tree.species = s;
  tree.base = baseFrame(glm::vec3(0.0f), 0.0f, scale);
  one->trees = {tree};
  one->index();
  // Far trees of this species lean as much as this one bends in a steady wind.
  mSway[static_cast<std::size_t>(s)] = calibrateImpostorSway(*one, 0);
  TreeRenderer renderer(*mLibrary, one);
  if (options.prepare) {
    options.prepare(renderer);
  }
  // Bounding sphere: first a loose one around the joints (grown by two rims; rim units are metres · scale),
  // then fitted to what is drawn: the covered pixels of three views (side, side, top) as points.
  std::vector<gpu::JointFrame> frames;
  forestFrames(*one, {}, frames);
  glm::vec3 lo(0.0f);
  glm::vec3 hi(0.0f);
  for (const gpu::JointFrame& f : frames) {
    const glm::vec3 p(f.x.w, f.y.w, f.z.w);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  lo -= glm::vec3(2.0f * scale);
  hi += glm::vec3(2.0f * scale);
  glm::vec3 centre = 0.5f * (lo + hi);
  float radius = 0.5f * glm::length(hi - lo);
  const float height = std::max(treeStats(one->pieces, tree.topology).height * scale, 1e-3f);

  const int cell = mSettings.layout.cell;
  const int views = mSettings.layout.views;
  TreeLod lod;
  lod.fixedLevel = mSettings.bakeLevel;
  TreeDrawOptions drawOptions;
  drawOptions.environment = impostorBakeEnvironment();
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  auto viewCamera = [&](glm::vec3 f) {
    const float distance = kBakeDistance * radius;
    render::Camera camera;
    camera.position = centre + f * distance;
    camera.target = centre;
    camera.up = impostorBasis(f).up;
    camera.fovY = 2.0f * std::atan(radius / distance);
    camera.nearPlane = distance - 1.5f * radius;
    camera.farPlane = distance + 1.5f * radius;
    return camera;
  };
  auto drawView = [&](render::RenderTarget& target, const render::Camera& camera) {
    target.begin(glm::vec4(0.0f));
    renderer.cull(camera, 1.0f, lod);
    renderer.draw(camera, target.width(), target.height(), 0.0, lod, nullptr, drawOptions);
    if (options.extra) {
      options.extra(camera, target.width(), target.height());
    }
  };
  {
    const int fit = std::max(cell, 128);
    render::RenderTarget target(fit, fit);
    std::vector<glm::vec3> points;
    for (const glm::vec3 f : {glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}) {
      const render::Camera camera = viewCamera(f);
      drawView(target, camera);
      const Image depth = target.readDepth();
      const glm::mat4 inverse = glm::inverse(camera.viewProjection(1.0f));
      for (int y = 0; y < fit; ++y) {
        for (int x = 0; x < fit; ++x) {
          const float d = depth.get(x, y, 0);
          if (d < 1.0f) {
            const glm::vec4 ndc((static_cast<float>(x) + 0.5f) / static_cast<float>(fit) * 2.0f - 1.0f,
                                1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(fit) * 2.0f,
                                d * 2.0f - 1.0f, 1.0f);
            const glm::vec4 w = inverse * ndc;
            points.push_back(glm::vec3(w) / w.w);
          }
        }
      }
    }
    if (!points.empty()) {
      glm::vec3 a = points[0];
      glm::vec3 b = points[0];
      for (const glm::vec3& p : points) {
        a = glm::min(a, p);
        b = glm::max(b, p);
      }
      centre = 0.5f * (a + b);
      float r = 0.0f;
      for (const glm::vec3& p : points) {
        r = std::max(r, glm::distance(p, centre));
      }
      // A texel of the fitting views either way, then the margin.
      radius = (r + 2.0f * radius / static_cast<float>(fit)) * mSettings.sphereMargin;
    }
  }
  mSpheres[static_cast<std::size_t>(s)] = glm::vec4(centre / height, radius / height);

  render::RenderTarget target(cell, cell);
  gl::Texture colour = gl::Texture::create2D(GL_RGBA8, cell, cell);
  gl::Texture normal = gl::Texture::create2D(GL_RGBA8, cell, cell);
  const float distance = kBakeDistance * radius;
  render::FrameUniformBuffer bakeFrame; // the bake's own views, never a frame path's
  for (int j = 0; j < views; ++j) {
    for (int i = 0; i < views; ++i) {
      const glm::vec3 f = impostorViewDirection({i, j}, views);
      const ImpostorBasis basis = impostorBasis(f);
      const render::Camera camera = viewCamera(f);
      drawView(target, camera);
      gl::bindDefaultFramebuffer(viewport[2], viewport[3]);
      bakeFrame.update(camera, cell, cell, 0.0, impostorBakeEnvironment());
      bakeFrame.bind();
      mResolve.use();
      const GLuint program = mResolve.id();
      const glm::mat4 inverse = glm::inverse(camera.projection(1.0f));
      const glm::mat3 frame(basis.right, basis.up, basis.forward);
      glProgramUniformMatrix4fv(program, mResolve.uniformLocation("uInverseProjection"), 1, GL_FALSE,
                                glm::value_ptr(inverse));
      glProgramUniformMatrix3fv(program, mResolve.uniformLocation("uBasis"), 1, GL_FALSE,
                                glm::value_ptr(frame));
      glProgramUniform1f(program, mResolve.uniformLocation("uDistance"), distance);
      glProgramUniform1f(program, mResolve.uniformLocation("uRadius"), radius);
      glProgramUniform3fv(program, mResolve.uniformLocation("uCentre"), 1, glm::value_ptr(centre));
      target.color().bind(SYLVA_TREE_IMPOSTOR_SOURCE_UNIT);
      target.depth().bind(SYLVA_TREE_IMPOSTOR_SOURCE_UNIT + 1);
      colour.bindImage(0, GL_WRITE_ONLY);
      normal.bindImage(1, GL_WRITE_ONLY);
      const auto groups = static_cast<GLuint>((cell + SYLVA_TREE_IMPOSTOR_RESOLVE_GROUP - 1) /
                                              SYLVA_TREE_IMPOSTOR_RESOLVE_GROUP);
      glDispatchCompute(groups, groups, 1);
      glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                      GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
      glCopyImageSubData(colour.id(), GL_TEXTURE_2D, 0, 0, 0, 0, mColour.id(), GL_TEXTURE_2D_ARRAY, 0,
                         i * cell, j * cell, s, cell, cell, 1);
      glCopyImageSubData(normal.id(), GL_TEXTURE_2D, 0, 0, 0, 0, mNormal.id(), GL_TEXTURE_2D_ARRAY, 0,
                         i * cell, j * cell, s, cell, cell, 1);
    }
  }
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

void ImpostorRenderer::setTrees(std::span<const FarTree> trees) {
  const std::vector<gpu::ImpostorInstanceGpu> packed = packImpostors(trees);
  const std::size_t bytes = std::max<std::size_t>(packed.size(), 1) * sizeof(gpu::ImpostorInstanceGpu);
  if (mInstances.id() == 0 || mInstances.size() < bytes) {
    mInstances = gl::Buffer(bytes);
    mVisible = gl::Buffer(bytes / sizeof(gpu::ImpostorInstanceGpu) * sizeof(std::uint32_t));
    gl::setLabel(GL_BUFFER, mInstances.id(), "impostor instances");
  }
  if (!packed.empty()) {
    mInstances.setSubData(std::span<const gpu::ImpostorInstanceGpu>(packed));
  }
  mTreeCount = packed.size();
}

void ImpostorRenderer::draw(const render::Camera& camera, int width, int height, double time,
                            glm::vec2 farRange, render::GpuTimers* timers,
                            const render::Environment& environment) {
  if (mTreeCount == 0 || mSpecies == 0) {
    return;
  }
  {
    const render::GpuTimerScope timed(timers, "impostors cull");
    gpu::ImpostorUniforms u{};
    u.atlas = glm::vec4(static_cast<float>(mSettings.layout.views), static_cast<float>(mSettings.layout.cell),
                        mSettings.alphaThreshold, mSettings.depthParallax ? 1.0f : 0.0f);
    u.far = glm::vec4(farRange, 0.0f, 0.0f);
    u.info = glm::uvec4(static_cast<unsigned>(mTreeCount), static_cast<unsigned>(mSpecies), 0u, 0u);
    for (std::size_t s = 0; s < SYLVA_TREE_MAX_SPECIES; ++s) {
      u.sphere[s] = mSpheres[s];
      u.sway[s] = glm::vec4(mSway[s].perSpeedSquared, mSway[s].maxLean, 0.0f, 0.0f);
    }
    u.wind = mWind;
    const Frustum frustum =
        camera.frustum(static_cast<float>(width) / static_cast<float>(std::max(height, 1)));
    for (std::size_t p = 0; p < 6; ++p) {
      u.frustum[p] = frustum.planes()[p];
    }
    mUniforms.setSubData(0, sizeof(u), &u);
    mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_TREE_IMPOSTOR_UNIFORM_BINDING);
    mFrame.bind(camera, width, height, time, environment);
    mInstances.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_IMPOSTOR_BINDING);
    mVisible.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_IMPOSTOR_VISIBLE_BINDING);
    mCommand.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_IMPOSTOR_COMMAND_BINDING);
    const std::uint32_t reset[4] = {4u, 0u, 0u, 0u};
    mCommand.setSubData(0, sizeof(reset), reset);
    mCull.use();
    glDispatchCompute(static_cast<GLuint>((mTreeCount + SYLVA_TREE_IMPOSTOR_CULL_GROUP - 1) /
                                          SYLVA_TREE_IMPOSTOR_CULL_GROUP),
                      1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  }
  const render::GpuTimerScope timed(timers, "impostors");
  mColour.bind(SYLVA_TREE_IMPOSTOR_UNIT);
  mNormal.bind(SYLVA_TREE_IMPOSTOR_NORMAL_UNIT);
  const GLboolean culling = glIsEnabled(GL_CULL_FACE);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  mDraw.use();
  mVao.bind();
  mCommand.bind(GL_DRAW_INDIRECT_BUFFER);
  glDrawArraysIndirect(GL_TRIANGLE_STRIP, nullptr);
  if (culling == GL_TRUE) {
    glEnable(GL_CULL_FACE);
  }
}

std::uint32_t ImpostorRenderer::readVisibleCount() const {
  std::uint32_t command[4] = {0u, 0u, 0u, 0u};
  mCommand.getSubData(0, sizeof(command), command);
  return command[1];
}

Image ImpostorRenderer::readAtlas(int species) const {
  Image image = mColour.download(4, PixelType::U8, 0, species);
  image.flipVertically();
  return image;
}

Image ImpostorRenderer::readAtlasNormal(int species) const {
  Image image = mNormal.download(4, PixelType::U8, 0, species);
  image.flipVertically();
  return image;
}

std::size_t ImpostorRenderer::gpuBytes() const {
  const std::size_t side = static_cast<std::size_t>(mSettings.layout.side());
  // Two RGBA8 arrays with their mip chains (at most 4/3 of the base level).
  const std::size_t atlas = side * side * 4 * 2 * static_cast<std::size_t>(mSpecies) * 4 / 3;
  return atlas + (mInstances.id() != 0 ? mInstances.size() + mVisible.size() : 0) + mCommand.size() +
         sizeof(gpu::ImpostorUniforms);
}

ImpostorAtlas bakeTreeImpostor(const shader::Library& library, const PieceSet& pieces, const Species& species,
                               const TreeTopology& topology, const std::vector<glm::vec2>& pose, float scale,
                               const TreeImpostorBake& bake) {
  auto forest = std::make_shared<Forest>();
  forest->pieces = pieces;
  forest->species = {species};
  ForestTree one;
  one.topology = topology;
  one.species = 0;
  one.base = baseFrame(glm::vec3(0.0f), 0.0f, scale);
  one.pose = pose;
  forest->trees = {std::move(one)};
  forest->index();
  std::vector<BarkSet> bark;
  std::vector<int> speciesSet;
  if (bake.bark) {
    bark.push_back(*bake.bark);
    speciesSet.push_back(0);
  }
  ImpostorSettings settings;
  settings.layout.views = bake.views;
  settings.layout.cell = bake.cell;
  ImpostorRenderer impostors(library, settings);
  impostors.bake(*forest, sceneBakeOptions(library, std::move(bark), std::move(speciesSet), bake.foliage,
                                           bake.foliage ? bake.leafImage : nullptr));
  ImpostorAtlas atlas;
  atlas.image = impostors.readAtlas(0);
  atlas.viewsPerSide = bake.views;
  atlas.layout = "hemi-octahedral";
  // speciesSphere is in crown heights (the tree's height in rim units times the scale, as the bake measures).
  const float height = std::max(treeStats(pieces, topology).height * scale, 1e-3f);
  atlas.sphere = impostors.speciesSphere(0) * height;
  return atlas;
}

} // namespace sylva::trees

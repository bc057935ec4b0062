#include <sylva/terrain/gpu/TerrainRenderer.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/shader/Compiler.hpp>
#include <sylva/terrain/Geomorph.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/gpu/GpuQuadtreeSelection.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <deque>

namespace sylva::terrain {

namespace {

/**
 * Heights with every absent sample replaced by its nearest valid sample (breadth-first), for geometry, and
 * the validity mask (255 = present). Fields without absent samples (the common case) need neither copy nor
 * queue: `filled` stays empty and the caller uploads the field itself.
 */
void fillAbsent(const HeightField& field, std::vector<float>& filled, std::vector<std::uint8_t>& valid) {
  const int w = field.width();
  const int h = field.height();
  const std::vector<float>& in = field.samples();
  valid.assign(in.size(), 0);
  std::size_t present = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (!std::isnan(in[i])) {
      valid[i] = 255;
      ++present;
    }
  }
  if (present == in.size()) {
    return;
  }
  filled = in;
  std::deque<int> queue;
  for (int i = 0; i < w * h; ++i) {
    if (valid[static_cast<std::size_t>(i)] != 0) {
      queue.push_back(i);
    }
  }
  // `valid` doubles as the visited set: 1 marks a filled (absent) sample, which the shaders read as absent.
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    const int x = i % w;
    const int y = i / w;
    const int neighbours[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
    for (const auto& n : neighbours) {
      if (n[0] < 0 || n[1] < 0 || n[0] >= w || n[1] >= h) {
        continue;
      }
      const int j = n[1] * w + n[0];
      if (valid[static_cast<std::size_t>(j)] == 0) {
        valid[static_cast<std::size_t>(j)] = 1;
        filled[static_cast<std::size_t>(j)] = filled[static_cast<std::size_t>(i)];
        queue.push_back(j);
      }
    }
  }
}

constexpr GLuint kGroup = SYLVA_TERRAIN_GROUP_SIZE;

GLuint groups(int n) {
  return static_cast<GLuint>((n + static_cast<int>(kGroup) - 1) / static_cast<int>(kGroup));
}

} // namespace

std::vector<gpu::TerrainNode> packTerrainNodes(const QuadtreeSelection& selection, float extentX,
                                               float extentZ, bool skirts) {
  std::vector<gpu::TerrainNode> out;
  out.reserve(selection.nodes.size() * (skirts ? 5 : 1));
  for (const SelectedNode& n : selection.nodes) {
    gpu::TerrainNode node{};
    node.rect = glm::vec4(n.x, n.size, n.z, n.minY);
    node.tessOuter = glm::vec4(n.tessOuter[0], n.tessOuter[1], n.tessOuter[2], n.tessOuter[3]);
    node.tessInner = glm::vec4(n.tessInner, n.maxY, static_cast<float>(n.edgeFlags), 0.0f);
    node.grid = glm::ivec4(n.gridX, n.level, n.gridZ, -1);
    out.push_back(node);
  }
  if (skirts) {
    const std::size_t surfaces = out.size();
    for (std::size_t i = 0; i < surfaces; ++i) {
      const SelectedNode& n = selection.nodes[i];
      // Only edges with terrain on the other side: the outer border has nothing to stitch.
      const bool interior[4] = {n.x > 0.0f, n.z > 0.0f, n.x + n.size < extentX, n.z + n.size < extentZ};
      for (int e = 0; e < 4; ++e) {
        if (interior[e]) {
          gpu::TerrainNode skirt = out[i];
          skirt.grid.w = e;
          out.push_back(skirt);
        }
      }
    }
  }
  return out;
}

TerrainRenderer::TerrainRenderer(const shader::Library& library, const HeightField& field,
                                 std::vector<SplatLayer> layers, const SobelOptions& sobel,
                                 float verticalScale)
    : mField{field.width(),    field.height(),  field.spacingX(),
             field.spacingZ(), field.extentX(), field.extentZ()},
      mSobel(sobel), mVerticalScale(verticalScale),
      mHeights(gl::Texture::create2D(GL_R32F, std::max(field.width(), 1), std::max(field.height(), 1))),
      mValid(gl::Texture::create2D(GL_R8, std::max(field.width(), 1), std::max(field.height(), 1))),
      mNormalMap(
          gl::Texture::create2D(GL_RG16_SNORM, std::max(field.width(), 1), std::max(field.height(), 1))),
      mUniforms(sizeof(gpu::TerrainUniforms)), mRules(sizeof(gpu::SplatRuleGpu) * SYLVA_TERRAIN_MAX_LAYERS) {
  if (!std::isfinite(verticalScale) || verticalScale <= 0.0f) {
    fail("terrain: vertical scale {} must be finite and > 0", verticalScale);
  }
  if (field.width() < 2 || field.height() < 2) {
    fail("terrain: a height field needs at least 2x2 samples (got {}x{})", field.width(), field.height());
  }
  const HeightFieldInfo info = heightFieldInfo(field);
  if (info.validCount == 0) {
    fail("terrain: the height field has no valid sample");
  }
  mMinHeight = info.minHeight;
  mMaxHeight = info.maxHeight;
  mHoles =
      info.validCount < static_cast<std::size_t>(field.width()) * static_cast<std::size_t>(field.height());
  std::vector<std::uint8_t> valid;
  {
    std::vector<float> filled;
    fillAbsent(field, filled, valid);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(mHeights.id(), 0, 0, 0, field.width(), field.height(), GL_RED, GL_FLOAT,
                        filled.empty() ? field.samples().data() : filled.data());
  }
  glTextureSubImage2D(mValid.id(), 0, 0, 0, field.width(), field.height(), GL_RED, GL_UNSIGNED_BYTE,
                      valid.data());
  mHeights.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
  mValid.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
  mNormalMap.setSampler({GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE});
  gl::setLabel(GL_TEXTURE, mHeights.id(), "terrain heights");
  gl::setLabel(GL_TEXTURE, mNormalMap.id(), "terrain normals");
  if (epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")) {
    mInvocations = gl::Query(GL_TESS_EVALUATION_SHADER_INVOCATIONS_ARB);
  }
  reloadShaders(library);
  computeMaps(std::move(layers));
}

void TerrainRenderer::reloadShaders(const shader::Library& library) {
  gl::Program surface = shader::compileProgram(
      library, {"terrain surface",
                {"terrain/patch.vert", "terrain/patch.tesc", "terrain/patch.tese", "terrain/patch.frag"},
                {}});
  gl::Program normals = shader::compileProgram(library, {"terrain normals", {"terrain/normals.comp"}, {}});
  gl::Program splat = shader::compileProgram(library, {"terrain splat", {"terrain/splat.comp"}, {}});
  gl::Program water =
      shader::compileProgram(library, {"terrain water", {"terrain/water.vert", "terrain/water.frag"}, {}});
  mWater = std::move(water);
  mSurface = std::move(surface);
  mSurfacePoints = gl::Program(gl::NoCreate);
  mSurfaceDepth = gl::Program(gl::NoCreate);
  mSurfaceCapture = gl::Program(gl::NoCreate);
  mLibrary = &library;
  mNormals = std::move(normals);
  mSplat = std::move(splat);
}

void TerrainRenderer::computeMaps(std::vector<SplatLayer> layers) {
  if (layers.empty() || layers.size() > static_cast<std::size_t>(kMaxSplatLayers)) {
    fail("terrain: {} splat layers (expected 1..{})", layers.size(), kMaxSplatLayers);
  }
  mLayers = std::move(layers);
  const int w = mField.width;
  const int h = mField.height;
  gpu::TerrainMapsUniforms u{};
  u.field = glm::ivec4(w, h, static_cast<int>(mLayers.size()), mSobel.border == BorderMode::Constant ? 1 : 0);
  u.spacing = glm::vec4(mField.spacingX, mField.spacingZ, mSobel.constantHeight, mVerticalScale);
  gl::Buffer mapsUniforms(sizeof(u), &u);
  mapsUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_TERRAIN_BINDING);
  mHeights.bind(0);
  mValid.bind(1);

  mNormals.use();
  mNormalMap.bindImage(0, GL_WRITE_ONLY);
  glDispatchCompute(groups(w), groups(h), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  std::vector<gpu::SplatRuleGpu> rules(SYLVA_TERRAIN_MAX_LAYERS);
  for (std::size_t i = 0; i < mLayers.size(); ++i) {
    const SplatLayer& l = mLayers[i];
    rules[i].height = glm::vec4(l.minHeight, l.maxHeight, l.heightBlend, 0.0f);
    rules[i].slope = glm::vec4(l.minSlope, l.maxSlope, l.slopeBlend, 0.0f);
  }
  mRules.setSubData(std::span<const gpu::SplatRuleGpu>(rules));
  mRules.bindBase(GL_UNIFORM_BUFFER, SYLVA_TERRAIN_LAYER_BINDING);
  const int pages = (static_cast<int>(mLayers.size()) + 3) / 4;
  mSplatMap = gl::Texture::create2DArray(GL_RGBA8, w, h, pages);
  mSplatMap.setSampler({GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE});
  mSplat.use();
  mNormalMap.bind(2);
  mSplatMap.bindImage(0, GL_WRITE_ONLY);
  glDispatchCompute(groups(w), groups(h), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  uploadLayerTextures();
}

void TerrainRenderer::uploadLayerTextures() {
  constexpr int kSize = 256;
  const int levels = std::bit_width(static_cast<unsigned>(kSize));
  mLayerAlbedo = gl::Texture::create2DArray(GL_RGBA8, kSize, kSize, static_cast<int>(mLayers.size()), levels);
  for (std::size_t i = 0; i < mLayers.size(); ++i) {
    mLayerAlbedo.upload(proceduralLayerTexture(mLayers[i], static_cast<int>(i), kSize), 0,
                        static_cast<int>(i));
  }
  mLayerAlbedo.generateMipmaps();
  mLayerAlbedo.setSampler({GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT});
}

void TerrainRenderer::draw(const QuadtreeSelection& selection, const render::Camera& camera, int width,
                           int height, double time, render::GpuTimers* timers,
                           const TerrainDrawOptions& options) {
  const render::GpuTimerScope timed(timers, "terrain");
  const std::size_t nodes = uploadNodes(selection, options.skirts);
  if (nodes != 0) {
    // Depth only: without holes in the data or patches past its extent nothing is discarded, and a fragment
    // shader without discard lets the rasteriser reject hidden fragments before shading.
    bool depthOnly = options.view == TerrainView::Depth && !options.vertexPoints && !mHoles;
    for (std::size_t i = 0; depthOnly && i < selection.nodes.size(); ++i) {
      const SelectedNode& n = selection.nodes[i];
      depthOnly =
          n.x >= 0.0f && n.z >= 0.0f && n.x + n.size <= mField.extentX && n.z + n.size <= mField.extentZ;
    }
    const auto surfaces = static_cast<GLsizei>(selection.nodes.size());
    gl::Program& surface = drawSurface(selection.config, selection.camera,
                                       depthOnly ? SurfaceProgram::DepthOnly : SurfaceProgram::Shaded,
                                       surfaces, nullptr, camera, width, height, time, options);
    if (options.skirts && !options.vertexPoints) {
      // Skirts lose depth ties against the surface they hang from (exactly shared edge points).
      if (!mCrackSamples) {
        mCrackSamples = gl::Query(GL_SAMPLES_PASSED);
      }
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(1.0f, 4.0f);
      surface.setUniform("uNodeOffset", static_cast<int>(surfaces));
      mCrackSamples.begin();
      glDrawArraysInstanced(GL_PATCHES, 0, 4, static_cast<GLsizei>(nodes) - surfaces);
      mCrackSamples.end();
      glDisable(GL_POLYGON_OFFSET_FILL);
      mLastCrackSamples = static_cast<std::int64_t>(*mCrackSamples.result(true));
    }
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    if (options.waterLevel && options.view == TerrainView::Shaded && !options.wireframe &&
        !options.vertexPoints) {
      // Blended over the terrain, tested against its depth, writing none (the plane is a single quad).
      mWater.use();
      mWater.setUniform("uWaterLevel", *options.waterLevel);
      mWater.setUniform("uVerticalScale", mVerticalScale);
      mWater.setUniform("uWaterBottom", std::min(mMinHeight, *options.waterLevel));
      glEnable(GL_BLEND);
      glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      glDepthMask(GL_FALSE);
      glDrawArrays(GL_TRIANGLES, 0, 30);
      glDepthMask(GL_TRUE);
      glDisable(GL_BLEND);
    }
  }
}

std::size_t TerrainRenderer::uploadNodes(const QuadtreeSelection& selection, bool skirts) {
  const std::vector<gpu::TerrainNode> nodes =
      packTerrainNodes(selection, mField.extentX, mField.extentZ, skirts);
  if (!nodes.empty()) {
    const std::size_t bytes = nodes.size() * sizeof(gpu::TerrainNode);
    if (!mNodes || mNodes.size() < bytes) {
      mNodes = gl::Buffer(std::bit_ceil(bytes));
    }
    mNodes.setSubData(0, bytes, nodes.data());
    mNodes.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TERRAIN_NODE_BINDING);
  }
  return nodes.size();
}

std::vector<render::ClipTriangle> TerrainRenderer::captureTriangles(const QuadtreeSelection& selection,
                                                                    const render::Camera& camera, int width,
                                                                    int height,
                                                                    const TerrainDrawOptions& options) {
  const std::size_t nodes = uploadNodes(selection, options.skirts);
  if (nodes == 0) {
    return {};
  }
  TerrainDrawOptions capture = options;
  capture.vertexPoints = false;
  capture.countVertices = false;
  const auto patches = static_cast<GLsizei>(nodes);
  glEnable(GL_RASTERIZER_DISCARD);
  // Count first (any surface program emits the same primitives), then capture into a buffer of that size.
  const gl::Query generated(GL_PRIMITIVES_GENERATED);
  generated.begin();
  drawSurface(selection.config, selection.camera, SurfaceProgram::Shaded, patches, nullptr, camera, width,
              height, 0.0, capture);
  generated.end();
  const std::uint64_t triangles = *generated.result(true);
  struct Vertex {
    glm::vec4 clip;
    std::int32_t skirt;
  };
  static_assert(sizeof(Vertex) == 20, "transform feedback packs gl_Position and teSkirt tightly");
  std::vector<render::ClipTriangle> out;
  if (triangles != 0) {
    const gl::Buffer feedback(triangles * 3 * sizeof(Vertex));
    feedback.bindBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
    drawSurface(selection.config, selection.camera, SurfaceProgram::Capture, patches, nullptr, camera, width,
                height, 0.0, capture);
    std::vector<Vertex> vertices(triangles * 3);
    feedback.getSubData(0, vertices.size() * sizeof(Vertex), vertices.data());
    out.reserve(triangles);
    for (std::size_t t = 0; t < triangles; ++t) {
      out.push_back({{vertices[3 * t].clip, vertices[3 * t + 1].clip, vertices[3 * t + 2].clip},
                     vertices[3 * t].skirt});
    }
  }
  glDisable(GL_RASTERIZER_DISCARD);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  return out;
}

gl::Program& TerrainRenderer::drawSurface(const QuadtreeConfig& lod, const glm::vec3& selectionCamera,
                                          SurfaceProgram program, GLsizei patches, const gl::Buffer* indirect,
                                          const render::Camera& camera, int width, int height, double time,
                                          const TerrainDrawOptions& options) {
  gpu::TerrainUniforms u{};
  u.field = glm::ivec4(mField.width, mField.height, mSplatMap.layers(), static_cast<int>(mLayers.size()));
  u.spacing = glm::vec4(mField.spacingX, mField.spacingZ, options.textureTiling, options.skirtDepth);
  u.extent = glm::vec4(mField.extentX, mField.extentZ, static_cast<float>(options.view), 0.0f);
  u.heightRange = glm::vec4(mMinHeight, mMaxHeight, 0.0f, 0.0f);
  mUniforms.setSubData(0, sizeof(u), &u);
  mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_TERRAIN_BINDING);
  mFrame.bind(camera, width, height, time, options.environment);
  mHeights.bind(0);
  mValid.bind(1);
  mNormalMap.bind(2);
  mSplatMap.bind(3);
  mLayerAlbedo.bind(4);
  if (options.vertexPoints && !mSurfacePoints) {
    mSurfacePoints = shader::compileProgram(
        *mLibrary, {"terrain surface points",
                    {"terrain/patch.vert", "terrain/patch.tesc", "terrain/patch.tese", "terrain/patch.frag"},
                    {{"SYLVA_TERRAIN_POINTS", "1"}}});
  }
  const bool depthOnly = program == SurfaceProgram::DepthOnly;
  const bool capture = program == SurfaceProgram::Capture;
  if (capture && !mSurfaceCapture) {
    mSurfaceCapture = shader::compileProgram(
        *mLibrary, {"terrain surface capture",
                    {"terrain/patch.vert", "terrain/patch.tesc", "terrain/patch.tese", "terrain/patch.frag"},
                    {},
                    {"gl_Position", "teSkirt"}});
  }
  if (depthOnly && !mSurfaceDepth) {
    mSurfaceDepth = shader::compileProgram(
        *mLibrary, {"terrain surface depth",
                    {"terrain/patch.vert", "terrain/patch.tesc", "terrain/patch.tese", "terrain/patch.frag"},
                    {{"SYLVA_TERRAIN_DEPTH_ONLY", "1"}}});
  }
  gl::Program& surface = capture                ? mSurfaceCapture
                         : options.vertexPoints ? mSurfacePoints
                         : depthOnly            ? mSurfaceDepth
                                                : mSurface;
  surface.use();
  mVao.bind();
  // Geomorphing follows the selection's camera and LOD distances (off: w = 0, the plain surface).
  const bool morph = options.geomorph && GeomorphParams::of(lod).enabled;
  surface.setUniform("uMorphCamera", glm::vec4(selectionCamera, morph ? 1.0f : 0.0f));
  surface.setUniform("uMorphLod", glm::vec4(lod.rootSize, static_cast<float>(lod.maxDepth),
                                            static_cast<float>(lod.patchTessLevel), lod.lodDistanceFactor));
  glPatchParameteri(GL_PATCH_VERTICES, 4);
  glPolygonMode(GL_FRONT_AND_BACK, options.wireframe ? GL_LINE : GL_FILL);
  const bool count = options.countVertices && mInvocations;
  if (count) {
    mInvocations.begin();
  }
  surface.setUniform("uNodeOffset", 0);
  if (options.groundTint && options.groundTint->texture != nullptr) {
    const GroundTint& tint = *options.groundTint;
    tint.texture->bind(5);
    surface.setUniform("uGroundTint", glm::vec4(tint.colour, std::clamp(tint.strength, 0.0f, 1.0f)));
    surface.setUniform("uGroundTintMap",
                       glm::vec4(1.0f / tint.spacing.x, 1.0f / tint.spacing.y,
                                 static_cast<float>(tint.size.x), static_cast<float>(tint.size.y)));
  } else {
    surface.setUniform("uGroundTint", glm::vec4(0.0f));
  }
  if (indirect != nullptr) {
    indirect->bind(GL_DRAW_INDIRECT_BUFFER);
    glDrawArraysIndirect(GL_PATCHES, nullptr);
  } else if (capture) {
    glBeginTransformFeedback(GL_TRIANGLES);
    glDrawArraysInstanced(GL_PATCHES, 0, 4, patches);
    glEndTransformFeedback();
  } else {
    glDrawArraysInstanced(GL_PATCHES, 0, 4, patches);
  }
  if (count) {
    mInvocations.end();
    mLastInvocations = static_cast<std::int64_t>(*mInvocations.result(true));
  }
  return surface;
}

void TerrainRenderer::draw(const GpuQuadtreeSelection& selection, const render::Camera& camera, int width,
                           int height, double time, render::GpuTimers* timers,
                           const TerrainDrawOptions& options) {
  const render::GpuTimerScope timed(timers, "terrain");
  selection.nodes().bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TERRAIN_NODE_BINDING);
  drawSurface(selection.quadtree().config(), selection.camera(), SurfaceProgram::Shaded, 0,
              &selection.command(), camera, width, height, time, options);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

Image TerrainRenderer::downloadNormals() const {
  const Image rg = mNormalMap.download(2, PixelType::F32);
  Image rgb(rg.width(), rg.height(), 3, PixelType::F32);
  for (int y = 0; y < rg.height(); ++y) {
    for (int x = 0; x < rg.width(); ++x) {
      const float nx = rg.get(x, y, 0);
      const float nz = rg.get(x, y, 1);
      rgb.set(x, y, 0, nx);
      rgb.set(x, y, 1, std::sqrt(std::max(0.0f, 1.0f - nx * nx - nz * nz)));
      rgb.set(x, y, 2, nz);
    }
  }
  return rgb;
}

std::vector<Image> TerrainRenderer::downloadSplat() const {
  std::vector<Image> pages;
  pages.reserve(static_cast<std::size_t>(mSplatMap.layers()));
  for (int page = 0; page < mSplatMap.layers(); ++page) {
    pages.push_back(mSplatMap.download(4, PixelType::F32, 0, page));
  }
  return pages;
}

} // namespace sylva::terrain

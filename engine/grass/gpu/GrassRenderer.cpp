#include <sylva/grass/gpu/GrassRenderer.hpp>
#include <sylva/grass/gpu/GrassSimulator.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Geometry.hpp>
#include <sylva/grass/Simulation.hpp>
#include <sylva/shader/Compiler.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::grass {
namespace {

constexpr std::array<int, 3> kFirstKnot{0, SYLVA_GRASS_LOD0_KNOTS,
                                        SYLVA_GRASS_LOD0_KNOTS + SYLVA_GRASS_LOD1_KNOTS};

/** Tiles of a disc of `radius` metres (plus a tile's margin), capped by the whole grid. */
std::size_t tilesWithin(const FieldLayout& layout, float radius) {
  const double r = static_cast<double>(radius) / layout.tileSize + 1.5;
  const double disc = std::ceil(std::numbers::pi * r * r * 1.05);
  const double side = 2.0 * r + 1.0;
  const double square =
      std::min(side, static_cast<double>(layout.tilesX)) * std::min(side, static_cast<double>(layout.tilesZ));
  return static_cast<std::size_t>(std::max(1.0, std::min(disc, square)));
}

gl::Texture floatTexture(int width, int height, const float* data, GLenum format) {
  gl::Texture t = gl::Texture::create2D(format, std::max(width, 1), std::max(height, 1));
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.id(), 0, 0, 0, width, height, GL_RED, format == GL_R8 ? GL_UNSIGNED_BYTE : GL_FLOAT,
                      data);
  t.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
  return t;
}

gl::Texture heightTexture(const terrain::HeightField& field) {
  // Absent samples are never read for a drawn blade (their four-sample test fails first); zero them.
  std::vector<float> heights(field.samples());
  for (float& h : heights) {
    h = std::isnan(h) ? 0.0f : h;
  }
  return floatTexture(field.width(), field.height(), heights.data(), GL_R32F);
}

gl::Texture validTexture(const terrain::HeightField& field) {
  std::vector<std::uint8_t> valid(field.samples().size());
  for (std::size_t i = 0; i < valid.size(); ++i) {
    valid[i] = std::isnan(field.samples()[i]) ? 0 : 255;
  }
  return floatTexture(field.width(), field.height(), reinterpret_cast<const float*>(valid.data()), GL_R8);
}

} // namespace

std::vector<gpu::GrassTypeGpu> packBladeTypes(const std::vector<BladeType>& types) {
  std::vector<gpu::GrassTypeGpu> out(types.size());
  for (std::size_t t = 0; t < types.size(); ++t) {
    const BladeType& type = types[t];
    gpu::GrassTypeGpu& g = out[t];
    g.colour = glm::vec4(type.colour, type.stiffness);
    g.size = glm::vec4(type.length(), 0.0f, 0.0f, 0.0f);
    for (std::size_t lod = 0; lod < kLodKnots.size(); ++lod) {
      const BladeShapeLod& shape = type.lods[lod];
      if (shape.knots.size() != static_cast<std::size_t>(kLodKnots[lod]) ||
          shape.widths.size() != shape.knots.size()) {
        fail("grass: blade type '{}' level {} has {} knots, expected {}", type.name, lod, shape.knots.size(),
             kLodKnots[lod]);
      }
      for (std::size_t k = 0; k < shape.knots.size(); ++k) {
        g.knots[static_cast<std::size_t>(kFirstKnot[lod]) + k] = glm::vec4(shape.knots[k], shape.widths[k]);
      }
    }
  }
  return out;
}

GrassRenderer::GrassRenderer(const shader::Library& library, std::shared_ptr<const GrassField> field,
                             const CullSettings& settings)
    : mField(std::move(field)), mUniforms(sizeof(gpu::GrassUniforms)),
      mPatch(std::span<const gpu::GrassBlade>(mField->patch())),
      mTypes(std::span<const gpu::GrassTypeGpu>(packBladeTypes(mField->types()))),
      mCommands(sizeof(gpu::GrassCounters)), mHeights(heightTexture(mField->terrain())),
      mValid(validTexture(mField->terrain())),
      mDensity(floatTexture(mField->density().width(), mField->density().height(),
                            mField->density().values().data(), GL_R32F)) {
  mDensity.setSampler({GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE});
  gl::setLabel(GL_BUFFER, mPatch.id(), "grass patch");
  gl::setLabel(GL_TEXTURE, mDensity.id(), "grass density");
  // The average colour of the blades, weighted by how often each type occurs in the patch.
  std::vector<float> counts(mField->types().size(), 0.0f);
  for (const gpu::GrassBlade& b : mField->patch()) {
    counts[std::min<std::size_t>(b.info.x, counts.size() - 1)] += 1.0f;
  }
  for (std::size_t t = 0; t < counts.size(); ++t) {
    mAverageColour += mField->types()[t].colour * (counts[t] / static_cast<float>(mField->patch().size()));
  }
  if (epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")) {
    mVerticesQuery = gl::Query(GL_VERTICES_SUBMITTED_ARB);
    mPrimitivesQuery = gl::Query(GL_PRIMITIVES_SUBMITTED_ARB);
  }
  // An empty stand-in for the simulation's buffers, bound when there is none (never read then).
  mNoSimulation = gl::Buffer(64);
  uploadConstants();
  reloadShaders(library);
  setCullSettings(settings);
}

void GrassRenderer::uploadConstants() {
  const GrassField& f = *mField;
  const FieldLayout& layout = f.layout();
  gpu::GrassUniforms& u = mLast;
  u.field = glm::vec4(layout.origin, f.terrain().extentX(), f.terrain().extentZ());
  u.tiles =
      glm::ivec4(layout.tilesX, layout.tilesZ, layout.bladesPerTile, static_cast<int>(f.patch().size()));
  u.grids = glm::ivec4(f.terrain().width(), f.terrain().height(), f.density().width(), f.density().height());
  u.spacing = glm::vec4(f.terrain().spacingX(), f.terrain().spacingZ(), f.density().spacing());
  u.options = glm::uvec4(mSimulation != nullptr ? static_cast<unsigned>(mSimulation->slots()) : 0u,
                         u.options.y, static_cast<unsigned>(f.types().size()),
                         mSimulation != nullptr ? static_cast<unsigned>(mSimulation->bladesPerTile()) : 0u);
  u.ground = glm::vec4(mAverageColour, 0.0f);
  u.heights = glm::vec4(f.heightRange(), 0.0f, 0.0f);
  u.orient.z = f.bladeTop();
  u.orient.w = layout.tileSize;
  mUniforms.setSubData(0, sizeof(u), &u);
}

void GrassRenderer::setSimulation(const GrassSimulator* simulation) {
  mSimulation = simulation;
  uploadConstants();
  setCullSettings(mSettings);
}

void GrassRenderer::bindFieldResources() const {
  mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_GRASS_BINDING);
  mPatch.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_PATCH_BINDING);
  mTypes.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_TYPE_BINDING);
  mHeights.bind(0);
  mValid.bind(1);
  mDensity.bind(2);
}

void GrassRenderer::reloadShaders(const shader::Library& library) {
  gl::Program tiles = shader::compileProgram(library, {"grass tiles", {"grass/tiles.comp"}, {}});
  gl::Program blades = shader::compileProgram(library, {"grass blades", {"grass/blades.comp"}, {}});
  gl::Program finish = shader::compileProgram(library, {"grass finish", {"grass/finish.comp"}, {}});
  gl::Program draw =
      shader::compileProgram(library, {"grass draw", {"grass/blade.vert", "grass/blade.frag"}, {}});
  gl::Program capture = shader::compileProgram(
      library, {"grass capture", {"grass/blade.vert", "grass/blade.frag"}, {{"SYLVA_GRASS_CAPTURE", "1"}}});
  mTiles = std::move(tiles);
  mBlades = std::move(blades);
  mFinish = std::move(finish);
  mDraw = std::move(draw);
  mCapture = std::move(capture);
}

void GrassRenderer::setCullSettings(const CullSettings& settings) {
  validate(settings);
  mSettings = settings;
  const FieldLayout& layout = mField->layout();
  const auto perTile =
      static_cast<std::size_t>(std::min(layout.bladesPerTile, static_cast<int>(mField->patch().size())));
  const float half = 0.5f * settings.lodFade;
  // The near layers' tuft blades: (layers − 1) per field blade in the tiles within their reach, level 0.
  const auto layers = static_cast<std::size_t>(
      nearLayerCount(settings, layout, static_cast<std::uint32_t>(mField->patch().size())));
  const std::size_t nearTiles = layers > 1 ? tilesWithin(layout, nearReach(settings)) : 0;
  const std::size_t tufts = nearTiles * perTile * (layers - 1);
  const std::array<std::size_t, 4> lists{
      tilesWithin(layout, settings.lodDistances[0] + half) * perTile + tufts,
      tilesWithin(layout, settings.lodDistances[1] + half) * perTile,
      tilesWithin(layout, settings.maxDistance) * perTile, tilesWithin(layout, settings.maxDistance)};
  const std::size_t slots = mSimulation != nullptr ? static_cast<std::size_t>(mSimulation->slots()) : 0;
  const std::size_t simulated = mSimulation != nullptr
                                    ? slots * static_cast<std::size_t>(mSimulation->bladesPerTile()) +
                                          std::min(slots, nearTiles) * perTile * (layers - 1)
                                    : 0;
  const std::size_t instances = lists[0] + lists[1] + lists[2] + simulated;
  if (instances > (1u << 30) / sizeof(glm::uvec4)) {
    fail("grass: a draw distance of {} m with {} blades per tile needs {} instances (more than 2^26)",
         settings.maxDistance, perTile, instances);
  }
  mLast.lists = glm::uvec4(lists[0], lists[1], lists[2], lists[3]);
  mLast.simulated = glm::uvec4(static_cast<unsigned>(simulated), 0u, 0u, 0u);
  mLast.near = glm::vec4(nearReach(settings), static_cast<float>(layers), tuftRadius(layout), 0.0f);
  mCapacity = lists[2];
  if (!mInstances || mInstances.size() < instances * sizeof(glm::uvec4)) {
    mInstances = gl::Buffer(instances * sizeof(glm::uvec4), nullptr, 0);
    gl::setLabel(GL_BUFFER, mInstances.id(), "grass instances");
  }
  if (!mVisibleTiles || mVisibleTiles.size() < lists[3] * sizeof(glm::ivec2)) {
    mVisibleTiles = gl::Buffer(lists[3] * sizeof(glm::ivec2), nullptr, 0);
  }
  // The instance list feeds the blade vertex shader as a per-instance integer attribute, so each level's
  // draw command picks its list by baseInstance.
  glVertexArrayVertexBuffer(mVao.id(), 0, mInstances.id(), 0, sizeof(glm::uvec4));
  glVertexArrayBindingDivisor(mVao.id(), 0, 1);
  glVertexArrayAttribIFormat(mVao.id(), 0, 4, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(mVao.id(), 0, 0);
  glEnableVertexArrayAttrib(mVao.id(), 0);
}

void GrassRenderer::uploadUniforms(const render::Camera& camera, float aspect, const wind::WindSettings& wind,
                                   double time, GrassView view) {
  const FieldLayout& layout = mField->layout();
  gpu::GrassUniforms& u = mLast;
  const Frustum frustum(camera.viewProjection(aspect));
  for (std::size_t i = 0; i < 6; ++i) {
    u.planes[i] = frustum.planes()[i];
  }
  u.eye = glm::vec4(camera.position, mSettings.maxDistance);
  u.lod =
      glm::vec4(mSettings.lodDistances[0], mSettings.lodDistances[1], mSettings.lodFade, mSettings.farFade);
  u.orient.x = mSettings.orientationDistance;
  u.orient.y = mSettings.orientationCos;
  u.options.y = static_cast<unsigned>(view);
  u.window = tileWindow(layout, glm::vec2(camera.position.x, camera.position.z), mSettings.maxDistance);
  u.wind = wind::toUniforms(wind, static_cast<float>(time));
  mUniforms.setSubData(0, sizeof(u), &u);
}

void GrassRenderer::bindCommon() const {
  bindFieldResources();
  if (mSimulation != nullptr) {
    mSimulation->bindForDrawing();
  } else {
    mNoSimulation.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_SLOT_BINDING);
    mNoSimulation.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_POSITION_BINDING);
  }
  mVisibleTiles.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_VISIBLE_BINDING);
  mInstances.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_INSTANCE_BINDING);
  mCommands.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_COMMAND_BINDING);
}

void GrassRenderer::cull(const render::Camera& camera, float aspect, render::GpuTimers* timers) {
  const render::GpuTimerScope timed(timers, "grass cull");
  uploadUniforms(camera, aspect, {}, 0.0, GrassView::Shaded);
  gpu::GrassCounters reset{};
  std::uint32_t base = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    reset.draws[k] = glm::uvec4(2 * kLodKnots[k], 0u, 0u, base);
    base += mLast.lists[static_cast<int>(k)];
  }
  reset.draws[3] = glm::uvec4(2 * kSimKnots, 0u, 0u, base);
  reset.dispatch = glm::uvec4(0u, 1u, 1u, 0u);
  mCommands.setSubData(0, sizeof(reset), &reset);
  bindCommon();
  mTiles.use();
  const glm::ivec4& window = mLast.window;
  if (window.z > 0 && window.w > 0) {
    glDispatchCompute(static_cast<GLuint>((window.z + SYLVA_GRASS_TILE_GROUP - 1) / SYLVA_GRASS_TILE_GROUP),
                      static_cast<GLuint>((window.w + SYLVA_GRASS_TILE_GROUP - 1) / SYLVA_GRASS_TILE_GROUP),
                      1);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  mFinish.use();
  mFinish.setUniform("uStage", 0);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  mBlades.use();
  mCommands.bind(GL_DISPATCH_INDIRECT_BUFFER);
  glDispatchComputeIndirect(static_cast<GLintptr>(offsetof(gpu::GrassCounters, dispatch)));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  mFinish.use();
  mFinish.setUniform("uStage", 1);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                  GL_SHADER_STORAGE_BARRIER_BIT);
}

void GrassRenderer::draw(const render::Camera& camera, int width, int height, double time,
                         render::GpuTimers* timers, const GrassDrawOptions& options) {
  const render::GpuTimerScope timed(timers, "grass");
  wind::validate(options.wind);
  // The cull's frustum and distances stay; the wind time and the view change per draw.
  gpu::GrassUniforms& u = mLast;
  u.options.y = static_cast<unsigned>(options.view);
  u.wind = wind::toUniforms(options.wind, static_cast<float>(time));
  mUniforms.setSubData(0, sizeof(u), &u);
  mFrame.bind(camera, width, height, time, options.environment);
  bindCommon();
  mDraw.use();
  mVao.bind();
  mCommands.bind(GL_DRAW_INDIRECT_BUFFER);
  const GLboolean culling = glIsEnabled(GL_CULL_FACE);
  glDisable(GL_CULL_FACE);
  const bool count = options.countPrimitives && mVerticesQuery;
  if (count) {
    mVerticesQuery.begin();
    mPrimitivesQuery.begin();
  }
  glMultiDrawArraysIndirect(GL_TRIANGLE_STRIP, nullptr, 4, sizeof(glm::uvec4));
  if (count) {
    mPrimitivesQuery.end();
    mVerticesQuery.end();
    mLastVertices = static_cast<std::int64_t>(*mVerticesQuery.result(true));
    mLastPrimitives = static_cast<std::int64_t>(*mPrimitivesQuery.result(true));
  }
  if (culling == GL_TRUE) {
    glEnable(GL_CULL_FACE);
  }
}

gpu::GrassCounters GrassRenderer::readCounters() const {
  gpu::GrassCounters c{};
  mCommands.getSubData(0, sizeof(c), &c);
  return c;
}

std::vector<VisibleBlade> GrassRenderer::readInstances() const {
  const gpu::GrassCounters c = readCounters();
  std::vector<VisibleBlade> out;
  std::size_t base = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t n = c.draws[k].y;
    std::vector<glm::uvec4> raw(n);
    if (n > 0) {
      mInstances.getSubData(base * sizeof(glm::uvec4), n * sizeof(glm::uvec4), raw.data());
    }
    for (const glm::uvec4& r : raw) {
      VisibleBlade v;
      v.blade.root =
          glm::vec3(std::bit_cast<float>(r.x), std::bit_cast<float>(r.y), std::bit_cast<float>(r.z));
      v.blade.patchIndex = r.w & SYLVA_GRASS_INDEX_MASK;
      v.lod = static_cast<int>((r.w >> 22) & 3u);
      v.fade = static_cast<Fade>((r.w >> 24) & 3u);
      v.amount = static_cast<float>(r.w >> 26) / 63.0f;
      out.push_back(v);
    }
    base += mLast.lists[k];
  }
  return out;
}

std::vector<std::vector<BladeVertex>>
GrassRenderer::captureExpansion(const std::vector<VisibleBlade>& instances, const wind::WindSettings& wind,
                                double time) {
  wind::validate(wind);
  mLast.wind = wind::toUniforms(wind, static_cast<float>(time));
  mLast.options.z = static_cast<unsigned>(mField->types().size());
  mUniforms.setSubData(0, sizeof(mLast), &mLast);
  bindCommon();
  std::vector<std::vector<BladeVertex>> out;
  out.reserve(instances.size());
  gl::VertexArray vao;
  mCapture.use();
  glEnable(GL_RASTERIZER_DISCARD);
  for (const VisibleBlade& v : instances) {
    if (v.lod < 0 || v.lod > 2) {
      fail("grass: level of detail {} outside 0..2", v.lod);
    }
    const int vertices = 2 * kLodKnots[static_cast<std::size_t>(v.lod)];
    const glm::uvec4 record(
        std::bit_cast<std::uint32_t>(v.blade.root.x), std::bit_cast<std::uint32_t>(v.blade.root.y),
        std::bit_cast<std::uint32_t>(v.blade.root.z),
        (v.blade.patchIndex & SYLVA_GRASS_INDEX_MASK) | (static_cast<std::uint32_t>(v.lod) << 22));
    gl::Buffer instance(sizeof(record), &record);
    gl::Buffer captured(static_cast<std::size_t>(vertices) * 2 * sizeof(glm::vec4));
    captured.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_CAPTURE_BINDING);
    glVertexArrayVertexBuffer(vao.id(), 0, instance.id(), 0, sizeof(glm::uvec4));
    glVertexArrayBindingDivisor(vao.id(), 0, 1);
    glVertexArrayAttribIFormat(vao.id(), 0, 4, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(vao.id(), 0, 0);
    glEnableVertexArrayAttrib(vao.id(), 0);
    vao.bind();
    glDrawArraysInstanced(GL_POINTS, 0, vertices, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<glm::vec4> raw = captured.read<glm::vec4>();
    std::vector<BladeVertex> blade;
    for (int i = 0; i < vertices; ++i) {
      const glm::vec4& a = raw[static_cast<std::size_t>(2 * i)];
      const glm::vec4& b = raw[static_cast<std::size_t>(2 * i + 1)];
      blade.push_back({glm::vec3(a), glm::vec3(b), a.w, b.w});
    }
    out.push_back(std::move(blade));
  }
  glDisable(GL_RASTERIZER_DISCARD);
  return out;
}

terrain::GroundTint GrassRenderer::groundTint(float strength) const {
  terrain::GroundTint tint;
  tint.texture = &mDensity;
  tint.spacing = mField->density().spacing();
  tint.size = {mField->density().width(), mField->density().height()};
  // The ground between blades is partly shaded by them: a little darker than the blades' own colour.
  tint.colour = mAverageColour * 0.8f;
  tint.strength = strength;
  return tint;
}

std::size_t GrassRenderer::gpuBytes() const {
  const GrassField& f = *mField;
  return mPatch.size() + mTypes.size() + mVisibleTiles.size() + mInstances.size() + mCommands.size() +
         f.terrain().samples().size() * 5 + f.density().values().size() * sizeof(float);
}

} // namespace sylva::grass

// The scene's water with the folding-textured shore band (docs/scenes.md "Water with a folding-textured
// shore").
#include <sylva/scene/gpu/ShoreWater.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/shader/Compiler.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sylva::scene {
namespace {

/** Height of an absent sample in the GPU copy: far above any level, so the shader treats it as dry. */
constexpr float kAbsentHeight = 1e20f;

} // namespace

ShoreWater::ShoreWater(const shader::Library& library, const terrain::HeightField& field, float verticalScale,
                       ShoreSettings settings)
    : mSettings(std::move(settings)), mVerticalScale(verticalScale) {
  validate(mSettings);
  if (!std::isfinite(verticalScale) || verticalScale <= 0.0f) {
    fail("shore: vertical scale {} must be finite and > 0", verticalScale);
  }
  if (field.width() < 2 || field.height() < 2) {
    fail("shore: the height field needs at least 2x2 samples (got {}x{})", field.width(), field.height());
  }
  mFieldWidth = field.width();
  mFieldHeight = field.height();
  mSpacingX = field.spacingX();
  mSpacingZ = field.spacingZ();
  const WaterGrid grid = waterGrid(mFieldWidth, mFieldHeight, kMaxCells);
  mStride = grid.stride;
  mCellsX = grid.cellsX;
  mCellsZ = grid.cellsZ;
  // Only cells that can show water are drawn: on a lake scene most of the footprint is dry ground, whose
  // fragments the shader discards anyway (same pixels, a fraction of the vertices).
  const float wetTop = mSettings.level + mSettings.wet * verticalScale;
  const std::vector<std::uint32_t> cells =
      wetCells(field, grid, wetTop, 1e-4f * std::max(1.0f, std::abs(wetTop)));
  mWetCells = static_cast<int>(cells.size());
  const std::vector<glm::uvec4> rects =
      waterRects(field, grid, cells, mSettings.level, lift()); // the surface draw() draws
  const std::vector<glm::ivec2> points = waterTriangles(rects);
  mVertexCount = static_cast<int>(points.size());
  mCellList = gl::Buffer(std::max<std::size_t>(points.size(), 1) * sizeof(glm::ivec2));
  if (!points.empty()) {
    mCellList.setSubData(std::span<const glm::ivec2>(points));
  }
  gl::setLabel(GL_BUFFER, mCellList.id(), "shore water cells");

  // Heights: absent samples become "always dry".
  std::vector<float> heights = field.samples();
  for (float& h : heights) {
    if (std::isnan(h)) {
      h = kAbsentHeight;
    }
  }
  mHeights = gl::Texture::create2D(GL_R32F, mFieldWidth, mFieldHeight);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(mHeights.id(), 0, 0, 0, mFieldWidth, mFieldHeight, GL_RED, GL_FLOAT, heights.data());
  mHeights.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});

  // The folding project, synthesised on the CPU like `sylva fold render`.
  const std::string& where = mSettings.folding;
  folding::Project project;
  folding::Textures textures;
  try {
    project = folding::loadProject(where);
    const folding::ProjectImages images = folding::loadProjectImages(project, where);
    textures = folding::synthesize(project, images);
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.find(where) != std::string::npos) {
      throw;
    }
    fail("shore: {}: {}", where, message);
  }
  mProjectPeriod = folding::loopPeriod(project.profiles).seconds;
  const folding::AtlasEntry& entry =
      textures.atlas.entries.at(static_cast<std::size_t>(project.canvasIndex()));
  mRegion = entry.atlasRect();
  mAspect = static_cast<float>(mRegion.height()) / static_cast<float>(mRegion.width());
  mWaterlineV =
      (mSettings.waterline * static_cast<float>(entry.imageSize.y) - static_cast<float>(entry.crop.min.y)) /
      static_cast<float>(entry.crop.height());
  mFold = std::make_unique<folding::gpu::FoldRenderer>(library);
  mFold->upload(textures, project.profiles, project.jumpLayers);

  const float scale = std::min(1.0f, static_cast<float>(kMaxSwashSide) /
                                         static_cast<float>(std::max(mRegion.width(), mRegion.height())));
  const int w = std::max(1, static_cast<int>(std::lround(static_cast<float>(mRegion.width()) * scale)));
  const int h = std::max(1, static_cast<int>(std::lround(static_cast<float>(mRegion.height()) * scale)));
  mSwashLevels = 1 + static_cast<int>(std::floor(std::log2(static_cast<float>(std::max(w, h)))));
  mSwash = gl::Texture::create2D(GL_RGBA8, w, h, mSwashLevels);
  mSwash.setSampler({GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT});
  glTextureParameteri(mSwash.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE); // across the shore: no repeat
  gl::setLabel(GL_TEXTURE, mSwash.id(), "shore swash");
  mSwashTarget.attachColor(0, mSwash);
  mSwashTarget.checkComplete();
  reloadShaders(library);
  update(0.0);
}

ShoreWater::~ShoreWater() = default;

void ShoreWater::reloadShaders(const shader::Library& library) {
  gl::Program program =
      shader::compileProgram(library, {"shore water", {"scene/water.vert", "scene/water.frag"}, {}});
  mProgram = std::move(program);
  mFold->reloadShaders(library);
}

void ShoreWater::setSwashLevel(int level) {
  level = std::clamp(level, 0, mSwashLevels - 1);
  if (level == mSwashLevel) {
    return;
  }
  mSwashLevel = level;
  mSwashTarget.attachColor(0, mSwash, level);
  mSwashTarget.checkComplete();
  // Sampling starts at that level; glGenerateTextureMipmap builds the coarser ones from it.
  glTextureParameteri(mSwash.id(), GL_TEXTURE_BASE_LEVEL, level);
}

void ShoreWater::update(double time) {
  GLint previous = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, viewport);
  GLboolean blend = glIsEnabled(GL_BLEND);
  GLboolean depth = glIsEnabled(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  mSwashTarget.bindForDraw(std::max(1, mSwash.width() >> mSwashLevel),
                           std::max(1, mSwash.height() >> mSwashLevel));
  mFold->draw(swashTime(time, mSettings.period, mProjectPeriod), mRegion);
  mSwash.generateMipmaps();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  if (blend) {
    glEnable(GL_BLEND);
  }
  if (depth) {
    glEnable(GL_DEPTH_TEST);
  }
}

void ShoreWater::draw(const render::Camera& camera, int width, int height, double time,
                      const render::Environment& environment) {
  mFrame.bind(camera, width, height, time, environment);
  mHeights.bind(0);
  mSwash.bind(1);
  mProgram.use();
  const auto setInt2 = [&](const char* name, int x, int y) {
    glProgramUniform2i(mProgram.id(), mProgram.uniformLocation(name), x, y);
  };
  setInt2("uField", mFieldWidth, mFieldHeight);
  mProgram.setUniform("uSpacing", glm::vec2(mSpacingX, mSpacingZ));
  mProgram.setUniform("uStride", mStride);
  mProgram.setUniform("uLevel", mSettings.level);
  mProgram.setUniform("uLift", lift());
  mProgram.setUniform("uWetTop", mSettings.level + mSettings.wet * mVerticalScale);
  mProgram.setUniform("uVerticalScale", mVerticalScale);
  mProgram.setUniform("uBand", mSettings.band);
  mProgram.setUniform("uWet", mSettings.wet);
  mProgram.setUniform("uTile", mSettings.tile);
  mProgram.setUniform("uAspect", mAspect);
  mProgram.setUniform("uWaterline", mWaterlineV);
  mProgram.setUniform("uView", static_cast<int>(mView));
  int vertices = mVertexCount;
  if (mDrawEveryCell) {
    vertices = 6 * mCellsX * mCellsZ;
    if (mEveryCell.id() == 0) {
      std::vector<glm::uvec4> all;
      all.reserve(static_cast<std::size_t>(mCellsX) * static_cast<std::size_t>(mCellsZ));
      for (int z = 0; z < mCellsZ; ++z) {
        for (int x = 0; x < mCellsX; ++x) {
          all.emplace_back(x, z, 1, 1);
        }
      }
      mEveryCell = gl::Buffer(std::span<const glm::ivec2>(waterTriangles(all)));
    }
    mEveryCell.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  } else {
    mCellList.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  }
  mVao.bind();
  glEnable(GL_DEPTH_TEST);
  const bool blend = mView == ShoreWaterView::Shaded;
  if (blend) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  }
  glDepthMask(GL_FALSE);
  if (vertices > 0) {
    glDrawArrays(GL_TRIANGLES, 0, vertices);
  }
  glDepthMask(GL_TRUE);
  if (blend) {
    glDisable(GL_BLEND);
  }
}

} // namespace sylva::scene

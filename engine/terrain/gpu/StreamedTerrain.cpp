#include <sylva/terrain/gpu/StreamedTerrain.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Object.hpp>
#include <sylva/shader/Compiler.hpp>

#include <shared/Terrain.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_map>

namespace sylva::terrain {
namespace {

bool isPowerOfTwo(int n) {
  return n > 0 && (n & (n - 1)) == 0;
}

/** `key` and every ancestor up to the top level. */
void withAncestors(const PyramidInfo& layout, TileKey key, const std::function<void(const TileKey&)>& f) {
  for (; key.level < layout.levels; key = {key.level + 1, key.x >> 1, key.y >> 1}) {
    f(key);
  }
}

/** Distance (metres) from `eye` to a tile's footprint box at heights [lo, hi], over its footprint size. */
float relativeDistance(const PyramidInfo& layout, const TileKey& key, const TileSummary& s,
                       const glm::dvec3& eye) {
  const glm::dvec3 f = tileFootprint(layout, key);
  const double sizeZ = f.z * layout.spacingZ / layout.spacingX;
  const double lo = std::isnan(s.minHeight) ? 0.0 : s.minHeight;
  const double hi = std::isnan(s.maxHeight) ? 0.0 : s.maxHeight;
  const glm::dvec3 nearest =
      glm::clamp(eye, glm::dvec3(f.x, lo, f.y), glm::dvec3(f.x + f.z, hi, f.y + sizeZ));
  return static_cast<float>(glm::length(eye - nearest) / f.z);
}

} // namespace

StreamedTerrain::StreamedTerrain(const shader::Library& library, std::shared_ptr<const TileSource> source,
                                 const StreamedTerrainOptions& options)
    : mSource(std::move(source)), mOptions(options), mLibrary(&library) {
  const PyramidInfo& layout = mSource->layout();
  const int T = layout.tileSize;
  const int P = std::min(mOptions.patchLevel, T);
  if (!isPowerOfTwo(T) || P < 2 || P % 2 != 0 || T % P != 0 || P > 64) {
    fail("streamed terrain: tile size {} and patch level {}: the tile size must be a power of two and the "
         "patch "
         "level even, at most 64 and a divisor of it",
         T, mOptions.patchLevel);
  }
  mOptions.patchLevel = P;
  const int maxLayers = gl::queryContextInfo().maxArrayTextureLayers;
  const std::size_t wanted = mOptions.gpuBudget / layerBytes();
  // Tile records name neighbour layers in 16 bits (StreamTileGpu::flags): at most 65,534 layers.
  mLayerCount = static_cast<int>(
      std::min<std::size_t>({wanted, static_cast<std::size_t>(std::max(maxLayers, 1)), std::size_t{65534}}));
  if (mLayerCount < 64) {
    fail("GPU budget {:.1f} MB holds {} tiles of {}x{} samples; at least 64 are needed (raise --gpu-budget)",
         static_cast<double>(mOptions.gpuBudget) / 1.0e6, mLayerCount, T + 1, T + 1);
  }
  const std::size_t tileRam = layerBytes() + sizeof(TileData);
  if (mOptions.ramBudget < (static_cast<std::size_t>(mLayerCount) + 128) * tileRam) {
    fail("RAM budget {:.1f} MB cannot hold the {} tiles on the GPU and 128 more ({:.1f} MB); raise "
         "--ram-budget "
         "or lower --gpu-budget",
         static_cast<double>(mOptions.ramBudget) / 1.0e6, mLayerCount,
         static_cast<double>((static_cast<std::size_t>(mLayerCount) + 128) * tileRam) / 1.0e6);
  }
  // The always-resident coarsest levels take at most half the GPU layers.
  mStreamer =
      std::make_unique<TileStreamer>(mSource, mOptions.ramBudget, mOptions.loaders,
                                     std::min<std::size_t>(85, static_cast<std::size_t>(mLayerCount) / 2));
  while (glGetError() != GL_NO_ERROR) {
  }
  mHeights = gl::Texture::create2DArray(GL_R32F, T + 1, T + 1, mLayerCount);
  if (glGetError() == GL_OUT_OF_MEMORY) {
    fail("GPU budget: the driver cannot allocate {} tiles ({:.1f} MB) for the tile cache (out of memory; "
         "lower "
         "--gpu-budget)",
         mLayerCount, static_cast<double>(mLayerCount) * static_cast<double>(layerBytes()) / 1.0e6);
  }
  mHeights.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
  gl::setLabel(GL_TEXTURE, mHeights.id(), "streamed terrain tiles");
  mLayers.resize(static_cast<std::size_t>(mLayerCount));
  mProgram = shader::compileProgram(
      library, {"streamed terrain",
                {"terrain/stream.vert", "terrain/stream.tesc", "terrain/stream.tese", "terrain/stream.frag"},
                {}});
  // The coarsest levels (pinned in RAM by the streamer) live on the GPU for good: a stand-in always exists.
  for (int level = layout.levels - 1; level >= mStreamer->pinnedLevel(); --level) {
    const PyramidLevel l = layout.level(level);
    for (int y = 0; y < l.tilesY; ++y) {
      for (int x = 0; x < l.tilesX; ++x) {
        const TileKey key{level, x, y};
        const int layer = freeLayer();
        if (layer < 0) {
          fail("GPU budget: {} layers cannot hold the coarsest levels", mLayerCount);
        }
        upload(key, *mStreamer->get(key), layer);
        mLayers[static_cast<std::size_t>(layer)].lastFrame = ~std::uint64_t{0}; // never evicted
      }
    }
  }
}

StreamedTerrain::~StreamedTerrain() = default;

std::size_t StreamedTerrain::layerBytes() const {
  const auto n = static_cast<std::size_t>(mSource->layout().tileSize + 1);
  return n * n * sizeof(float);
}

int StreamedTerrain::freeLayer() {
  int best = -1;
  for (int k = 0; k < mLayerCount; ++k) {
    const Layer& layer = mLayers[static_cast<std::size_t>(k)];
    if (!layer.used) {
      return k;
    }
    // Layers used this frame (drawn, ancestors of drawn, wanted) are not candidates.
    if (layer.lastFrame < mFrameIndex &&
        (best < 0 || layer.lastFrame < mLayers[static_cast<std::size_t>(best)].lastFrame)) {
      best = k;
    }
  }
  if (best >= 0) {
    Layer& layer = mLayers[static_cast<std::size_t>(best)];
    mLayerOf.erase(layer.key);
    mStreamer->unpin(layer.key);
    layer.used = false;
  }
  return best;
}

void StreamedTerrain::upload(const TileKey& key, const TileData& tile, int layer) {
  const int n = tile.size + 1;
  glTextureSubImage3D(mHeights.id(), 0, 0, 0, layer, n, n, 1, GL_RED, GL_FLOAT, tile.heights.data());
  mStreamer->pin(key);
  mLayers[static_cast<std::size_t>(layer)] = {key, true, mFrameIndex};
  mLayerOf[key] = layer;
}

StreamedFrame StreamedTerrain::update(const glm::dvec3& eye, const glm::dvec3& target,
                                      const glm::dvec3& velocity, float fovY, float aspect, float farPlane) {
  ++mFrameIndex;
  mEye = eye;
  mTarget = target;
  const PyramidInfo& layout = mSource->layout();
  mOriginIndex = glm::ivec2(static_cast<int>(std::floor(eye.x / layout.spacingX)),
                            static_cast<int>(std::floor(eye.z / layout.spacingZ)));
  mOrigin = glm::dvec3(mOriginIndex.x * static_cast<double>(layout.spacingX), 0.0,
                       mOriginIndex.y * static_cast<double>(layout.spacingZ));
  const auto summary = [&](const TileKey& key) { return mSource->tileSummary(key); };
  // The view's frustum relative to the eye (selectTiles' convention); the prefetch view reuses it.
  render::Camera relative;
  relative.position = glm::vec3(0.0f);
  relative.target = glm::vec3(target - eye);
  relative.fovY = fovY;
  relative.nearPlane = 0.5f;
  relative.farPlane = farPlane;
  const Frustum frustum = relative.frustum(aspect);

  // What the view wants (every tile on the way down to the wanted leaves), here and where the camera goes.
  mStreamer->beginFrame();
  std::map<TileKey, float> wanted;
  const auto want = [&](const glm::dvec3& from, float offset) {
    const TileSelection ideal = selectTiles(
        layout, summary, [](const TileKey&) { return true; }, from, &frustum, mOptions.lod);
    for (const TileKey& k : ideal.tree) {
      const float p = offset + static_cast<float>(layout.levels - 1 - k.level) +
                      std::min(relativeDistance(layout, k, summary(k), from), 0.99f);
      auto [it, inserted] = wanted.emplace(k, p);
      if (!inserted) {
        it->second = std::min(it->second, p);
      }
    }
  };
  want(eye, 0.0f);
  if (glm::length(velocity) > 0.0 && mOptions.prefetchSeconds > 0.0f) {
    want(eye + velocity * static_cast<double>(mOptions.prefetchSeconds), 1000.0f);
  }
  // Wanted tiles keep their layers this frame.
  for (const auto& [key, priority] : wanted) {
    const auto it = mLayerOf.find(key);
    if (it != mLayerOf.end()) {
      Layer& layer = mLayers[static_cast<std::size_t>(it->second)];
      layer.lastFrame = std::max(layer.lastFrame, mFrameIndex);
    }
  }
  for (const SelectedTile& t : mSelection.tiles) { // the last frame's tiles stay drawable until replaced
    withAncestors(layout, t.key, [&](const TileKey& k) {
      const auto it = mLayerOf.find(k);
      if (it != mLayerOf.end()) {
        Layer& layer = mLayers[static_cast<std::size_t>(it->second)];
        layer.lastFrame = std::max(layer.lastFrame, mFrameIndex);
      }
    });
  }
  std::vector<std::pair<float, TileKey>> candidates;
  for (const auto& [key, priority] : wanted) {
    if (onGpu(key)) {
      continue;
    }
    if (mStreamer->holds(key)) {
      candidates.emplace_back(priority, key);
    } else {
      mStreamer->request(key, priority);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  StreamedFrame frame;
  for (const auto& [priority, key] : candidates) {
    if (frame.uploads >= mOptions.uploadsPerFrame) {
      break;
    }
    const std::shared_ptr<const TileData> tile = mStreamer->get(key);
    if (!tile) {
      continue;
    }
    const int layer = freeLayer();
    if (layer < 0) {
      break; // every layer is in use this frame: the GPU budget is full
    }
    upload(key, *tile, layer);
    ++frame.uploads;
  }

  mSelection = selectTiles(
      layout, summary, [this](const TileKey& k) { return onGpu(k); }, eye, &frustum, mOptions.lod);
  for (const SelectedTile& t : mSelection.tiles) {
    withAncestors(layout, t.key, [&](const TileKey& k) {
      const auto it = mLayerOf.find(k);
      if (it != mLayerOf.end()) {
        Layer& layer = mLayers[static_cast<std::size_t>(it->second)];
        layer.lastFrame = std::max(layer.lastFrame, mFrameIndex);
      }
    });
  }
  // The tiles the view wants that it could not draw yet: the leaves of the ideal selection not drawn.
  frame.tiles = static_cast<int>(mSelection.tiles.size());
  frame.missing = static_cast<int>(std::count_if(
      wanted.begin(), wanted.end(), [&](const auto& w) { return w.second < 1000.0f && !onGpu(w.first); }));
  frame.waited = frame.missing > 0;
  frame.layersUsed = static_cast<int>(mLayerOf.size());
  const int P = mOptions.patchLevel;
  const std::uint64_t perTile = static_cast<std::uint64_t>(layout.tileSize / P) * (layout.tileSize / P) *
                                static_cast<std::uint64_t>(P + 1) * static_cast<std::uint64_t>(P + 1);
  frame.vertices = perTile * mSelection.tiles.size();

  // The tile records for the draw.
  std::vector<gpu::StreamTileGpu> records;
  records.reserve(mSelection.tiles.size());
  for (const SelectedTile& t : mSelection.tiles) {
    gpu::StreamTileGpu r{};
    r.key = glm::ivec4(t.key.x, t.key.y, t.key.level, mLayerOf.at(t.key));
    // Same-level neighbours on the GPU, for central differences across the tile's border.
    const auto across = [&](int dx, int dy) {
      const auto it = mLayerOf.find(TileKey{t.key.level, t.key.x + dx, t.key.y + dy});
      return it != mLayerOf.end() ? it->second + 1 : 0;
    };
    r.flags = glm::ivec4(static_cast<int>(t.coarserEdges), across(-1, 0) | (across(1, 0) << 16),
                         across(0, -1) | (across(0, 1) << 16), 0);
    records.push_back(r);
  }
  const std::size_t bytes = std::max<std::size_t>(records.size(), 1) * sizeof(gpu::StreamTileGpu);
  if (!mTiles || mTiles.size() < bytes) {
    mTiles = gl::Buffer(std::max(bytes, mTiles ? mTiles.size() * 2 : bytes));
  }
  if (!records.empty()) {
    mTiles.setSubData(0, records.size() * sizeof(gpu::StreamTileGpu), records.data());
  }
  return frame;
}

StreamedFrame StreamedTerrain::updateComplete(const glm::dvec3& eye, const glm::dvec3& target, float fovY,
                                              float aspect, float farPlane) {
  StreamedFrame frame;
  for (int round = 0; round < 10000; ++round) {
    frame = update(eye, target, glm::dvec3(0.0), fovY, aspect, farPlane);
    if (!frame.waited) {
      return frame;
    }
    if (frame.uploads == 0) {
      mStreamer->waitIdle();
      if (mStreamer->stats().failed > 0) {
        fail("streamed terrain: tiles failed to load (see the log)");
      }
    }
  }
  return frame;
}

render::Environment StreamedTerrain::wideEnvironment(double viewDepth) {
  render::Environment e;
  e.fogDensity = static_cast<float>(1.6 / std::max(viewDepth, 100.0));
  return e;
}

glm::vec4 StreamedTerrain::clearColour(const render::Environment& environment) {
  const auto encode = [](float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; // as toSrgb in GLSL
  };
  const glm::vec3 c = environment.fogColor;
  return glm::vec4(encode(c.r), encode(c.g), encode(c.b), 1.0f);
}

render::Camera StreamedTerrain::relativeCamera(float fovY, float nearPlane, float farPlane) const {
  render::Camera c;
  c.position = glm::vec3(mEye - mOrigin);
  c.target = glm::vec3(mTarget - mOrigin);
  c.fovY = fovY;
  c.nearPlane = nearPlane;
  c.farPlane = farPlane;
  return c;
}

void StreamedTerrain::draw(const render::Camera& camera, int width, int height, double time,
                           StreamedView view, const render::Environment& environment, bool points) {
  if (mSelection.tiles.empty()) {
    return;
  }
  const PyramidInfo& layout = mSource->layout();
  const int P = mOptions.patchLevel;
  gpu::StreamUniforms u{};
  u.shape = glm::ivec4(layout.tileSize, P, layout.tileSize / P, static_cast<int>(view));
  u.origin = glm::ivec4(mOriginIndex.x, mOriginIndex.y, 0, 0);
  u.spacing = glm::vec4(layout.spacingX, layout.spacingZ, 0.0f, 0.0f);
  mUniforms.setSubData(0, sizeof(u), &u);
  mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_STREAM_BINDING);
  mTiles.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_STREAM_TILE_BINDING);
  mFrame.bind(camera, width, height, time, environment);
  mHeights.bind(0);
  if (points && !mPoints) {
    mPoints = shader::compileProgram(*mLibrary, {"streamed terrain points",
                                                 {"terrain/stream.vert", "terrain/stream.tesc",
                                                  "terrain/stream.tese", "terrain/stream.frag"},
                                                 {{"SYLVA_STREAM_POINTS", "1"}}});
  }
  gl::Program& program = points ? mPoints : mProgram;
  program.use();
  mVao.bind();
  glPatchParameteri(GL_PATCH_VERTICES, 4);
  const int perTile = (layout.tileSize / P) * (layout.tileSize / P);
  glDrawArraysInstanced(GL_PATCHES, 0, 4, static_cast<GLsizei>(mSelection.tiles.size()) * perTile);
}

float StreamedTerrain::drawnHeightAt(double x, double z) const {
  const PyramidInfo& layout = mSource->layout();
  const auto inTile = [&](const TileKey& key) {
    const glm::dvec3 f = tileFootprint(layout, key);
    return x >= f.x && x <= f.x + f.z && z >= f.y && z <= f.y + f.z * layout.spacingZ / layout.spacingX;
  };
  const auto heightIn = [&](const TileKey& key) {
    const std::shared_ptr<const TileData> tile = mStreamer->get(key);
    return tile ? heightInTile(layout, *tile, x, z) : std::numeric_limits<float>::quiet_NaN();
  };
  for (const SelectedTile& t : mSelection.tiles) {
    if (inTile(t.key)) {
      return heightIn(t.key);
    }
  }
  // Not drawn (culled): the finest tile on the GPU there, as it would be drawn.
  if (x >= 0.0 && z >= 0.0) {
    for (int level = 0; level < layout.levels; ++level) {
      const double span = std::ldexp(static_cast<double>(layout.tileSize), level);
      const TileKey key{level, static_cast<int>(x / (span * layout.spacingX)),
                        static_cast<int>(z / (span * layout.spacingZ))};
      if (onGpu(key) && inTile(key)) {
        return heightIn(key);
      }
    }
  }
  return std::numeric_limits<float>::quiet_NaN();
}

} // namespace sylva::terrain

#include <sylva/trees/gpu/TreeRenderer.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/shader/Compiler.hpp>
#include <sylva/trees/Tessellation.hpp>
#include <sylva/trees/Tree.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sylva::trees {
namespace {

constexpr std::size_t kCommandUints = 5;

/** Culling slack for bends: a bent piece stays within its sphere grown by this factor. */
constexpr float kBendSlack = 1.25f;

} // namespace

TreeRenderer::TreeRenderer(const shader::Library& library, std::shared_ptr<const Forest> forest)
    : mForest(std::move(forest)), mUniforms(sizeof(gpu::TreeUniforms)) {
  const Forest& f = *mForest;
  if (f.pieces.size() > SYLVA_TREE_MAX_PIECES) {
    fail("trees: {} piece types (at most {})", f.pieces.size(), SYLVA_TREE_MAX_PIECES);
  }
  mPacked = packInstances(f);
  // One vertex and index buffer for all piece types; quads as 4-index patches.
  std::vector<PieceVertexGpu> vertices;
  std::vector<std::uint32_t> indices;
  for (std::size_t t = 0; t < f.pieces.size(); ++t) {
    const Piece& piece = f.pieces[t];
    if (piece.joints.size() > SYLVA_TREE_MAX_PIECE_JOINTS) {
      fail("trees: piece '{}' has {} joints (at most {})", piece.name, piece.joints.size(),
           SYLVA_TREE_MAX_PIECE_JOINTS);
    }
    const auto baseVertex = static_cast<std::uint32_t>(vertices.size());
    const auto firstIndex = static_cast<std::uint32_t>(indices.size());
    for (const PieceVertex& v : piece.vertices) {
      PieceVertexGpu g{};
      std::memcpy(g.position, &v.position, sizeof g.position);
      std::memcpy(g.normal, &v.normal, sizeof g.normal);
      std::memcpy(g.weights, &v.weights, sizeof g.weights);
      g.uv[0] = v.u;
      g.uv[1] = v.v;
      std::memcpy(g.joints, v.joints.data(), 4);
      g.rim = v.rim >= 0 ? (v.rim << 8) | v.corner : -1;
      vertices.push_back(g);
    }
    for (const auto& q : piece.quads) {
      indices.insert(indices.end(), q.begin(), q.end());
    }
    mPieceTable.push_back(pieceTableEntry(piece));
    mPieceGeometry.push_back({firstIndex, baseVertex, static_cast<std::uint32_t>(piece.quads.size())});
  }
  // Tile class and rotation of every quad of every piece type (the patch id indexes it).
  std::vector<glm::uvec2> quadTable;
  for (std::size_t t = 0; t < f.pieces.size(); ++t) {
    mQuadFirst[t] = static_cast<std::uint32_t>(quadTable.size());
    const std::vector<glm::uvec2> entries = quadTileTable(f.pieces[t]);
    quadTable.insert(quadTable.end(), entries.begin(), entries.end());
  }
  quadTable.emplace_back(0u);
  mQuadTable = gl::Buffer{std::span<const glm::uvec2>(quadTable)};
  // Tree centres for the far-field fade: base position and crown height in metres.
  mCentres.reserve(f.trees.size() + 1);
  for (const ForestTree& tree : f.trees) {
    const float scale = glm::length(glm::vec3(tree.base[0]));
    const float height = treeStats(f.pieces, tree.topology).height * scale;
    mCentres.emplace_back(glm::vec3(tree.base[3]), height);
  }
  mCentreBuffer = gl::Buffer{
      std::span<const glm::vec4>(mCentres.empty() ? std::vector<glm::vec4>{glm::vec4(0.0f)} : mCentres)};
  mVertexBytes = vertices.size() * sizeof(PieceVertexGpu);
  mIndexBytes = indices.size() * sizeof(std::uint32_t);
  mVertices = gl::Buffer{std::span<const PieceVertexGpu>(vertices)};
  mIndices = gl::Buffer{std::span<const std::uint32_t>(indices)};
  const std::size_t n = std::max<std::size_t>(mPacked.instances.size(), 1);
  mInstances = gl::Buffer(n * sizeof(gpu::TreeInstanceGpu), mPacked.instances.data());
  mPieces = gl::Buffer(std::max<std::size_t>(mPieceTable.size(), 1) * sizeof(gpu::TreePieceGpu));
  mVisible = gl::Buffer(n * sizeof(std::uint32_t));
  std::vector<std::uint32_t> all(n);
  for (std::size_t i = 0; i < n; ++i) {
    all[i] = static_cast<std::uint32_t>(i);
  }
  mAll = gl::Buffer{std::span<const std::uint32_t>(all)};
  useQuadsPerCommand(kMaxQuadsPerCommand);
  mFrames = gl::Buffer(std::max<std::size_t>(f.jointCount, 1) * sizeof(gpu::JointFrame));
  gl::setLabel(GL_BUFFER, mVertices.id(), "tree piece vertices");
  gl::setLabel(GL_BUFFER, mFrames.id(), "tree joint frames");

  // Vertex layout (PieceVertexGpu) and the instanced list attribute, for the culled lists and for all.
  for (gl::VertexArray* vao : {&mVao, &mAllVao}) {
    const GLuint id = vao->id();
    glVertexArrayVertexBuffer(id, 0, mVertices.id(), 0, sizeof(PieceVertexGpu));
    glVertexArrayElementBuffer(id, mIndices.id());
    glVertexArrayAttribFormat(id, 0, 3, GL_FLOAT, GL_FALSE, offsetof(PieceVertexGpu, position));
    glVertexArrayAttribFormat(id, 1, 3, GL_FLOAT, GL_FALSE, offsetof(PieceVertexGpu, normal));
    glVertexArrayAttribIFormat(id, 2, 4, GL_UNSIGNED_BYTE, offsetof(PieceVertexGpu, joints));
    glVertexArrayAttribFormat(id, 3, 4, GL_FLOAT, GL_FALSE, offsetof(PieceVertexGpu, weights));
    glVertexArrayAttribFormat(id, 4, 2, GL_FLOAT, GL_FALSE, offsetof(PieceVertexGpu, uv));
    glVertexArrayAttribIFormat(id, 5, 1, GL_INT, offsetof(PieceVertexGpu, rim));
    for (GLuint a = 0; a < 6; ++a) {
      glVertexArrayAttribBinding(id, a, 0);
      glEnableVertexArrayAttrib(id, a);
    }
    glVertexArrayVertexBuffer(id, 1, vao == &mVao ? mVisible.id() : mAll.id(), 0, sizeof(std::uint32_t));
    glVertexArrayBindingDivisor(id, 1, 1);
    glVertexArrayAttribIFormat(id, 6, 1, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(id, 6, 1);
    glEnableVertexArrayAttrib(id, 6);
  }
  // Rest frames until someone sets others.
  std::vector<gpu::JointFrame> frames;
  forestFrames(f, {}, frames);
  setFrames(frames);
  reloadShaders(library);
}

void TreeRenderer::reloadShaders(const shader::Library& library) {
  gl::Program cull = shader::compileProgram(library, {"trees cull", {"trees/cull.comp"}, {}});
  gl::Program draw = shader::compileProgram(
      library,
      {"trees draw", {"trees/piece.vert", "trees/piece.tesc", "trees/piece.tese", "trees/piece.frag"}, {}});
  gl::Program depth = shader::compileProgram(
      library, {"trees draw depth",
                {"trees/piece.vert", "trees/piece.tesc", "trees/piece.tese", "trees/piece.frag"},
                {{"SYLVA_TREE_DEPTH_ONLY", "1"}}});
  mCull = std::move(cull);
  mDraw = std::move(draw);
  mDrawDepth = std::move(depth);
}

void TreeRenderer::useQuadsPerCommand(std::uint32_t quads) {
  if (quads == mQuadsPerCommand) {
    return;
  }
  // One command per chunk of `quads` quads of a type (all the type's visible instances in each).
  mQuadsPerCommand = quads;
  mCommandsReset.clear();
  for (std::size_t t = 0; t < mPieceTable.size(); ++t) {
    const PieceGeometry& g = mPieceGeometry[t];
    const auto firstCommand = static_cast<std::uint32_t>(mCommandsReset.size() / kCommandUints);
    std::uint32_t chunks = 0;
    for (std::uint32_t q = 0; q < g.quads; q += quads, ++chunks) {
      const std::uint32_t n = std::min(quads, g.quads - q);
      mCommandsReset.insert(mCommandsReset.end(),
                            {n * 4u, 0u, g.firstIndex + q * 4u, g.baseVertex, mPacked.first[t]});
    }
    mPieceTable[t].range = glm::uvec4(firstCommand, chunks, mPacked.first[t], g.quads * 4u);
  }
  if (!mPieceTable.empty()) {
    mPieces.setSubData(std::span<const gpu::TreePieceGpu>(mPieceTable));
  }
  mCommands = gl::Buffer{std::span<const std::uint32_t>(mCommandsReset)};
}

void TreeRenderer::setFrames(std::span<const gpu::JointFrame> frames) {
  if (frames.size() != mForest->jointCount) {
    fail("trees: {} joint frames for {} joints", frames.size(), mForest->jointCount);
  }
  if (!frames.empty()) {
    mFrames.setSubData(frames);
  }
}

void TreeRenderer::useFrames(const gl::Buffer* external) {
  mExternalFrames = external;
}

void TreeRenderer::setBark(std::span<const BarkSet> sets, std::span<const int> speciesSet) {
  if (sets.empty()) {
    mBarkColour = gl::Texture{gl::NoCreate};
    mBarkNormal = gl::Texture{gl::NoCreate};
    mBarkLayers = 0;
    return;
  }
  for (std::size_t i = 0; i < sets.size(); ++i) {
    validate(sets[i], "bark set '" + sets[i].name + "'");
    if (sets[i].tileSize != sets[0].tileSize || sets[i].colour.size() != sets[0].colour.size() ||
        sets[i].classFirst != sets[0].classFirst || sets[i].classCount != sets[0].classCount ||
        sets[i].edgeColours != sets[0].edgeColours) {
      fail("bark set '{}': tile size and class layout differ from bark set '{}'", sets[i].name, sets[0].name);
    }
  }
  const int size = sets[0].tileSize;
  const auto perSet = static_cast<std::uint32_t>(sets[0].colour.size());
  const auto layers = static_cast<int>(perSet * sets.size());
  const int levels = static_cast<int>(std::floor(std::log2(static_cast<float>(size)))) + 1;
  const bool normals =
      std::all_of(sets.begin(), sets.end(), [](const BarkSet& s) { return !s.normal.empty(); });
  gl::Texture colour = gl::Texture::create2DArray(GL_SRGB8_ALPHA8, size, size, layers, levels);
  gl::Texture normal{gl::NoCreate};
  if (normals) {
    normal = gl::Texture::create2DArray(GL_RGBA8, size, size, layers, levels);
  }
  for (std::size_t i = 0; i < sets.size(); ++i) {
    for (std::uint32_t k = 0; k < perSet; ++k) {
      const int layer = static_cast<int>(i * perSet + k);
      colour.upload(sets[i].colour[k], 0, layer);
      if (normals) {
        normal.upload(sets[i].normal[k], 0, layer);
      }
    }
  }
  const gl::SamplerState sampler{GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE};
  colour.setSampler(sampler);
  colour.generateMipmaps();
  gl::setLabel(GL_TEXTURE, colour.id(), "bark tiles");
  if (normals) {
    normal.setSampler(sampler);
    normal.generateMipmaps();
  }
  mBarkColour = std::move(colour);
  mBarkNormal = std::move(normal);
  mBarkLayers = perSet;
  mBarkTileSize = size;
  mBarkNormals = normals;
  mTileFirst = sets[0].classFirst;
  mTileCount = sets[0].classCount;
  mEdgeColours = sets[0].edgeColours;
  for (std::size_t s = 0; s < mSpeciesSet.size(); ++s) {
    const int set = s < speciesSet.size() ? speciesSet[s] : 0;
    if (set < 0 || static_cast<std::size_t>(set) >= sets.size()) {
      fail("bark: species {} uses bark set {} (have {})", s, set, sets.size());
    }
    mSpeciesSet[s] = static_cast<std::uint32_t>(set);
  }
}

void TreeRenderer::uploadUniforms(const render::Camera& camera, float aspect, const TreeLod& lod,
                                  TreeView view, bool breakRims, glm::vec4 sizeCull) {
  gpu::TreeUniforms& u = mLast;
  const Frustum frustum = camera.frustum(aspect);
  for (std::size_t p = 0; p < 6; ++p) {
    u.frustum[p] = frustum.planes()[p];
  }
  u.tess.y = std::clamp(lod.maxLevel, 1.0f, 64.0f);
  u.tess.z = lod.fixedLevel > 0.0f ? std::clamp(lod.fixedLevel, 1.0f, 64.0f) : 0.0f;
  u.tess.w = lod.drawDistance;
  for (std::size_t k = 0; k < SYLVA_TREE_MAX_SPECIES; ++k) {
    // Species beyond the table share its last colour (the shader clamps the index the same way).
    const std::size_t from = std::min(k, mForest->species.size() - 1);
    u.colours[k] =
        glm::vec4(mForest->species.empty() ? Species{}.barkColour : mForest->species[from].barkColour,
                  static_cast<float>(mSpeciesSet[from]));
  }
  for (std::size_t t = 0; t < SYLVA_TREE_MAX_PIECES; ++t) {
    u.quadTable[t / 4][static_cast<glm::length_t>(t % 4)] = mQuadFirst[t];
  }
  for (std::size_t c = 0; c < SYLVA_TREE_MAX_TILE_CLASSES; ++c) {
    // Classes without tiles of their own fall back to class 0 (plain bark).
    // Per class: its first tile and its variants per edge colouring (blocks of K⁴ colourings follow).
    const bool own = mTileCount[c] > 0;
    u.tileFirst[static_cast<glm::length_t>(c)] = own ? mTileFirst[c] : mTileFirst[0];
    u.tileCount[static_cast<glm::length_t>(c)] =
        std::max((own ? mTileCount[c] : mTileCount[0]) / colourings(mEdgeColours), 1u);
  }
  u.bark = glm::vec4(static_cast<float>(mBarkLayers), static_cast<float>(mBarkTileSize),
                     mBarkNormals ? 1.0f : 0.0f, static_cast<float>(mEdgeColours));
  u.far = glm::vec4(lod.farRange, sizeCull.z, sizeCull.w);
  u.info =
      glm::uvec4(static_cast<unsigned>(mPacked.instances.size()), static_cast<unsigned>(mPieceTable.size()),
                 static_cast<unsigned>(view), breakRims ? 1u : 0u);
  u.cull = glm::vec4(kBendSlack, static_cast<float>(mQuadsPerCommand), sizeCull.x, sizeCull.y);
  for (int k = 0; k < kRimCorners; ++k) {
    u.corners[k] = glm::vec4(rimCorner(k), 0.0f);
    u.rimNormals[k] = glm::vec4(rimNormal(k), 0.0f);
  }
  mUniforms.setSubData(0, sizeof(u), &u);
}

void TreeRenderer::bindAll() const {
  mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_TREE_BINDING);
  (mExternalFrames != nullptr ? *mExternalFrames : mFrames)
      .bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_JOINT_BINDING);
  mInstances.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_INSTANCE_BINDING);
  mVisible.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_VISIBLE_BINDING);
  mCommands.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_COMMAND_BINDING);
  mPieces.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_PIECE_BINDING);
  mQuadTable.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_QUAD_BINDING);
  mCentreBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_CENTRE_BINDING);
  if (mBarkLayers > 0) {
    mBarkColour.bind(SYLVA_TREE_BARK_COLOUR_UNIT);
    if (mBarkNormals) {
      mBarkNormal.bind(SYLVA_TREE_BARK_NORMAL_UNIT);
    }
  }
}

void TreeRenderer::cull(const render::Camera& camera, float aspect, const TreeLod& lod,
                        render::GpuTimers* timers) {
  runCull(camera, aspect, lod, glm::vec4(0.0f), timers, {});
}

void TreeRenderer::cull(const render::Camera& camera, int width, int height, const TreeLod& lod,
                        render::GpuTimers* timers, const render::Environment& environment) {
  runCull(camera, static_cast<float>(std::max(width, 1)) / static_cast<float>(std::max(height, 1)), lod,
          glm::vec4(sizeCullTerms(camera.fovY, camera.orthoHeight, height, lod.minPixels),
                    sizeCullTerms(camera.fovY, camera.orthoHeight, height, lod.minWidthPixels)),
          timers, environment);
}

void TreeRenderer::runCull(const render::Camera& camera, float aspect, const TreeLod& lod, glm::vec4 sizeCull,
                           render::GpuTimers* timers, const render::Environment& environment) {
  const render::GpuTimerScope timed(timers, "trees cull");
  useQuadsPerCommand(quadsPerCommand(lod.fixedLevel > 0.0f ? lod.fixedLevel : lod.maxLevel));
  uploadUniforms(camera, aspect, lod, TreeView::Shaded, false, sizeCull);
  mFrame.bind(camera, 1, 1, 0.0, environment); // the cull reads the camera position only
  mCommands.setSubData(std::span<const std::uint32_t>(mCommandsReset));
  bindAll();
  mCull.use();
  const auto n = static_cast<GLuint>(mPacked.instances.size());
  if (n > 0) {
    glDispatchCompute((n + SYLVA_TREE_CULL_GROUP - 1) / SYLVA_TREE_CULL_GROUP, 1, 1);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                  GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

void TreeRenderer::submit(const TreeDrawOptions& options, bool perPiece) {
  const GLboolean culling = glIsEnabled(GL_CULL_FACE);
  GLint cullMode = GL_BACK;
  glGetIntegerv(GL_CULL_FACE_MODE, &cullMode);
  if (options.faces == TreeFaces::Both) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(options.faces == TreeFaces::Front ? GL_BACK : GL_FRONT);
  }
  glPatchParameteri(GL_PATCH_VERTICES, 4);
  const gl::Program& program = options.view == TreeView::Depth ? mDrawDepth : mDraw;
  program.use();
  const GLint drawBase = glGetUniformLocation(program.id(), "uDrawBase");
  glUniform1ui(drawBase, 0u);
  if (perPiece) {
    mAllVao.bind();
    for (std::size_t t = 0; t < mPieceTable.size(); ++t) {
      for (std::uint32_t i = 0; i < mPacked.count[t]; ++i) {
        for (std::uint32_t k = 0; k < mPieceTable[t].range.y; ++k) {
          const std::uint32_t command = mPieceTable[t].range.x + k;
          const std::uint32_t* c = &mCommandsReset[command * kCommandUints];
          // A single draw has gl_DrawID 0: the command index comes as a uniform instead.
          glUniform1ui(drawBase, command);
          glDrawElementsInstancedBaseVertexBaseInstance(
              GL_PATCHES, static_cast<GLsizei>(c[0]), GL_UNSIGNED_INT,
              reinterpret_cast<const void*>(static_cast<std::uintptr_t>(c[2]) * sizeof(std::uint32_t)), 1,
              static_cast<GLint>(c[3]), mPacked.first[t] + i);
        }
      }
    }
    glUniform1ui(drawBase, 0u);
  } else {
    mVao.bind();
    mCommands.bind(GL_DRAW_INDIRECT_BUFFER);
    glMultiDrawElementsIndirect(GL_PATCHES, GL_UNSIGNED_INT, nullptr,
                                static_cast<GLsizei>(mCommandsReset.size() / kCommandUints),
                                kCommandUints * sizeof(std::uint32_t));
  }
  if (culling == GL_TRUE) {
    glEnable(GL_CULL_FACE);
  } else {
    glDisable(GL_CULL_FACE);
  }
  glCullFace(static_cast<GLenum>(cullMode));
}

void TreeRenderer::prepareDraw(const render::Camera& camera, int width, int height, double time,
                               const TreeLod& lod, const TreeDrawOptions& options) {
  uploadUniforms(camera, static_cast<float>(width) / static_cast<float>(std::max(height, 1)), lod,
                 options.view, options.breakRims);
  // Level = K · edge length / distance: K turns metres at a distance into pixels, per target segment length.
  mLast.tess.x = static_cast<float>(height) / (2.0f * std::tan(camera.fovY * 0.5f)) /
                 std::max(lod.pixelsPerSegment, 0.5f);
  mUniforms.setSubData(0, sizeof(mLast), &mLast);
  mFrame.bind(camera, width, height, time, options.environment);
  bindAll();
}

void TreeRenderer::draw(const render::Camera& camera, int width, int height, double time, const TreeLod& lod,
                        render::GpuTimers* timers, const TreeDrawOptions& options) {
  const render::GpuTimerScope timed(timers, "trees");
  prepareDraw(camera, width, height, time, lod, options);
  submit(options, false);
}

void TreeRenderer::drawPerPiece(const render::Camera& camera, int width, int height, double time,
                                const TreeLod& lod, const TreeDrawOptions& options) {
  prepareDraw(camera, width, height, time, lod, options);
  submit(options, true);
}

std::vector<std::uint32_t> TreeRenderer::readVisibleCounts() const {
  std::vector<std::uint32_t> commands(mCommandsReset.size());
  glGetNamedBufferSubData(mCommands.id(), 0, static_cast<GLsizeiptr>(commands.size() * sizeof(std::uint32_t)),
                          commands.data());
  std::vector<std::uint32_t> counts(mPieceTable.size());
  for (std::size_t t = 0; t < counts.size(); ++t) {
    counts[t] = commands[mPieceTable[t].range.x * kCommandUints + 1];
  }
  return counts;
}

std::vector<std::uint32_t> TreeRenderer::readVisible(std::size_t type) const {
  const std::uint32_t count = readVisibleCounts()[type];
  std::vector<std::uint32_t> out(count);
  if (count > 0) {
    glGetNamedBufferSubData(mVisible.id(), static_cast<GLintptr>(mPacked.first[type] * sizeof(std::uint32_t)),
                            static_cast<GLsizeiptr>(count * sizeof(std::uint32_t)), out.data());
  }
  return out;
}

std::size_t TreeRenderer::gpuBytes() const {
  // Tile arrays with their mip chains (4/3 of the base level), colour and normals.
  const std::size_t barkBytes = mBarkLayers == 0
                                    ? 0
                                    : static_cast<std::size_t>(mBarkColour.layers()) * mBarkTileSize *
                                          mBarkTileSize * 4 * 4 / 3 * (mBarkNormals ? 2 : 1);
  return mVertexBytes + mIndexBytes + mPacked.instances.size() * (sizeof(gpu::TreeInstanceGpu) + 8) +
         mPieceTable.size() * sizeof(gpu::TreePieceGpu) + mForest->jointCount * sizeof(gpu::JointFrame) +
         sizeof(gpu::TreeUniforms) + mCentres.size() * sizeof(glm::vec4) + barkBytes;
}

} // namespace sylva::trees

#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace sylva::gl {

/** What the current context is and the limits Sylva relies on. */
struct ContextInfo {
  std::string vendor;                          ///< GL_VENDOR
  std::string renderer;                        ///< GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version;                         ///< GL_VERSION
  std::string glslVersion;                     ///< GL_SHADING_LANGUAGE_VERSION
  int major = 0;                               ///< GL major version
  int minor = 0;                               ///< GL minor version
  bool coreProfile = false;                    ///< a core-profile context
  bool debugContext = false;                   ///< a debug context (KHR_debug output on)
  int maxTessGenLevel = 0;                     ///< GL_MAX_TESS_GEN_LEVEL
  int maxPatchVertices = 0;                    ///< GL_MAX_PATCH_VERTICES
  int maxComputeWorkGroupCount[3] = {0, 0, 0}; ///< GL_MAX_COMPUTE_WORK_GROUP_COUNT per axis
  int maxComputeWorkGroupSize[3] = {0, 0, 0};  ///< GL_MAX_COMPUTE_WORK_GROUP_SIZE per axis
  int maxComputeWorkGroupInvocations = 0;      ///< GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS
  int maxComputeSharedMemory = 0;              ///< GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, bytes
  int maxArrayTextureLayers = 0;               ///< GL_MAX_ARRAY_TEXTURE_LAYERS
  int maxTextureSize = 0;                      ///< GL_MAX_TEXTURE_SIZE, texels
  int maxSamples = 0;                          ///< GL_MAX_SAMPLES
  int maxShaderStorageBlockSize = 0;           ///< GL_MAX_SHADER_STORAGE_BLOCK_SIZE, bytes
  int timestampBits = 0;                       ///< GL_QUERY_COUNTER_BITS of GL_TIMESTAMP (0: no timers)

  /** "llvmpipe" for Mesa's CPU rasteriser, otherwise "gpu": selects golden-image references. */
  std::string deviceClass() const;
  /** The fields as JSON (`sylva info --json`). */
  nlohmann::json toJson() const;
};

/** Queries the current context. */
ContextInfo queryContextInfo();

/**
 * Throws sylva::Error unless the current context is OpenGL ≥ 4.5 core with tessellation and compute
 * (i.e. what every Sylva pass needs); the message says what is missing.
 */
void requireSylvaFeatures(const ContextInfo& info);

} // namespace sylva::gl

#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace sylva::gl {

/** What the current context is and the limits Sylva relies on. */
struct ContextInfo {
  std::string vendor;
  std::string renderer;
  std::string version;
  std::string glslVersion;
  int major = 0;
  int minor = 0;
  bool coreProfile = false;
  bool debugContext = false;
  int maxTessGenLevel = 0;
  int maxPatchVertices = 0;
  int maxComputeWorkGroupCount[3] = {0, 0, 0};
  int maxComputeWorkGroupSize[3] = {0, 0, 0};
  int maxComputeWorkGroupInvocations = 0;
  int maxComputeSharedMemory = 0;
  int maxArrayTextureLayers = 0;
  int maxTextureSize = 0;
  int maxSamples = 0;
  int maxShaderStorageBlockSize = 0;
  int timestampBits = 0;

  /** "llvmpipe" for Mesa's CPU rasteriser, otherwise "gpu": selects golden-image references. */
  std::string deviceClass() const;
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

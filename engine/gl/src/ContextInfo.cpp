#include <sylva/gl/ContextInfo.hpp>

#include <sylva/core/Error.hpp>

#include <epoxy/gl.h>

#include <string>

namespace sylva::gl {

namespace {
std::string str(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s != nullptr ? s : "";
}
int integer(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}
} // namespace

ContextInfo queryContextInfo() {
  ContextInfo info;
  info.vendor = str(GL_VENDOR);
  info.renderer = str(GL_RENDERER);
  info.version = str(GL_VERSION);
  info.glslVersion = str(GL_SHADING_LANGUAGE_VERSION);
  info.major = integer(GL_MAJOR_VERSION);
  info.minor = integer(GL_MINOR_VERSION);
  info.coreProfile = (integer(GL_CONTEXT_PROFILE_MASK) & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
  info.debugContext = (integer(GL_CONTEXT_FLAGS) & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
  info.maxTessGenLevel = integer(GL_MAX_TESS_GEN_LEVEL);
  info.maxPatchVertices = integer(GL_MAX_PATCH_VERTICES);
  for (GLuint i = 0; i < 3; ++i) {
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, i, &info.maxComputeWorkGroupCount[i]);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, i, &info.maxComputeWorkGroupSize[i]);
  }
  info.maxComputeWorkGroupInvocations = integer(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
  info.maxComputeSharedMemory = integer(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE);
  info.maxArrayTextureLayers = integer(GL_MAX_ARRAY_TEXTURE_LAYERS);
  info.maxTextureSize = integer(GL_MAX_TEXTURE_SIZE);
  info.maxSamples = integer(GL_MAX_SAMPLES);
  info.maxShaderStorageBlockSize = integer(GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
  glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &info.timestampBits);
  return info;
}

std::string ContextInfo::deviceClass() const {
  return renderer.find("llvmpipe") != std::string::npos ? "llvmpipe" : "gpu";
}

nlohmann::json ContextInfo::toJson() const {
  return {{"vendor", vendor},
          {"renderer", renderer},
          {"version", version},
          {"glsl", glslVersion},
          {"core_profile", coreProfile},
          {"device_class", deviceClass()},
          {"limits",
           {{"max_tess_gen_level", maxTessGenLevel},
            {"max_patch_vertices", maxPatchVertices},
            {"max_compute_work_group_count",
             {maxComputeWorkGroupCount[0], maxComputeWorkGroupCount[1], maxComputeWorkGroupCount[2]}},
            {"max_compute_work_group_size",
             {maxComputeWorkGroupSize[0], maxComputeWorkGroupSize[1], maxComputeWorkGroupSize[2]}},
            {"max_compute_work_group_invocations", maxComputeWorkGroupInvocations},
            {"max_compute_shared_memory_bytes", maxComputeSharedMemory},
            {"max_array_texture_layers", maxArrayTextureLayers},
            {"max_texture_size", maxTextureSize},
            {"max_samples", maxSamples},
            {"max_shader_storage_block_bytes", maxShaderStorageBlockSize},
            {"timestamp_bits", timestampBits}}}};
}

void requireSylvaFeatures(const ContextInfo& info) {
  if (info.major * 10 + info.minor < 45) {
    fail("OpenGL 4.5 is required; the context is {} ({})", info.version, info.renderer);
  }
  if (!info.coreProfile) {
    fail("an OpenGL core profile context is required; got {}", info.version);
  }
  if (info.maxTessGenLevel < 64 || info.maxComputeWorkGroupInvocations < 256) {
    fail("the driver's tessellation ({}) or compute ({}) limits are below Sylva's needs",
         info.maxTessGenLevel, info.maxComputeWorkGroupInvocations);
  }
}

} // namespace sylva::gl

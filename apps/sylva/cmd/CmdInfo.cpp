#include "Commands.hpp"

#include <sylva/gl/ContextInfo.hpp>

#include <cstdio>
#include <iostream>

namespace sylva::app {

void registerInfo(CLI::App& app) {
  auto* command =
      app.add_subcommand("info", "Print the OpenGL context Sylva gets headless and the limits it relies on");
  struct Options {
    ContextFlags context;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  options->context.add(*command);
  command->add_flag("--json", options->json, "Print JSON instead of text");
  command->callback([options] {
    auto context = platform::createHeadlessContext(options->context.options());
    const gl::ContextInfo info = gl::queryContextInfo();
    if (options->json) {
      nlohmann::json json = info.toJson();
      json["context"] = context->description();
      json["context_attempts"] = context->creationReport();
      json["sylva_version"] = SYLVA_VERSION;
      json["sylva_revision"] = gitRevision();
      std::cout << json.dump(2) << "\n";
      return;
    }
    std::printf("Sylva %s (git %s)\n", SYLVA_VERSION, gitRevision());
    std::printf("context:          %s\n", context->description().c_str());
    std::printf("GL vendor:        %s\n", info.vendor.c_str());
    std::printf("GL renderer:      %s\n", info.renderer.c_str());
    std::printf("GL version:       %s\n", info.version.c_str());
    std::printf("GLSL version:     %s\n", info.glslVersion.c_str());
    std::printf("profile:          %s%s\n", info.coreProfile ? "core" : "compatibility",
                info.debugContext ? ", debug" : "");
    std::printf("device class:     %s (golden references: tests/golden/refs/%s)\n",
                info.deviceClass().c_str(), info.deviceClass().c_str());
    std::printf("limits:\n");
    std::printf("  max tessellation level:           %d\n", info.maxTessGenLevel);
    std::printf("  max patch vertices:               %d\n", info.maxPatchVertices);
    std::printf("  compute work-group count:         %d x %d x %d\n", info.maxComputeWorkGroupCount[0],
                info.maxComputeWorkGroupCount[1], info.maxComputeWorkGroupCount[2]);
    std::printf("  compute work-group size:          %d x %d x %d\n", info.maxComputeWorkGroupSize[0],
                info.maxComputeWorkGroupSize[1], info.maxComputeWorkGroupSize[2]);
    std::printf("  compute invocations per group:    %d\n", info.maxComputeWorkGroupInvocations);
    std::printf("  compute shared memory:            %d bytes\n", info.maxComputeSharedMemory);
    std::printf("  max texture array layers:         %d\n", info.maxArrayTextureLayers);
    std::printf("  max texture size:                 %d\n", info.maxTextureSize);
    std::printf("  max SSBO size:                    %d bytes\n", info.maxShaderStorageBlockSize);
    std::printf("  timestamp query bits:             %d\n", info.timestampBits);
    // Every EGL platform and device tried, with its reason when it failed: what to read when a GPU machine
    // ends up on Mesa instead of its driver.
    std::printf("context creation:\n");
    for (const std::string& line : context->creationReport()) {
      std::printf("  %s\n", line.c_str());
    }
  });
}

} // namespace sylva::app

#pragma once

#include <memory>
#include <string>
#include <vector>

namespace sylva::platform {

/** Options for creating an OpenGL 4.5 core context, headless or windowed. */
struct ContextOptions {
  /** Request a debug context (KHR_debug messages are routed to the log either way when available). */
  bool debug = true;
  /** Headless only: EGL device index to use (-1 = first that works, hardware before software). */
  int eglDevice = -1;
  /** Headless only: "auto", "device" (EGL_EXT_platform_device only) or "surfaceless" (Mesa only). */
  std::string eglPlatform = "auto";
};

/**
 * An OpenGL 4.5 core context, current on the creating thread. Headless contexts have no default framebuffer:
 * render into gl::Framebuffer objects. Not thread-safe; use on one thread.
 */
class GlContext {
public:
  virtual ~GlContext() = default;
  /** Makes the context current on the calling thread. */
  virtual void makeCurrent() = 0;
  /** How the context was made, e.g. "EGL device 0 (EGL_MESA_device_software)" or "GLFW window". */
  virtual std::string description() const = 0;
  /** Presents the default framebuffer (no-op headless). */
  virtual void swapBuffers() {}
  /** True for contexts without a window. */
  virtual bool headless() const = 0;
  /**
   * How creation went, one line each, for `sylva info`: headless contexts list the EGL client extensions seen
   * and every platform/device tried with its outcome (the reason when it failed); windows return nothing.
   */
  virtual std::vector<std::string> creationReport() const { return {}; }
};

/**
 * Creates a headless EGL context: EGL_EXT_platform_device devices first (so NVIDIA GPUs work without X),
 * hardware before software, then EGL_MESA_platform_surfaceless. Devices are enumerated when the client
 * extensions name EGL_EXT_device_enumeration or EGL_EXT_device_base (which includes it; some drivers name
 * only that one). Also routes KHR_debug to the log and checks that the context meets Sylva's needs. Throws
 * sylva::Error listing every attempt and its reason if none works.
 * Environment overrides: SYLVA_EGL_PLATFORM=device|surfaceless, SYLVA_EGL_DEVICE=N.
 */
std::unique_ptr<GlContext> createHeadlessContext(const ContextOptions& options = {});

/** True when EGL can be loaded at all (tests use this to skip with a clear message). */
bool eglAvailable();

} // namespace sylva::platform

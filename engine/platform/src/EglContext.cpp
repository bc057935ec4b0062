// Headless OpenGL through EGL. Order of attempts (as Magnum's windowless EGL application does it): devices of
// EGL_EXT_platform_device, hardware before software, so NVIDIA GPUs work without a display server; then
// Mesa's surfaceless platform. Each attempt that fails is logged at debug level with its reason.
#include <sylva/platform/GlContext.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Debug.hpp>

#include <epoxy/egl.h>

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace sylva::platform {

namespace {

bool hasExtension(const char* list, const std::string& name) {
  if (list == nullptr) {
    return false;
  }
  const std::string all = std::string(" ") + list + " ";
  return all.find(" " + name + " ") != std::string::npos;
}

std::string eglErrorName(EGLint error) {
  switch (error) {
  case EGL_SUCCESS:
    return "EGL_SUCCESS";
  case EGL_NOT_INITIALIZED:
    return "EGL_NOT_INITIALIZED";
  case EGL_BAD_ACCESS:
    return "EGL_BAD_ACCESS";
  case EGL_BAD_ALLOC:
    return "EGL_BAD_ALLOC";
  case EGL_BAD_ATTRIBUTE:
    return "EGL_BAD_ATTRIBUTE";
  case EGL_BAD_CONFIG:
    return "EGL_BAD_CONFIG";
  case EGL_BAD_CONTEXT:
    return "EGL_BAD_CONTEXT";
  case EGL_BAD_DISPLAY:
    return "EGL_BAD_DISPLAY";
  case EGL_BAD_MATCH:
    return "EGL_BAD_MATCH";
  case EGL_BAD_PARAMETER:
    return "EGL_BAD_PARAMETER";
  default:
    return fmt::format("EGL error 0x{:x}", error);
  }
}

// eglTerminate invalidates every context on a display, so displays are reference-counted across contexts.
std::mutex gDisplayMutex;
std::map<EGLDisplay, int> gDisplayUsers;

void retainDisplay(EGLDisplay display) {
  const std::lock_guard lock(gDisplayMutex);
  ++gDisplayUsers[display];
}

void releaseDisplay(EGLDisplay display) {
  const std::lock_guard lock(gDisplayMutex);
  if (--gDisplayUsers[display] == 0) {
    gDisplayUsers.erase(display);
    eglTerminate(display);
  }
}

class EglContext final : public GlContext {
public:
  EglContext(EGLDisplay display, EGLContext context, std::string description)
      : mDisplay(display), mContext(context), mDescription(std::move(description)) {}
  void setReport(std::vector<std::string> report) { mReport = std::move(report); }
  ~EglContext() override {
    if (eglGetCurrentContext() == mContext) {
      eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(mDisplay, mContext);
    releaseDisplay(mDisplay);
  }
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void makeCurrent() override {
    if (eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, mContext) != EGL_TRUE) {
      fail("EGL: eglMakeCurrent failed ({})", eglErrorName(eglGetError()));
    }
  }
  std::string description() const override { return mDescription; }
  bool headless() const override { return true; }
  std::vector<std::string> creationReport() const override { return mReport; }

private:
  EGLDisplay mDisplay;
  EGLContext mContext;
  std::string mDescription;
  std::vector<std::string> mReport;
};

/** Initialises `display` and creates a current 4.5 core context on it; returns nullptr with `why` on failure.
 */
std::unique_ptr<EglContext> tryDisplay(EGLDisplay display, const ContextOptions& options,
                                       const std::string& name, std::string& why) {
  if (display == EGL_NO_DISPLAY) {
    why = "no display";
    return nullptr;
  }
  EGLint major = 0;
  EGLint minor = 0;
  if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
    why = "eglInitialize: " + eglErrorName(eglGetError());
    return nullptr;
  }
  retainDisplay(display);
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!hasExtension(extensions, "EGL_KHR_surfaceless_context")) {
    why = "no EGL_KHR_surfaceless_context";
    releaseDisplay(display);
    return nullptr;
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    why = "eglBindAPI(EGL_OPENGL_API): " + eglErrorName(eglGetError());
    releaseDisplay(display);
    return nullptr;
  }
  EGLConfig config = nullptr;
  if (!hasExtension(extensions, "EGL_KHR_no_config_context")) {
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLint count = 0;
    if (eglChooseConfig(display, attribs, &config, 1, &count) != EGL_TRUE || count == 0) {
      why = "no OpenGL-capable EGL config";
      releaseDisplay(display);
      return nullptr;
    }
  }
  std::vector<EGLint> attribs = {EGL_CONTEXT_MAJOR_VERSION,       4,
                                 EGL_CONTEXT_MINOR_VERSION,       5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
  if (options.debug && major * 10 + minor >= 15) {
    attribs.insert(attribs.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
  }
  attribs.push_back(EGL_NONE);
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
  if (context == EGL_NO_CONTEXT && options.debug) {
    // Some drivers refuse debug contexts; KHR_debug still works on most non-debug contexts.
    attribs.resize(6);
    attribs.push_back(EGL_NONE);
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
  }
  if (context == EGL_NO_CONTEXT) {
    why = "eglCreateContext(4.5 core): " + eglErrorName(eglGetError());
    releaseDisplay(display);
    return nullptr;
  }
  if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
    why = "eglMakeCurrent: " + eglErrorName(eglGetError());
    eglDestroyContext(display, context);
    releaseDisplay(display);
    return nullptr;
  }
  return std::make_unique<EglContext>(display, context, name + fmt::format(", EGL {}.{}", major, minor));
}

/**
 * Tries every EGL device (EGL_EXT_platform_device), hardware before software, appending one line per device
 * (or one saying why devices could not be listed) to `attempts`. The entry points are resolved with
 * eglGetProcAddress, so a libEGL that names only EGL_EXT_device_base (which includes enumeration and query)
 * works as well as one that names EGL_EXT_device_enumeration.
 */
void tryDevices(const char* clientExtensions, const ContextOptions& options,
                std::vector<std::string>& attempts, std::unique_ptr<EglContext>& context) {
  if (!hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
    attempts.emplace_back("EGL devices: EGL_EXT_platform_device not in the client extensions");
    return;
  }
  const bool enumeration = hasExtension(clientExtensions, "EGL_EXT_device_enumeration") ||
                           hasExtension(clientExtensions, "EGL_EXT_device_base");
  if (!enumeration) {
    attempts.emplace_back(
        "EGL devices: neither EGL_EXT_device_enumeration nor EGL_EXT_device_base in the client extensions");
    return;
  }
  const auto queryDevices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  const auto queryDeviceString =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  const auto platformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (queryDevices == nullptr || platformDisplay == nullptr) {
    attempts.emplace_back(fmt::format("EGL devices: libEGL returns no {}", queryDevices == nullptr
                                                                               ? "eglQueryDevicesEXT"
                                                                               : "eglGetPlatformDisplayEXT"));
    return;
  }
  EGLint count = 0;
  if (queryDevices(0, nullptr, &count) != EGL_TRUE || count <= 0) {
    attempts.emplace_back(fmt::format("EGL devices: none listed ({})", eglErrorName(eglGetError())));
    return;
  }
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  queryDevices(count, devices.data(), &count);
  // Hardware devices first: Mesa lists its software rasteriser as a device too.
  std::vector<std::pair<int, bool>> order;
  for (int i = 0; i < count; ++i) {
    const char* deviceExtensions =
        queryDeviceString != nullptr ? queryDeviceString(devices[static_cast<std::size_t>(i)], EGL_EXTENSIONS)
                                     : nullptr;
    order.emplace_back(i, hasExtension(deviceExtensions, "EGL_MESA_device_software"));
  }
  std::stable_sort(order.begin(), order.end(), [](auto a, auto b) { return !a.second && b.second; });
  for (const auto& [index, software] : order) {
    const std::string name = fmt::format("EGL device {} ({})", index, software ? "software" : "hardware");
    if (options.eglDevice >= 0 && index != options.eglDevice) {
      attempts.push_back(fmt::format("{}: skipped (--egl-device {})", name, options.eglDevice));
      continue;
    }
    std::string why;
    EGLDisplay display =
        platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(index)], nullptr);
    context = tryDisplay(display, options, name, why);
    attempts.push_back(name + ": " + (context ? std::string("ok") : why));
    log::debug("{}", attempts.back());
    if (context) {
      return;
    }
  }
}

std::string envOr(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : fallback;
}

} // namespace

bool eglAvailable() {
  static const bool kAvailable = [] {
    void* handle = ::dlopen("libEGL.so.1", RTLD_LAZY | RTLD_LOCAL);
    if (handle == nullptr) {
      return false;
    }
    ::dlclose(handle);
    return true;
  }();
  return kAvailable;
}

std::unique_ptr<GlContext> createHeadlessContext(const ContextOptions& requested) {
  if (!eglAvailable()) {
    fail("EGL is not available (libEGL.so.1 not found; install libegl1 and a driver such as libegl-mesa0)");
  }
  ContextOptions options = requested;
  options.eglPlatform = envOr("SYLVA_EGL_PLATFORM", options.eglPlatform);
  options.eglDevice = std::stoi(envOr("SYLVA_EGL_DEVICE", std::to_string(options.eglDevice)));
  if (options.eglPlatform != "auto" && options.eglPlatform != "device" &&
      options.eglPlatform != "surfaceless") {
    fail("EGL platform '{}' is unknown (expected auto, device or surfaceless)", options.eglPlatform);
  }
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  std::vector<std::string> attempts; // "<platform or device>: <ok | reason>", in the order tried
  std::unique_ptr<EglContext> context;

  if (options.eglPlatform != "surfaceless") {
    tryDevices(clientExtensions, options, attempts, context);
  }
  if (!context && options.eglPlatform != "device") {
    if (!hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
      attempts.emplace_back(
          "EGL Mesa surfaceless: EGL_MESA_platform_surfaceless not in the client extensions");
    } else {
      std::string why;
      EGLDisplay display =
          eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      context = tryDisplay(display, options, "EGL Mesa surfaceless", why);
      attempts.push_back("EGL Mesa surfaceless: " + (context ? std::string("ok") : why));
    }
  }
  if (!context) {
    std::string all;
    for (const std::string& a : attempts) {
      all += (all.empty() ? "" : "; ") + a;
    }
    fail("no headless OpenGL 4.5 core context could be created ({}; EGL client extensions: {})",
         all.empty() ? "no EGL platform" : all, clientExtensions != nullptr ? clientExtensions : "none");
  }
  std::vector<std::string> report{
      fmt::format("EGL client extensions: {}", clientExtensions != nullptr ? clientExtensions : "none")};
  report.insert(report.end(), attempts.begin(), attempts.end());
  context->setReport(std::move(report));
  gl::enableDebugOutput();
  const gl::ContextInfo info = gl::queryContextInfo();
  gl::requireSylvaFeatures(info);
  log::debug("OpenGL {} on {} via {}", info.version, info.renderer, context->description());
  return std::unique_ptr<GlContext>(std::move(context));
}

} // namespace sylva::platform

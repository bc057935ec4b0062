// Context creation paths. These tests make their own contexts, so they do not use the shared GlTest fixture;
// each CTest test runs in its own process.
#include <sylva/core/Error.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/platform/GlContext.hpp>
#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/gpu/DemoScene.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>

#include "Golden.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

namespace sylva::platform {
namespace {

bool required(const char* variable) {
  const char* value = std::getenv(variable);
  return value != nullptr && std::string(value) == "1";
}

#define SKIP_WITHOUT_EGL()                                                                                   \
  if (!eglAvailable()) {                                                                                     \
    if (required("SYLVA_REQUIRE_GL")) {                                                                      \
      FAIL() << "libEGL missing and SYLVA_REQUIRE_GL=1";                                                     \
    }                                                                                                        \
    GTEST_SKIP() << "libEGL.so.1 not available; headless context tests skipped";                             \
  }

TEST(HeadlessContext, AutoGivesCore45WithTessellationAndCompute) {
  SKIP_WITHOUT_EGL();
  auto context = createHeadlessContext();
  ASSERT_TRUE(context);
  EXPECT_TRUE(context->headless());
  const gl::ContextInfo info = gl::queryContextInfo();
  EXPECT_GE(info.major * 10 + info.minor, 45);
  EXPECT_TRUE(info.coreProfile);
  EXPECT_GE(info.maxTessGenLevel, 64);
  EXPECT_GE(info.maxArrayTextureLayers, 256);
}

TEST(HeadlessContext, DevicePlatformWorks) {
  SKIP_WITHOUT_EGL();
  ContextOptions options;
  options.eglPlatform = "device";
  auto context = createHeadlessContext(options);
  EXPECT_NE(context->description().find("EGL device"), std::string::npos) << context->description();
}

TEST(HeadlessContext, MesaSurfacelessWorks) {
  SKIP_WITHOUT_EGL();
  ContextOptions options;
  options.eglPlatform = "surfaceless";
  try {
    auto context = createHeadlessContext(options);
    EXPECT_NE(context->description().find("surfaceless"), std::string::npos) << context->description();
  } catch (const Error& e) {
    GTEST_SKIP() << "no Mesa surfaceless platform here (" << e.what() << ")";
  }
}

// `sylva info` prints this report; on a GPU machine it is what tells why the driver was not used.
TEST(HeadlessContext, CreationReportListsClientExtensionsAndEveryAttempt) {
  SKIP_WITHOUT_EGL();
  auto context = createHeadlessContext();
  const std::vector<std::string> report = context->creationReport();
  ASSERT_GE(report.size(), 2u);
  EXPECT_EQ(report.front().rfind("EGL client extensions: ", 0), 0u) << report.front();
  EXPECT_NE(report.front().find("EGL_EXT_platform_device"), std::string::npos) << report.front();
  // The last attempt is the one that worked, and names the context the description names.
  EXPECT_EQ(report.back().substr(report.back().size() - 4), ": ok") << report.back();
  EXPECT_EQ(context->description().rfind(report.back().substr(0, report.back().size() - 4), 0), 0u)
      << context->description() << " vs " << report.back();
}

TEST(HeadlessContext, DeviceIndexThatDoesNotExistListsEveryDevice) {
  SKIP_WITHOUT_EGL();
  ContextOptions options;
  options.eglPlatform = "device";
  options.eglDevice = 99;
  try {
    auto context = createHeadlessContext(options);
    FAIL() << "device 99 should not exist: " << context->description();
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("skipped (--egl-device 99)"), std::string::npos) << message;
    EXPECT_NE(message.find("EGL client extensions:"), std::string::npos) << message;
  }
}

TEST(HeadlessContext, UnknownPlatformIsAClearError) {
  SKIP_WITHOUT_EGL();
  ContextOptions options;
  options.eglPlatform = "x11";
  EXPECT_THROW(createHeadlessContext(options), Error);
}

// The viewer path: a real GLFW window (under Xvfb in CI) renders the demo into its default framebuffer, and
// the frame read back matches the headless golden reference of the same view.
TEST(Window, RendersTheDemoLikeTheHeadlessPath) {
  if (!displayAvailable()) {
    if (required("SYLVA_REQUIRE_DISPLAY")) {
      FAIL() << "no display and SYLVA_REQUIRE_DISPLAY=1 (run under xvfb-run)";
    }
    GTEST_SKIP() << "no display (set DISPLAY or run under xvfb-run); window test skipped";
  }
  GlfwWindow window(320, 240, "sylva window test", true);
  const glm::ivec2 size = window.framebufferSize();
  ASSERT_EQ(size, glm::ivec2(320, 240));
  render::DemoScene scene{shader::Library()};
  gl::bindDefaultFramebuffer(size.x, size.y);
  glEnable(GL_DEPTH_TEST);
  glClearColor(0.62f, 0.72f, 0.85f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  scene.render(scene.defaultCamera(), size.x, size.y, 1.0);
  glFinish();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  const Image frame = render::readFramebuffer(size.x, size.y);
  window.swapBuffers();
  // Same renderer, same inputs: only the window-system path differs. Allow tiny rasteriser-path differences.
  test::expectGolden(frame, "demo_320x240", {2, 0.001});
}

} // namespace
} // namespace sylva::platform

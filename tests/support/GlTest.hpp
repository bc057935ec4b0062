#pragma once

#include <sylva/platform/GlContext.hpp>
#include <sylva/shader/Library.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace sylva::test {

/**
 * Fixture for tests that need a headless OpenGL 4.5 core context (EGL). One context per test process. A test
 * is skipped with a clear message where no context can be created, unless SYLVA_REQUIRE_GL=1 (set by the
 * project's test command), where that is a failure. Any GL error reported through KHR_debug or glGetError
 * during the test fails it.
 */
class GlTest : public ::testing::Test {
protected:
  void SetUp() override;
  void TearDown() override;

  /** The embedded shader library. */
  static const shader::Library& shaders();
  /** True when the renderer is Mesa llvmpipe. */
  static bool onLlvmpipe();
};

/** Creates (once) and returns the process's headless context, or nullptr with `why` filled. */
platform::GlContext* sharedContext(std::string* why = nullptr);

} // namespace sylva::test

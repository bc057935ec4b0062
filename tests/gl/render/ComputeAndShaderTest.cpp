#include <sylva/core/Error.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/render/gpu/DemoScene.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/shader/Compiler.hpp>

#include "GlTest.hpp"

#include <cmath>

namespace sylva::render {
namespace {

using DemoGl = test::GlTest;

TEST_F(DemoGl, ComputeHeightsMatchCpuReference) {
  DemoSettings settings;
  settings.fieldSize = 100; // not a multiple of the work-group size: exercises the bounds check
  DemoScene scene(shaders(), settings);
  RenderTarget target(64, 64);
  target.begin(glm::vec4(0.0f));
  const double time = 2.75;
  scene.render(scene.defaultCamera(), 64, 64, time);
  const Image gpu = scene.heights().download(1, PixelType::F32);
  float worst = 0.0f;
  for (int j = 0; j < settings.fieldSize; ++j) {
    for (int i = 0; i < settings.fieldSize; ++i) {
      // GL images are stored bottom-up, but texel (i, j) is row j in both: no flip for data textures.
      const float cpu = demoHeightReference(settings, time, i, j);
      worst = std::max(worst, std::abs(gpu.get(i, j, 0) - cpu));
    }
  }
  // GPU sin/cos/exp are not correctly rounded; 1 mm on a 28 m field is far below anything visible.
  EXPECT_LT(worst, 1e-3f);
}

TEST_F(DemoGl, EveryStageCompilesWithTheDriver) {
  int compiled = 0;
  for (const std::string& path : shaders().list()) {
    GLenum stage = 0;
    try {
      stage = shader::stageForPath(path);
    } catch (const Error&) {
      continue; // include files
    }
    const shader::Preprocessed pre = shader::preprocess(shaders(), path);
    // Compile only: tessellation stages cannot link on their own.
    const GLuint shader = glCreateShader(stage);
    const char* text = pre.source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    glDeleteShader(shader);
    EXPECT_EQ(ok, GL_TRUE) << path << ": " << gl::translateShaderLog(log, pre.files);
    ++compiled;
  }
  EXPECT_GE(compiled, 5);
}

TEST_F(DemoGl, TimersReportEveryPass) {
  DemoScene scene(shaders());
  RenderTarget target(64, 64);
  GpuTimers timers(2, true);
  for (int i = 0; i < 3; ++i) {
    timers.beginFrame();
    target.begin(glm::vec4(0.0f));
    scene.render(scene.defaultCamera(), 64, 64, 1.0, &timers);
    timers.endFrame();
  }
  ASSERT_EQ(timers.lastFrame().size(), 2u);
  EXPECT_EQ(timers.lastFrame()[0].name, "heights");
  EXPECT_EQ(timers.lastFrame()[1].name, "surface");
  for (const PassTiming& t : timers.lastFrame()) {
    EXPECT_GE(t.gpuMs, 0.0);
    EXPECT_GE(t.cpuMs, 0.0);
  }
}

TEST_F(DemoGl, CountedPassesReportTheWorkTheyMade) {
  // A triangle over the lower-left half of a 64×32 target, inside the clip volume, and a 10×3 dispatch of
  // 8-wide groups: counts known in advance.
  const gl::Program draw({{GL_VERTEX_SHADER,
                           "#version 450\nconst vec2 p[3] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(-1, 1));\n"
                           "void main() { gl_Position = vec4(p[gl_VertexID], 0, 1); }\n",
                           {"tri.vert"}},
                          {GL_FRAGMENT_SHADER,
                           "#version 450\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1); }\n",
                           {"tri.frag"}}},
                         "counted triangle");
  const gl::Program compute(
      {{GL_COMPUTE_SHADER, "#version 450\nlayout(local_size_x = 8) in;\nvoid main() {}\n", {"empty.comp"}}},
      "counted dispatch");
  RenderTarget target(64, 32);
  const gl::VertexArray empty;
  GpuTimers timers(1, true, true);
  timers.beginFrame();
  target.begin(glm::vec4(0.0f));
  timers.begin("draw");
  draw.use();
  empty.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  timers.end();
  timers.begin("compute");
  compute.use();
  glDispatchCompute(10, 3, 1);
  timers.end();
  timers.endFrame();
  ASSERT_EQ(timers.lastFrame().size(), 2u);
  const PassCounts& d = timers.lastFrame()[0].counts;
  ASSERT_TRUE(d.counted());
  EXPECT_EQ(d.verticesSubmitted, 3);
  EXPECT_EQ(d.primitivesSubmitted, 1);
  EXPECT_EQ(d.vertexInvocations, 3);
  EXPECT_EQ(d.tessEvaluations, 0);
  EXPECT_EQ(d.clippedPrimitives, 1);
  // Half of the 2,048 pixel centres, plus at most the helper invocations a driver runs in 2×2 quads along the
  // diagonal edge.
  EXPECT_GE(d.fragmentInvocations, 64 * 32 / 2 - 64);
  EXPECT_LE(d.fragmentInvocations, 64 * 32 / 2 + 4 * 64);
  EXPECT_EQ(d.computeInvocations, 0);
  const PassCounts& c = timers.lastFrame()[1].counts;
  EXPECT_EQ(c.computeInvocations, 10 * 3 * 8);
  EXPECT_EQ(c.verticesSubmitted, 0);
  EXPECT_EQ(c.fragmentInvocations, 0);
  EXPECT_THROW(GpuTimers(1, false, true), Error); // counting waits for results: synchronous only
}

TEST_F(DemoGl, SameTimeSameImage) {
  DemoScene scene(shaders());
  RenderTarget target(96, 64);
  auto frame = [&](double time) {
    target.begin(glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
    scene.render(scene.defaultCamera(), 96, 64, time);
    return target.readColor();
  };
  const Image a = frame(1.5);
  EXPECT_EQ(frame(1.5), a) << "rendering must be deterministic";
  EXPECT_NE(frame(3.0), a) << "time must animate the scene";
}

} // namespace
} // namespace sylva::render

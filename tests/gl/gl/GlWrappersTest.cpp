#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Query.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/shader/Compiler.hpp>

#include "GlTest.hpp"
#include "TempDir.hpp"

#include <numeric>

namespace sylva::gl {
namespace {

using GlWrappers = test::GlTest;

TEST_F(GlWrappers, BufferRoundTripAndBounds) {
  std::vector<std::uint32_t> values(1000);
  std::iota(values.begin(), values.end(), 7u);
  Buffer buffer{std::span<const std::uint32_t>(values)};
  EXPECT_EQ(buffer.size(), 4000u);
  EXPECT_EQ(buffer.read<std::uint32_t>(), values);
  const std::uint32_t patch[2] = {1, 2};
  buffer.setSubData(std::span<const std::uint32_t>(patch), 8);
  EXPECT_EQ(buffer.read<std::uint32_t>()[2], 1u);
  EXPECT_THROW(buffer.setSubData(3999, 8, patch), Error);
  buffer.clear();
  EXPECT_EQ(buffer.read<std::uint32_t>()[500], 0u);
}

TEST_F(GlWrappers, MoveTransfersOwnershipAndDestructionDeletes) {
  GLuint name = 0;
  {
    Buffer a(64);
    name = a.id();
    EXPECT_TRUE(glIsBuffer(name));
    Buffer b(std::move(a));
    EXPECT_EQ(a.id(), 0u); // NOLINT(bugprone-use-after-move): checking the moved-from state is the point
    EXPECT_EQ(b.id(), name);
    Buffer c(NoCreate);
    EXPECT_FALSE(c);
    c = std::move(b);
    EXPECT_EQ(c.id(), name);
  }
  EXPECT_FALSE(glIsBuffer(name));
}

TEST_F(GlWrappers, TextureUploadDownloadAllTypes) {
  for (PixelType type : {PixelType::U8, PixelType::U16, PixelType::F32}) {
    Image image(17, 9, 4, type);
    for (int y = 0; y < 9; ++y) {
      for (int x = 0; x < 17; ++x) {
        for (int c = 0; c < 4; ++c) {
          image.set(x, y, c, static_cast<float>((x + 3 * y + 5 * c) % 11) / 10.0f);
        }
      }
    }
    const Texture texture = Texture::fromImage(image);
    EXPECT_EQ(texture.download(4, type), image) << pixelTypeName(type);
  }
}

TEST_F(GlWrappers, TextureArrayLayersAreIndependent) {
  Texture array = Texture::create2DArray(GL_R32F, 4, 4, 3);
  for (int layer = 0; layer < 3; ++layer) {
    Image image(4, 4, 1, PixelType::F32);
    for (float& v : image.values<float>()) {
      v = static_cast<float>(layer * 10);
    }
    array.upload(image, 0, layer);
  }
  EXPECT_EQ(array.download(1, PixelType::F32, 0, 2).values<float>()[5], 20.0f);
  EXPECT_EQ(array.download(1, PixelType::F32, 0, 1).values<float>()[0], 10.0f);
  EXPECT_THROW(Texture::create2D(GL_RGBA8, 0, 4), Error);
}

TEST_F(GlWrappers, FramebufferClearsAndReadsBack) {
  Texture color = Texture::create2D(GL_RGBA8, 8, 8);
  Framebuffer fb;
  fb.attachColor(0, color);
  fb.checkComplete();
  fb.clearColor(0, {1.0f, 0.5f, 0.0f, 1.0f});
  const Image image = color.download(4, PixelType::U8);
  EXPECT_EQ(image.values<std::uint8_t>()[0], 255);
  EXPECT_NEAR(image.values<std::uint8_t>()[1], 128, 1);
  Framebuffer empty;
  EXPECT_THROW(empty.checkComplete(), Error);
}

TEST_F(GlWrappers, CompileErrorsNameFileAndLine) {
  test::TempDir dir;
  writeTextFile(dir / "bad.frag", "#version 450 core\n#include \"lib.glsl\"\nvoid main() {}\n");
  writeTextFile(dir / "lib.glsl", "float ok() { return 1.0; }\nfloat broken() { return undefinedThing; }\n");
  const shader::Library library(dir.path());
  try {
    shader::compileProgram(library, {"bad", {"bad.frag"}, {}});
    FAIL() << "expected a compile error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lib.glsl:2"), std::string::npos) << e.what();
  }
}

TEST_F(GlWrappers, TimestampsIncreaseAndFencesSignal) {
  Query a(GL_TIMESTAMP);
  Query b(GL_TIMESTAMP);
  a.timestamp();
  Texture t = Texture::create2D(GL_RGBA8, 256, 256);
  Framebuffer fb;
  fb.attachColor(0, t);
  fb.clearColor(0, glm::vec4(1.0f));
  b.timestamp();
  const Sync sync = Sync::fence();
  EXPECT_TRUE(sync.clientWait(5'000'000'000ULL));
  EXPECT_GE(*b.result(), *a.result());
}

TEST_F(GlWrappers, GlErrorsAreReportedToTests) {
  // Binding a name that was never generated is GL_INVALID_OPERATION in core profile: the debug callback must
  // record it (GlTest::TearDown turns recorded errors into failures; cleared here because it is expected).
  clearDebugErrors();
  glBindBuffer(GL_ARRAY_BUFFER, 987654);
  glFinish();
  const bool reported = !debugErrors().empty() || !drainGlErrors().empty();
  EXPECT_TRUE(reported);
  clearDebugErrors();
  drainGlErrors();
}

} // namespace
} // namespace sylva::gl

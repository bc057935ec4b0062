#pragma once

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>

namespace sylva::render {

/** Parameters of the built-in demo scene. */
struct DemoSettings {
  int patches = 16;          ///< patches per side of the square grid
  float worldSize = 400.0f;  ///< metres per side
  float heightScale = 28.0f; ///< metres
  float tessLevel = 24.0f;   ///< base tessellation level near the camera (1..64)
  int fieldSize = 256;       ///< height texture texels per side
};

/**
 * CPU reference of the demo's compute pass (shaders/demo/heights.comp): height in metres of texel (i, j) of
 * the `settings.fieldSize`² field at `time` seconds. Texel centres sit at world xz = ((i + 0.5) / size - 0.5)
 * · worldSize.
 */
float demoHeightReference(const DemoSettings& settings, double time, int i, int j);

/**
 * The small built-in scene that exercises the whole pipeline: a compute pass writes an animated height field
 * into an r32f texture; one instanced draw of attribute-less quad patches is tessellated (per-edge levels
 * from distance), displaced by that texture and shaded with sun, sky and fog. Used by `sylva
 * render`/`view`/`bench` and the golden tests. Needs a current GL context.
 */
class DemoScene {
public:
  /** Compiles the programs from `library` and allocates the height texture `settings` describe. */
  DemoScene(const shader::Library& library, const DemoSettings& settings = {});

  /** Recompiles the programs from `library` (viewer hot reload); keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);
  /** Compute pass ("heights") then draw pass ("surface") into the bound framebuffer at `time` seconds. */
  void render(const Camera& camera, int width, int height, double time, GpuTimers* timers = nullptr,
              bool wireframe = false);
  /** A camera that frames the scene. */
  Camera defaultCamera() const;
  /** The settings the scene was made with. */
  const DemoSettings& settings() const { return mSettings; }
  /** The r32f height texture the compute pass writes. */
  const gl::Texture& heights() const { return mHeights; }

private:
  DemoSettings mSettings;
  gl::Program mCompute{gl::NoCreate};
  gl::Program mSurface{gl::NoCreate};
  gl::Texture mHeights;
  gl::Buffer mUniforms;
  gl::VertexArray mVao;
  FrameUniformBuffer mFrame;
};

} // namespace sylva::render

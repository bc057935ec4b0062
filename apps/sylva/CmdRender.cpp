#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/render/DemoScene.hpp>
#include <sylva/render/RenderTarget.hpp>

#include <cstdio>

namespace sylva::app {

void registerRender(CLI::App& app) {
  auto* command = app.add_subcommand("render", "Render a scene headless into a PNG image");
  struct Options {
    ContextFlags context;
    std::string out = "out/demo.png";
    int width = 1280;
    int height = 720;
    double time = 1.0;
    render::DemoSettings demo;
    bool wireframe = false;
    std::string shaderDir;
  };
  auto o = std::make_shared<Options>();
  o->context.add(*command);
  command->add_option("-o,--out", o->out, "Output PNG path (directories are created)")->capture_default_str();
  command->add_option("--width", o->width, "Image width in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  command->add_option("--height", o->height, "Image height in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  command->add_option("--time", o->time, "Scene time in seconds (fixed clock: same time, same image)")
      ->capture_default_str();
  command->add_option("--tess", o->demo.tessLevel, "Base tessellation level (1..64)")
      ->check(CLI::Range(1.0f, 64.0f))
      ->capture_default_str();
  command->add_option("--patches", o->demo.patches, "Demo patches per side")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  command->add_flag("--wireframe", o->wireframe, "Draw triangle edges only");
  command
      ->add_option("--shader-dir", o->shaderDir,
                   "Read shaders from this directory instead of the embedded copies")
      ->check(CLI::ExistingDirectory);
  command->callback([o] {
    auto context = platform::createHeadlessContext(o->context.options());
    shader::Library library(o->shaderDir);
    render::DemoScene scene(library, o->demo);
    render::RenderTarget target(o->width, o->height);
    target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
    scene.render(scene.defaultCamera(), o->width, o->height, o->time, nullptr, o->wireframe);
    saveImage(o->out, target.readColor());
    std::printf("%s\n", o->out.c_str());
  });
}

} // namespace sylva::app

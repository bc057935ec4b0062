// A folding texture synthesised and one frame rendered on the CPU: loads a folding project (its images, zones
// and tools), synthesises the textures the renderer reads (the colour atlas, the jump vectors, the
// thresholds), and renders the frame at time T with the CPU reference renderer, the same equations the GLSL
// renderer evaluates (docs/folding.md).
//
//   folding_frame [PROJECT.json] [T] [OUT.png]   (default: the installed beach.json, 1.5 s,
//   folding_frame.png)
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/folding/ProjectFile.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Synthesis.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

int main(int argc, char** argv) {
  namespace folding = sylva::folding;
  // The example projects ship with Sylva's data (share/sylva/data/folding).
  const std::string file = argc > 1 ? argv[1] : sylva::dataPath("folding/beach.json").string();
  const double t = argc > 2 ? std::strtod(argv[2], nullptr) : 1.5;
  const std::string out = argc > 3 ? argv[3] : "folding_frame.png";
  try {
    const folding::LoadedProject loaded = folding::loadProjectFile(file);
    const folding::Textures textures = folding::synthesize(loaded.project, loaded.images);
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    const sylva::Image frame =
        folding::renderFrame(textures, loaded.project.profiles, loaded.project.jumpLayers, t, threads);
    sylva::savePng(out, frame);
    std::printf("%s: %zu zone(s), %zu profile(s); frame at %.2f s of a %.2f s loop: %d x %d -> %s\n",
                file.c_str(), loaded.project.zones.size(), loaded.project.profiles.size(), t,
                folding::loopPeriod(loaded.project.profiles).seconds, frame.width(), frame.height(),
                out.c_str());
    return 0;
  } catch (const sylva::Error& e) {
    std::fprintf(stderr, "folding_frame: %s\n", e.what());
    return 1;
  }
}

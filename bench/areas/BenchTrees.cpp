// `sylva bench trees` (docs/trees.md): the paper's Fig. 16 workloads (1 … 1,000 trees) drawn by piece-type
// instancing (one cull pass, one multi-draw) beside the per-piece-draw baseline in the same run, the cost of
// tessellation levels 1 and 10, the foliage passes, 1,000 animated trees with 100,000 far impostors,
// generation of 1,000 trees on one thread, wind on 100,000 joints, bark tile-set synthesis and GPU memory.
#include "Bench.hpp"

#include <sylva/core/Log.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/gpu/FoliageRenderer.hpp>
#include <sylva/trees/gpu/ImpostorRenderer.hpp>
#include <sylva/trees/gpu/JointWindGpu.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>
#include <sylva/wind/Wind.hpp>

#include <glm/geometric.hpp>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace sylva::bench {
namespace {

/** A camera that sees the whole grid forest from the south-west, above the crowns. */
render::Camera overview(const trees::Forest& forest, float aspect) {
  glm::vec3 lo(1e30f);
  glm::vec3 hi(-1e30f);
  for (const trees::ForestTree& t : forest.trees) {
    const glm::vec3 p(t.base[3]);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p + glm::vec3(0.0f, 12.0f, 0.0f));
  }
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = std::max(8.0f, 0.5f * glm::length(hi - lo));
  render::Camera camera;
  camera.fovY = glm::radians(50.0f);
  const float distance = radius / std::sin(camera.fovY * 0.5f) * (aspect < 1.0f ? 1.0f / aspect : 1.0f);
  camera.target = centre;
  camera.position = centre + glm::normalize(glm::vec3(-1.0f, 0.55f, 1.0f)) * distance;
  camera.nearPlane = 0.5f;
  camera.farPlane = distance * 3.0f;
  return camera;
}

/** Median wall milliseconds per frame of `frame` (GPU finished each frame), after one warm-up frame. */
double medianMs(int frames, const std::function<void()>& frame) {
  const std::vector<double> runs = timeRuns(1, frames, [&] {
    frame();
    gl::finish();
  });
  std::vector<double> ms;
  for (double s : runs) {
    ms.push_back(s * 1e3);
  }
  return render::Stats::of(ms).median;
}

} // namespace

void benchTrees(int frames, int width, int height, nlohmann::json& report) {
  shader::Library library;
  render::RenderTarget target(width, height);
  const std::string rendererName = gl::queryContextInfo().renderer;
  std::vector<BenchRow> rows;
  const int runs = std::max(3, frames / 10);
  trees::TreeLod lod;

  // 1. Fig. 16: forests of 1 … 1,000 almond trees (the paper's species), rest pose, all in view.
  const double paperMs[] = {0.5319, 0.9523, 3.5714, 6.25, 17.5439, 28.5714, 58.8235};
  const int counts[] = {1, 10, 50, 100, 250, 500, 1000};
  nlohmann::json fig16 = nlohmann::json::array();
  std::printf("trees: Fig. 16 workloads at %dx%d on %s (%d frames each)\n", width, height,
              rendererName.c_str(), runs);
  for (std::size_t w = 0; w < std::size(counts); ++w) {
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(counts[w]))));
    trees::Forest grid = trees::gridForest({"almond"}, side, 9.0f, 16);
    grid.trees.resize(static_cast<std::size_t>(counts[w]));
    grid.index();
    auto forest = std::make_shared<const trees::Forest>(std::move(grid));
    trees::TreeRenderer renderer(library, forest);
    const render::Camera camera = overview(*forest, target.aspect());
    const double instanced = medianMs(runs, [&] {
      target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
      renderer.cull(camera, target.aspect(), lod);
      renderer.draw(camera, width, height, 0.0, lod);
    });
    const double perPiece = medianMs(runs, [&] {
      target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
      renderer.drawPerPiece(camera, width, height, 0.0, lod);
    });
    const std::size_t pieces = renderer.instances().instances.size();
    fig16.push_back({{"trees", counts[w]},
                     {"pieces", pieces},
                     {"instanced_ms", instanced},
                     {"per_piece_ms", perPiece},
                     {"paper_gtx980ti_ms", paperMs[w]}});
    rows.push_back({fmt::format("{} trees ({} pieces): instanced, 1 multi-draw", counts[w], pieces),
                    instanced, "ms", paperMs[w], true, 0,
                    fmt::format("per-piece draws: {:.2f} ms; paper GTX 980 Ti", perPiece)});
  }

  // 2. Tessellation cost: 100 trees at fixed levels 1 and 10 (paper: 2.0 vs 2.8–3.0 ms on a GTX 950M).
  {
    trees::Forest grid = trees::gridForest({"almond"}, 10, 9.0f, 16);
    auto forest = std::make_shared<const trees::Forest>(std::move(grid));
    trees::TreeRenderer renderer(library, forest);
    const render::Camera camera = overview(*forest, target.aspect());
    auto at = [&](float level) {
      trees::TreeLod fixed;
      fixed.fixedLevel = level;
      return medianMs(runs, [&] {
        target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
        renderer.cull(camera, target.aspect(), fixed);
        renderer.draw(camera, width, height, 0.0, fixed);
      });
    };
    const double l1 = at(1.0f);
    const double l10 = at(10.0f);
    rows.push_back({"100 trees, tessellation level 1", l1, "ms", 2.0, true, 0, "paper: 2.0 ms (GTX 950M)"});
    rows.push_back({"100 trees, tessellation level 10", l10, "ms", 3.0, true, 0,
                    fmt::format("{:.1f}x level 1; paper: 2.8-3.0 ms, 1.45x", l10 / l1)});
    rows.push_back({"GPU memory of 100 trees (meshes, instances, joints)",
                    static_cast<double>(renderer.gpuBytes()) / 1e6, "MB", std::nan(""), true, 0, ""});
    // Foliage (2.5D impostors): pass 1 bakes the leaf cloud for the view direction (only when it turns),
    // pass 2 draws one billboard per branch tip. Each measured alone on top of the same bare trees.
    trees::FoliageRenderer foliage(library, forest);
    const double bare = medianMs(runs, [&] {
      target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
      renderer.cull(camera, target.aspect(), lod);
      renderer.draw(camera, width, height, 0.0, lod);
    });
    render::Camera turning = camera;
    int turn = 0;
    const double bake = medianMs(runs, [&] {
      // A new view direction every frame, so every frame bakes.
      turning.target = camera.target + glm::vec3(0.01f * static_cast<float>(++turn), 0.0f, 0.0f);
      foliage.bake(turning);
    });
    const double leafy = medianMs(runs, [&] {
      target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
      renderer.cull(camera, target.aspect(), lod);
      renderer.draw(camera, width, height, 0.0, lod);
      foliage.bake(camera);
      foliage.draw(camera, width, height, 0.0, renderer, lod);
    });
    rows.push_back({fmt::format("foliage of 100 trees: bake the leaf cloud ({}² texture, {} leaf triangles)",
                                foliage.stats().textureSize, foliage.stats().leafTriangles),
                    bake, "ms", std::nan(""), true, 0, "pass 1; only when the view direction changes"});
    rows.push_back({fmt::format("foliage of 100 trees: {} billboards (pass 2)", foliage.stats().anchors),
                    leafy - bare, "ms", std::nan(""), true, 0,
                    fmt::format("frame with leaves {:.1f} ms vs bare {:.1f} ms", leafy, bare)});
  }

  // 3. Generation: 1,000 trees (topology, transforms, bone buffers) on one thread.
  {
    const trees::PieceSet pieces = trees::standardPieces();
    const trees::Species almond = trees::speciesPreset("almond");
    std::size_t joints = 0;
    std::vector<glm::mat4> frames;
    const std::vector<double> seconds = timeRuns(1, 5, [&] {
      joints = 0;
      for (int t = 0; t < 1000; ++t) {
        const trees::TreeTopology tree = trees::generateTree(pieces, almond, static_cast<std::uint64_t>(t));
        const std::vector<glm::vec2> pose = trees::randomPose(tree, almond, 1);
        trees::jointFrames(pieces, tree, trees::baseFrame(glm::vec3(t, 0, 0), 0.0f, 0.2f), pose, frames);
        joints += frames.size();
      }
    });
    std::vector<double> ms;
    for (double s : seconds) {
      ms.push_back(s * 1e3);
    }
    rows.push_back({"generate 1,000 almond trees (topology, pose, joint frames)",
                    render::Stats::of(ms).median, "ms", 50.0, true, 1, fmt::format("{} joints", joints)});
  }
  // 4. The spec's scene: 1,000 animated trees (joint wind on the GPU, bark tiles, foliage) and 100,000 far
  // impostor trees around them, seen from eye height inside the forest; beside it the same 1,000 trees drawn
  // as pieces only (no far field).
  {
    auto forest = std::make_shared<const trees::Forest>(trees::gridForest({"almond", "apple"}, 32, 9.0f, 23));
    const std::size_t near = std::min<std::size_t>(forest->trees.size(), 1000);
    auto thousand = std::make_shared<trees::Forest>(*forest);
    thousand->trees.resize(near);
    thousand->index();
    std::shared_ptr<const trees::Forest> animated = thousand;
    trees::TreeRenderer renderer(library, animated);
    trees::BarkSources sources;
    sources.mode = "procedural";
    std::vector<int> speciesSet;
    const std::vector<trees::BarkSet> bark = trees::barkSetsFor(*animated, sources, speciesSet);
    renderer.setBark(bark, speciesSet);
    trees::JointWindGpu wind(library, trees::forestWindRest(*animated));
    renderer.useFrames(&wind.frames());
    trees::FoliageRenderer foliage(library, animated);
    trees::ImpostorRenderer impostors(library);
    impostors.bake(*animated, trees::sceneBakeOptions(library, bark, speciesSet, true));
    std::vector<trees::FarTree> far = trees::farTrees(*animated);
    trees::FarTreeFieldSettings field;
    field.count = 100000;
    field.centre = glm::vec2(0.0f);
    field.innerRadius = 170.0f;
    field.outerRadius = 3000.0f;
    field.species = 2;
    field.firstId = static_cast<std::uint32_t>(near);
    const std::vector<trees::FarTree> extra = trees::farTreeField(field);
    far.insert(far.end(), extra.begin(), extra.end());
    impostors.setTrees(far);
    render::Camera camera;
    camera.fovY = glm::radians(60.0f);
    camera.position = glm::vec3(-150.0f, 1.7f, -150.0f);
    camera.target = glm::vec3(150.0f, 8.0f, 150.0f);
    camera.nearPlane = 0.2f;
    camera.farPlane = 4000.0f;
    wind::WindSettings breeze;
    breeze.speed = 5.0f;
    float time = 0.0f;
    trees::TreeLod farLod = lod;
    farLod.farRange = glm::vec2(60.0f, 85.0f);
    auto frame = [&](const trees::TreeLod& l, bool withImpostors) {
      time += 1.0f / 60.0f;
      wind.step(wind::toUniforms(breeze, time), 1.0f / 60.0f);
      wind.updateFrames();
      target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
      renderer.cull(camera, width, height, l); // as ForestScene culls: by size and width (TreeLod)
      renderer.draw(camera, width, height, time, l);
      foliage.bake(camera);
      foliage.draw(camera, width, height, time, renderer, l);
      if (withImpostors) {
        impostors.draw(camera, width, height, time, l.farRange);
      }
    };
    // Work, not only time: the piece instances the cull kept (llvmpipe's time is per patch).
    auto piecesDrawn = [&] {
      std::size_t n = 0;
      for (std::uint32_t c : renderer.readVisibleCounts()) {
        n += c;
      }
      return n;
    };
    const double withFar = medianMs(runs, [&] { frame(farLod, true); });
    const std::uint32_t visibleFar = impostors.readVisibleCount();
    const std::size_t drawnFar = piecesDrawn();
    const double piecesOnly = medianMs(runs, [&] { frame(lod, false); });
    const std::size_t drawnAll = piecesDrawn();
    rows.push_back(
        {fmt::format("{} animated trees + {} impostor trees (bark, foliage, wind), {}x{}", near, extra.size(),
                     width, height),
         withFar, "ms", 16.6, true, 0,
         fmt::format("{} impostors and {} of {} pieces after the cull; pieces within 60-85 m; target for a "
                     "desktop GPU",
                     visibleFar, drawnFar, renderer.instances().instances.size())});
    rows.push_back({fmt::format("the same {} trees as pieces only (no far field)", near), piecesOnly, "ms",
                    std::nan(""), true, 0,
                    fmt::format("every tree leafy and animated; {} pieces after the cull", drawnAll)});
    rows.push_back({"GPU memory of the far field (atlases of 2 species, 100,000 instances)",
                    static_cast<double>(impostors.gpuBytes()) / 1e6, "MB", std::nan(""), true, 0, ""});
  }
  // 5. Wind on the joints: a forest of about 100,000 joints, one step plus every joint's frame, on the CPU
  // (all cores) and on the GPU (wind.comp + frames.comp).
  {
    trees::Forest grid = trees::gridForest({"almond"}, 40, 9.0f, 21);
    std::size_t keep = 0;
    std::size_t joints = 0;
    while (keep < grid.trees.size() && joints < 100000) {
      joints += grid.trees[keep++].topology.jointCount();
    }
    grid.trees.resize(keep);
    grid.index();
    const trees::JointWindRest rest = trees::forestWindRest(grid);
    trees::JointWindState state(rest.jointCount());
    wind::WindSettings settings;
    settings.speed = 6.0f;
    std::vector<gpu::JointFrame> frames;
    float time = 0.0f;
    const std::vector<double> cpu = timeRuns(3, std::max(10, runs * 3), [&] {
      time += 1.0f / 60.0f;
      trees::stepJointWind(rest, state, wind::toUniforms(settings, time), 1.0f / 60.0f);
      trees::forestJointFrames(rest, state, frames);
    });
    trees::JointWindGpu gpuWind(library, rest);
    const std::vector<double> gpu = timeRuns(3, std::max(10, runs * 3), [&] {
      time += 1.0f / 60.0f;
      gpuWind.step(wind::toUniforms(settings, time), 1.0f / 60.0f);
      gpuWind.updateFrames();
      gl::finish();
    });
    auto ms = [](const std::vector<double>& s) {
      std::vector<double> v;
      for (double x : s) {
        v.push_back(x * 1e3);
      }
      return render::Stats::of(v).median;
    };
    rows.push_back({fmt::format("wind on {} joints ({} trees): step + frames, CPU", rest.jointCount(), keep),
                    ms(cpu), "ms", 4.0, true, static_cast<unsigned>(workerCount()), ""});
    rows.push_back(
        {fmt::format("wind on {} joints: step + frames, GPU (wind.comp, frames.comp)", rest.jointCount()),
         ms(gpu), "ms", 0.25, true, 0,
         fmt::format("{}; target for an NVIDIA GPU", rendererName.substr(0, 24))});
  }
  // 6. Bark tile sets (texsynth): the trees' set (3 classes × 8 variants of 128² tiles) from the oak photo
  // (halved to 512²) when it is fetched, and from procedural bark.
  for (const std::string source : {"oak", "procedural"}) {
    trees::BarkSources sources;
    sources.tiles.tileSize = 128;
    sources.variants = 8;
    sources.photoSide = 512;
    if (trees::barkSource(source, sources) != source) {
      rows.push_back({"bark tile set from the oak photo", std::nan(""), "ms", std::nan(""), true, 1,
                      "photo not fetched (scripts/fetch-sample-data.sh)"});
      continue;
    }
    std::size_t tiles = 0;
    const std::vector<double> seconds =
        timeRuns(0, 2, [&] { tiles = trees::barkSetFromSource(source, sources).colour.size(); });
    std::vector<double> ms;
    for (double sec : seconds) {
      ms.push_back(sec * 1e3);
    }
    rows.push_back(
        {fmt::format("bark tile set from {} ({} tiles of 128²: 3 classes x 16 edge colourings x 8)",
                     source == "oak" ? "the oak photo 512²" : "procedural bark 512²", tiles),
         render::Stats::of(ms).median, "ms", std::nan(""), true, 1,
         "image quilting: SSD choice + min-error cuts"});
  }
  report["rows"] = printBenchRows(rows);
  report["fig16"] = fig16;
}

} // namespace sylva::bench

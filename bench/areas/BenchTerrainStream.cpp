// `sylva bench terrain-stream` (docs/terrain-data.md, "Streaming"): a flight across the 2^20 x 2^20-sample
// procedural world (or a tile pyramid) at a fixed speed, one update and draw per simulated frame, with the
// streamer's budgets held: memory over the flight, tiles loaded per second, frames that drew stand-ins while
// tiles were loading, and drawn vertices against the CPU height query.
#include "Bench.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/render/Timing.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/terrain/TileSource.hpp>
#include <sylva/terrain/gpu/StreamedTerrain.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace sylva::bench {
namespace {

/** Largest |drawn vertex height − drawnHeightAt| (metres) over a point render of the current view. */
double vertexQueryError(terrain::StreamedTerrain& terrain, gl::Framebuffer& fb, gl::Texture& colour, int w,
                        int h, const render::Camera& camera, int& points) {
  fb.bindForDraw(w, h);
  fb.clearColor(0, glm::vec4(0.0f));
  fb.clearDepth();
  glEnable(GL_DEPTH_TEST);
  terrain.draw(camera, w, h, 0.0, terrain::StreamedView::WorldPosition, {}, true);
  const Image image = colour.download(4, PixelType::F32);
  const glm::dvec3 origin = terrain.origin();
  double worst = 0.0;
  points = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (image.get(x, y, 3) == 0.0f) {
        continue;
      }
      const float q = terrain.drawnHeightAt(origin.x + image.get(x, y, 0), origin.z + image.get(x, y, 2));
      worst = std::max(worst, std::isnan(q) ? 1e9 : std::abs(static_cast<double>(q) - image.get(x, y, 1)));
      ++points;
    }
  }
  return worst;
}

} // namespace

void benchTerrainStream(const BenchOptions& o, const platform::GlContext& context,
                        const StreamBenchOptions& s, nlohmann::json& report) {
  if (!(s.distanceKm > 0.0) || !(s.speed > 0.0) || !(s.simFps > 0.0)) {
    fail("bench terrain-stream: --distance, --speed and --sim-fps must be > 0");
  }
  shader::Library library;
  std::shared_ptr<const terrain::TileSource> source;
  std::shared_ptr<const terrain::ProceduralWorld> world;
  if (s.pyramid.empty()) {
    world = std::make_shared<terrain::ProceduralWorld>(terrain::defaultLandscapeSpec(s.seed));
    source = world;
  } else {
    source = terrain::pyramidSource(s.pyramid);
  }
  const terrain::PyramidInfo& layout = source->layout();
  const auto ground = [&](double x, double z) {
    return world ? static_cast<double>(world->heightAt(x, z)) : static_cast<double>(layout.maxHeight);
  };
  terrain::StreamedTerrainOptions options;
  options.gpuBudget = s.gpuBudget;
  options.ramBudget = s.ramBudget;
  terrain::StreamedTerrain terrain(library, source, options);

  const double extentX = (layout.width - 1) * static_cast<double>(layout.spacingX);
  const double extentZ = (layout.height - 1) * static_cast<double>(layout.spacingZ);
  const double distance = s.distanceKm * 1000.0;
  // A straight line at a slant through the middle of the world, clipped to it.
  const glm::dvec2 heading = glm::normalize(glm::dvec2(1.0, 0.35));
  const glm::dvec2 start = glm::dvec2(0.5 * extentX, 0.5 * extentZ) -
                           heading * std::min(0.5 * distance, 0.45 * std::min(extentX, extentZ));
  const double length = std::min(distance, 0.9 * std::min(extentX, extentZ) / std::max(heading.x, heading.y));
  const double dt = 1.0 / s.simFps;
  const int frames = static_cast<int>(std::ceil(length / (s.speed * dt)));
  const float fov = glm::radians(50.0f);
  const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
  const float farPlane = 30000.0f;
  report = header(o, "terrain-stream", context);
  const bool layerLimited =
      (static_cast<std::size_t>(terrain.layers()) + 1) * terrain.layerBytes() <= s.gpuBudget;
  std::printf(
      "terrain-stream: %s\n  %.1f km at %.0f m/s (%d frames of %.3f s), %dx%d, budgets: GPU %.0f MB (%d "
      "tiles%s), RAM %.0f MB; %s\n",
      source->describe().c_str(), length / 1000.0, s.speed, frames, dt, o.width, o.height,
      static_cast<double>(s.gpuBudget) / 1.0e6, terrain.layers(),
      layerLimited ? ": the GL limit on array layers" : "", static_cast<double>(s.ramBudget) / 1.0e6,
      gl::queryContextInfo().renderer.c_str());

  render::RenderTarget target(o.width, o.height);
  const render::Environment environment = terrain::StreamedTerrain::wideEnvironment(30000.0);
  const int pw = std::max(o.width / 4, 16);
  const int ph = std::max(o.height / 4, 16);
  gl::Texture positions = gl::Texture::create2D(GL_RGBA32F, pw, ph);
  gl::Texture depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, pw, ph);
  gl::Framebuffer fb;
  fb.attachColor(0, positions);
  fb.attachDepth(depth);
  fb.checkComplete();

  std::vector<double> updateMs;
  std::vector<double> frameMs;
  std::vector<double> rss;
  std::vector<double> sampleKm;
  std::vector<double> ram;
  int waited = 0;
  std::uint64_t vertices = 0;
  double worstQuery = 0.0;
  int checks = 0;
  double altitude = ground(start.x, start.y) + s.altitude;
  const auto wallStart = std::chrono::steady_clock::now();
  const terrain::StreamerStats before = terrain.streamer().stats();
  for (int f = 0; f <= frames; ++f) {
    const glm::dvec2 p = start + heading * std::min(f * s.speed * dt, length);
    // Terrain following, smoothed (the ground 300 m ahead and below), at most 30 m/s climb or sink.
    const glm::dvec2 ahead = p + heading * 300.0;
    const double wantAltitude = std::max(ground(p.x, p.y), ground(ahead.x, ahead.y)) + s.altitude;
    altitude += std::clamp(wantAltitude - altitude, -30.0 * dt, 30.0 * dt);
    const glm::dvec3 eye(p.x, altitude, p.y);
    const glm::dvec3 look = eye + glm::dvec3(heading.x, -0.22, heading.y) * 100.0;
    const glm::dvec3 velocity(heading.x * s.speed, 0.0, heading.y * s.speed);
    const auto t0 = std::chrono::steady_clock::now();
    const terrain::StreamedFrame frame = terrain.update(eye, look, velocity, fov, aspect, farPlane);
    const auto t1 = std::chrono::steady_clock::now();
    const render::Camera camera = terrain.relativeCamera(fov, 0.5f, farPlane);
    target.begin(terrain::StreamedTerrain::clearColour(environment));
    terrain.draw(camera, o.width, o.height, f * dt, terrain::StreamedView::Shaded, environment);
    glFinish();
    const auto t2 = std::chrono::steady_clock::now();
    updateMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    frameMs.push_back(std::chrono::duration<double, std::milli>(t2 - t0).count());
    waited += frame.waited ? 1 : 0;
    vertices += frame.vertices;
    if (f % s.checkEvery == 0) {
      int points = 0;
      worstQuery = std::max(worstQuery, vertexQueryError(terrain, fb, positions, pw, ph, camera, points));
      ++checks;
      const terrain::StreamerStats st = terrain.streamer().stats();
      rss.push_back(static_cast<double>(residentBytes()) / 1.0e6);
      sampleKm.push_back(std::min(f * s.speed * dt, length) / 1000.0);
      ram.push_back(static_cast<double>(st.residentBytes) / 1.0e6);
    }
    if (f % std::max(1, frames / 20) == 0 || f == frames) {
      const terrain::StreamerStats st = terrain.streamer().stats();
      std::printf(
          "  %5.1f km: %3d tiles, %4zu in RAM (%.0f MB, RSS %.0f MB), %d GPU layers, %llu loaded, %s\n",
          std::min(f * s.speed * dt, length) / 1000.0, frame.tiles, st.residentTiles,
          static_cast<double>(st.residentBytes) / 1.0e6, static_cast<double>(residentBytes()) / 1.0e6,
          frame.layersUsed, static_cast<unsigned long long>(st.loaded - before.loaded),
          frame.waited ? fmt::format("waiting for {} tiles", frame.missing).c_str() : "complete");
      std::fflush(stdout);
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  const terrain::StreamerStats after = terrain.streamer().stats();
  const double simSeconds = frames * dt;
  const double loaded = static_cast<double>(after.loaded - before.loaded);
  const double gpuMb =
      static_cast<double>(terrain.layers()) * static_cast<double>(terrain.layerBytes()) / 1.0e6;
  const auto maxOf = [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
  };
  // RSS after the first tenth of the flight (warm-up: the caches fill) against the rest.
  const std::size_t tenth = rss.size() / 10;
  const double rssWarm = rss.empty() ? 0.0 : rss[tenth];
  const double rssPeak = maxOf(rss);
  std::printf("  %-34s %12s\n", "", "measured");
  std::printf("  %-34s %12.1f\n", "flight, km", length / 1000.0);
  std::printf("  %-34s %12d\n", "frames", frames + 1);
  std::printf("  %-34s %12.2f\n", "update ms (median)", render::Stats::of(updateMs).median);
  std::printf("  %-34s %12.2f\n", "frame ms (median, update + draw)", render::Stats::of(frameMs).median);
  std::printf("  %-34s %12.0f\n", "tiles loaded", loaded);
  std::printf("  %-34s %12.1f\n", "tiles loaded per simulated s", loaded / simSeconds);
  std::printf("  %-34s %12.1f\n", "tiles loaded per wall s", loaded / wall);
  std::printf("  %-34s %12d (%.1f %%)\n", "frames that waited for a tile", waited,
              100.0 * waited / (frames + 1));
  std::printf("  %-34s %12.0f / %.0f\n", "RAM tiles MB: peak / budget",
              static_cast<double>(after.peakBytes) / 1.0e6, static_cast<double>(s.ramBudget) / 1.0e6);
  std::printf("  %-34s %12.0f / %.0f\n", "GPU tile cache MB / budget", gpuMb,
              static_cast<double>(s.gpuBudget) / 1.0e6);
  std::printf("  %-34s %12.0f -> %.0f\n", "process RSS MB: warm -> peak", rssWarm, rssPeak);
  std::printf("  %-34s %12.3f (%d checks; target <= 1 cm)\n", "height query vs drawn, worst cm",
              worstQuery * 100.0, checks);
  report["source"] = source->describe();
  report["flight_km"] = length / 1000.0;
  report["speed_m_s"] = s.speed;
  report["sim_fps"] = s.simFps;
  report["frames"] = frames + 1;
  report["update_ms"] = render::Stats::of(updateMs).toJson();
  report["frame_ms"] = render::Stats::of(frameMs).toJson();
  report["vertices_per_frame"] = static_cast<double>(vertices) / (frames + 1);
  report["tiles_loaded"] = loaded;
  report["tiles_loaded_per_sim_s"] = loaded / simSeconds;
  report["tiles_loaded_per_wall_s"] = loaded / wall;
  report["load_ms_per_tile"] = loaded > 0 ? 1000.0 * (after.loadSeconds - before.loadSeconds) / loaded : 0.0;
  report["frames_waited"] = waited;
  report["ram_budget_mb"] = static_cast<double>(s.ramBudget) / 1.0e6;
  report["ram_peak_mb"] = static_cast<double>(after.peakBytes) / 1.0e6;
  report["ram_mb_samples"] = ram;
  report["gpu_budget_mb"] = static_cast<double>(s.gpuBudget) / 1.0e6;
  report["gpu_tiles_mb"] = gpuMb;
  report["rss_mb_samples"] = rss;
  report["sample_km"] = sampleKm;
  report["rss_warm_mb"] = rssWarm;
  report["rss_peak_mb"] = rssPeak;
  report["height_query_worst_m"] = worstQuery;
  report["height_query_checks"] = checks;
  report["within_budgets"] =
      after.peakBytes <= s.ramBudget && gpuMb * 1.0e6 <= static_cast<double>(s.gpuBudget);
}

} // namespace sylva::bench

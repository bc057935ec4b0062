#include <sylva/capture/Pipeline.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Progress.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace sylva::capture {
namespace {

/** Camera space (x right, y down, z forward) to blade space (+Y up, +Z towards the camera), as a direction.
 */
glm::vec3 toBladeDirection(const glm::vec3& v) {
  return {v.x, -v.y, -v.z};
}

} // namespace

std::vector<TrackedBlade> trackBlades(const std::vector<ExtractResult>& results, float maxTipJumpPx) {
  std::vector<TrackedBlade> tracks;
  if (results.empty()) {
    return tracks;
  }
  std::vector<glm::vec2> lastTip;
  for (const CapturedBlade& blade : results[0].blades) {
    TrackedBlade t;
    t.reference = blade;
    t.motion.push_back(blade.knots);
    tracks.push_back(std::move(t));
    lastTip.push_back(blade.skeletonPx.empty() ? glm::vec2(0.0f) : blade.skeletonPx.back());
  }
  for (std::size_t f = 1; f < results.size(); ++f) {
    const std::vector<CapturedBlade>& blades = results[f].blades;
    std::vector<bool> used(blades.size(), false);
    // Nearest pairs first, so two tracks never fight over one blade in a greedy order that depends on
    // indices.
    struct Pair {
      float d;
      std::size_t track;
      std::size_t blade;
    };
    std::vector<Pair> pairs;
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      for (std::size_t b = 0; b < blades.size(); ++b) {
        if (blades[b].knots.size() != tracks[t].reference.knots.size() || blades[b].skeletonPx.empty()) {
          continue;
        }
        const float d = glm::length(blades[b].skeletonPx.back() - lastTip[t]);
        if (d <= maxTipJumpPx) {
          pairs.push_back({d, t, b});
        }
      }
    }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
      return a.d < b.d || (a.d == b.d && (a.track < b.track || (a.track == b.track && a.blade < b.blade)));
    });
    std::vector<bool> done(tracks.size(), false);
    for (const Pair& p : pairs) {
      if (done[p.track] || used[p.blade]) {
        continue;
      }
      done[p.track] = used[p.blade] = true;
      tracks[p.track].motion.push_back(blades[p.blade].knots);
      lastTip[p.track] = blades[p.blade].skeletonPx.back();
    }
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      if (!done[t]) {
        tracks[t].motion.push_back(tracks[t].motion.back());
        ++tracks[t].missingFrames;
      }
    }
  }
  return tracks;
}

blades::BladeModel makeBladeModel(const CapturedBlade& blade, const KnotFrames& motion,
                                  const ModelOptions& options, blades::BladeSource source) {
  const std::size_t n = blade.knots.size();
  if (n < 2 || blade.widths.size() != n || blade.sides.size() != n) {
    fail("blade model: the captured blade has {} knots, {} widths and {} sides", n, blade.widths.size(),
         blade.sides.size());
  }
  if (options.levels.empty()) {
    fail("--levels: give at least one knot count");
  }
  for (std::size_t i = 0; i < options.levels.size(); ++i) {
    const int l = options.levels[i];
    if (l < 2 || static_cast<std::size_t>(l) > n) {
      fail("--levels: {} knots outside 2..{} (the captured knot count)", l, n);
    }
    if (i > 0 && l >= options.levels[i - 1]) {
      fail("--levels: counts must decrease strictly, got {} after {}", l, options.levels[i - 1]);
    }
  }
  KnotFrames frames;
  if (!motion.empty()) {
    frames = motion;
  } else {
    frames.push_back(blade.knots);
    if (options.simulateSway) {
      glm::vec3 axis(0.0f);
      for (const glm::vec3& s : blade.sides) {
        axis += s;
      }
      axis = glm::length(axis) > 0.0f ? glm::normalize(axis) : glm::vec3(1.0f, 0.0f, 0.0f);
      // Bending about the width direction moves the blade towards and away from the camera: the way a blade
      // bends most easily.
      const KnotFrames sway = swayFrames(blade.knots, axis, options.sway);
      frames.insert(frames.end(), sway.begin(), sway.end());
    }
  }
  for (const auto& f : frames) {
    if (f.size() != n) {
      fail("blade model: a motion frame has {} knots, the blade {}", f.size(), n);
    }
  }

  blades::BladeModel model;
  model.hasColour = blade.hasColour;
  model.colour = blade.colour;
  glm::vec3 axis(0.0f);
  for (const glm::vec3& s : blade.sides) {
    axis += toBladeDirection(s);
  }
  axis = glm::length(axis) > 1e-6f ? glm::normalize(axis) : glm::vec3(1.0f, 0.0f, 0.0f);
  if (axis.x < 0.0f) {
    axis = -axis;
  }
  model.bendAxis = axis;

  // The unit of refining: the mean knot spacing of the captured skeleton.
  float spacing = 0.0f;
  for (std::size_t k = 1; k < n; ++k) {
    spacing += glm::length(blade.knots[k] - blade.knots[k - 1]);
  }
  spacing = std::max(spacing / static_cast<float>(n - 1), 1e-9f);
  for (int level : options.levels) {
    RefineOptions refine;
    refine.knots = level;
    refine.mu = options.mu;
    refine.keepEnds = true;
    refine.measure = options.measure;
    refine.unitMetres = options.rawMetres ? 0.0 : spacing;
    const RefineResult r = refineKnots(frames, blade.widths, refine);
    blades::BladeLod lod;
    const std::vector<glm::vec3>& pose = r.frames[0];
    const glm::vec3 root = pose[0];
    const std::size_t m = pose.size();
    lod.positions.resize(m);
    lod.widths = r.widths;
    lod.normals.resize(m);
    for (std::size_t k = 0; k < m; ++k) {
      lod.positions[k] = toBladeDirection(pose[k] - root);
    }
    // The original knot each refined knot stands for (the middle of the knots merged into it) gives its side.
    std::size_t first = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t count = static_cast<std::size_t>(std::max(r.merged[k], 1));
      const std::size_t middle = std::min(n - 1, first + count / 2);
      first += count;
      const glm::vec3 side = toBladeDirection(blade.sides[middle]);
      const glm::vec3 t = lod.positions[std::min(k + 1, m - 1)] - lod.positions[k > 0 ? k - 1 : 0];
      glm::vec3 normal = glm::cross(side, t);
      if (glm::length(normal) < 1e-9f) {
        normal = glm::vec3(0.0f, 0.0f, 1.0f);
      }
      normal = glm::normalize(normal);
      if (normal.z < 0.0f) {
        normal = -normal;
      }
      lod.normals[k] = normal;
    }
    model.lods.push_back(std::move(lod));
  }
  source.motionFrames = static_cast<int>(frames.size());
  source.mu = options.mu;
  source.medialAxis = blade.medialAxis;
  model.source = std::move(source);
  return model;
}

CaptureRun captureBlades(int frameCount, const std::function<DepthFrame(int)>& frame,
                         const CaptureSettings& settings, const std::string& source,
                         const std::string& label) {
  if (frameCount < 1) {
    fail("{}: no depth frames to capture", source);
  }
  CaptureRun run;
  {
    std::unique_ptr<Progress> progress;
    if (frameCount > 1) {
      progress = std::make_unique<Progress>(label, static_cast<std::size_t>(frameCount));
    }
    for (int i = 0; i < frameCount; ++i) {
      if (progress && progress->cancelled()) {
        fail("capture: cancelled");
      }
      DepthFrame depth = frame(i);
      ExtractResult r = extractBlades(depth, settings.extract);
      run.warnings.insert(run.warnings.end(), r.warnings.begin(), r.warnings.end());
      if (i == 0) {
        run.reference = std::move(depth);
      }
      run.results.push_back(std::move(r));
      if (progress) {
        progress->advance();
      }
    }
  }
  const ExtractResult& first = run.results.front();
  if (first.blades.empty()) {
    fail("{}: no blades found{}", run.reference.label(),
         first.warnings.empty() ? std::string() : " (" + first.warnings.front() + ")");
  }
  run.motion = settings.motion;
  if (run.motion == CaptureMotion::Auto) {
    run.motion = run.results.size() > 1 ? CaptureMotion::Recording : CaptureMotion::Sway;
  }
  if (run.motion == CaptureMotion::Recording && run.results.size() < 2) {
    fail("{}: refining by the recording's motion needs at least 2 frames", source);
  }
  ModelOptions model = settings.model;
  model.simulateSway = run.motion == CaptureMotion::Sway;
  run.tracks = trackBlades(run.results);
  run.file.generator = settings.generator;
  const KnotFrames still;
  for (std::size_t b = 0; b < run.tracks.size(); ++b) {
    blades::BladeSource meta;
    meta.file = source;
    meta.kind = depthSourceName(run.reference.kind);
    meta.frame = run.reference.frame;
    meta.cluster = run.tracks[b].reference.cluster;
    meta.blade = static_cast<int>(b);
    meta.intrinsics = run.reference.intrinsics;
    meta.relativeDepth = run.reference.relativeDepth;
    blades::BladeModel m;
    try {
      m = makeBladeModel(run.tracks[b].reference,
                         run.motion == CaptureMotion::Recording ? run.tracks[b].motion : still, model, meta);
    } catch (const Error& e) {
      fail("{}: blade {} of cluster {}: {}", source, b, meta.cluster, e.what());
    }
    m.name = settings.name + "-" + std::to_string(b);
    run.file.blades.push_back(std::move(m));
  }
  if (settings.scaleToMetres > 0.0) {
    // Relative depth (Middlebury without calibration) has no true scale: the user gives the longest blade's.
    float longest = 0.0f;
    for (const blades::BladeModel& m : run.file.blades) {
      longest = std::max(longest, m.length());
    }
    run.scale = static_cast<float>(settings.scaleToMetres) / std::max(longest, 1e-9f);
    for (blades::BladeModel& m : run.file.blades) {
      for (blades::BladeLod& lod : m.lods) {
        for (glm::vec3& p : lod.positions) {
          p *= run.scale;
        }
        for (float& w : lod.widths) {
          w *= run.scale;
        }
      }
    }
  }
  return run;
}

void writeCaptureStages(const std::filesystem::path& dir, const DepthFrame& frame,
                        const ExtractResult& result) {
  const auto range = depthRange(frame);
  saveImage(dir / "1-depth.png", depthPreview(frame, range.first, range.second));
  Image mask(result.width, result.height, 1, PixelType::U8);
  std::copy(result.mask.begin(), result.mask.end(), mask.values<std::uint8_t>().begin());
  saveImage(dir / "2-mask.png", mask);
  ExtractResult contours = result;
  contours.blades.clear();
  std::size_t junctions = 0;
  for (const Cluster& c : result.clusters) {
    junctions += c.junctions.size();
  }
  const std::size_t clusters = result.clusters.size();
  saveImage(dir / "3-contour.png",
            overlayImage(frame, contours,
                         frame.label() + ": contours of " + std::to_string(clusters) +
                             (clusters == 1 ? " cluster" : " clusters") + ", centres and " +
                             std::to_string(junctions) + " junctions"));
  if (!result.clusters.empty()) {
    saveImage(dir / "4-signal.png", signalPlot(result.clusters.front(), 960, 280));
  }
  saveImage(dir / "5-blades.png", overlayImage(frame, result));
}

} // namespace sylva::capture

// What `sylva capture` reports about a run (describeCapture), and the files `sylva capture synth` writes
// (syntheticTruthJson, saveSyntheticFrames).
#include <sylva/capture/Fakenect.hpp>
#include <sylva/capture/Pipeline.hpp>
#include <sylva/capture/Synthetic.hpp>

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

namespace sylva::capture {

namespace {

const char* plural(std::size_t n) {
  return n == 1 ? "" : "s";
}

const char* centreModeName(CentreMode mode) {
  switch (mode) {
  case CentreMode::Auto:
    return "auto";
  case CentreMode::Core:
    return "core";
  case CentreMode::Centroid:
    return "centroid";
  case CentreMode::Base:
    return "base";
  case CentreMode::Manual:
    return "manual";
  }
  return "?";
}

/** --explain: each cluster's centre, junctions, layer and what was not taken as a blade, and why. */
std::string explainClusters(const ExtractResult& first) {
  std::string text;
  for (std::size_t c = 0; c < first.clusters.size(); ++c) {
    const Cluster& cluster = first.clusters[c];
    text +=
        fmt::format("  cluster {}: {} px, centre ({:.0f}, {:.0f}) by {}, {} junction{}, blades", c,
                    cluster.areaPx, cluster.centre.x, cluster.centre.y, centreModeName(cluster.centreMode),
                    cluster.junctions.size(), plural(cluster.junctions.size()));
    for (int b : cluster.blades) {
      text += fmt::format(" {}", b);
    }
    if (cluster.layer >= 0) {
      text += fmt::format("; depth layer {} of {} ({:.3f} m) of its blob", cluster.layer, cluster.layerCount,
                          cluster.layerDepthMetres);
    }
    text += "\n";
    for (const Junction& j : cluster.junctions) {
      text +=
          fmt::format("    junction at contour {} ({:.0f}, {:.0f}): {:.0f} px from the centre, prominence "
                      "{:.3f}\n",
                      j.index, j.px.x, j.px.y, j.distancePx, j.prominence);
    }
    for (const std::string& r : cluster.rejected) {
      text += fmt::format("    not a blade: {}\n", r);
    }
    for (const std::string& m : cluster.split) {
      text += fmt::format("    split: {}\n", m);
    }
    for (const std::string& m : cluster.joined) {
      text += fmt::format("    joined: {}\n", m);
    }
    for (const std::string& m : cluster.merged) {
      text += fmt::format("    merged? {}\n", m);
    }
  }
  for (const std::string& d : first.droppedParts) {
    text += fmt::format("  dropped: {}\n", d);
  }
  return text;
}

} // namespace

std::string describeCapture(const CaptureRun& run, const std::string& kind, const std::string& levels,
                            bool explain) {
  const ExtractResult& first = run.results.front();
  const DepthFrame& reference = run.reference;
  std::string text = fmt::format(
      "{} ({}, {}x{}{}): {} blade{} in {} cluster{}, depth {:.3f}-{:.3f} m{}\n", reference.label(), kind,
      reference.width, reference.height, reference.relativeDepth ? ", relative depth" : "",
      first.blades.size(), plural(first.blades.size()), first.clusters.size(), plural(first.clusters.size()),
      first.nearMetres, first.farMetres, first.colourRefined ? ", colour-refined edges" : "");
  text += fmt::format("  {:<5} {:>6} {:>10} {:>10} {:>9}  {}\n", "blade", "knots", "length", "max width",
                      "length px", "skeleton");
  for (std::size_t b = 0; b < first.blades.size(); ++b) {
    const CapturedBlade& blade = first.blades[b];
    const float maxWidth = *std::max_element(blade.widths.begin(), blade.widths.end());
    text += fmt::format("  {:<5} {:>6} {:8.1f} cm {:8.2f} cm {:9.0f}  {}{}\n", b, blade.knots.size(),
                        blade.lengthMetres * 100.0f, maxWidth * 100.0f, blade.lengthPx,
                        blade.medialAxis ? "medial axis" : "symmetric matching",
                        blade.touchesBorder ? ", cut by the border" : "");
  }
  const int motionFrames = run.file.blades.front().source.motionFrames;
  text += fmt::format("  refined to {} knots over {} frame{} ({})\n", levels, motionFrames,
                      plural(static_cast<std::size_t>(motionFrames)),
                      run.motion == CaptureMotion::Recording ? "tracked through the recording"
                      : run.motion == CaptureMotion::Sway    ? "simulated sway"
                                                             : "static");
  if (explain) {
    text += explainClusters(first);
  }
  if (run.results.size() > 1) {
    int missing = 0;
    for (const TrackedBlade& t : run.tracks) {
      missing += t.missingFrames;
    }
    text += fmt::format("  {} frames, {} blade-frame{} not found (held)\n", run.results.size(), missing,
                        plural(static_cast<std::size_t>(missing)));
  }
  return text;
}

nlohmann::json syntheticTruthJson(const SyntheticScene& scene, const std::vector<SyntheticFrame>& frames) {
  nlohmann::json j;
  j["version"] = 1;
  j["kind"] = "sylva-capture-truth";
  j["intrinsics"] = {scene.intrinsics.fx, scene.intrinsics.fy, scene.intrinsics.cx, scene.intrinsics.cy};
  nlohmann::json list = nlohmann::json::array();
  for (const SyntheticFrame& f : frames) {
    nlohmann::json blades = nlohmann::json::array();
    for (std::size_t b = 0; b < f.truth.centrelinePx.size(); ++b) {
      nlohmann::json blade;
      blade["shape"] = bladeShapeName(scene.blades[b].shape);
      nlohmann::json px = nlohmann::json::array();
      nlohmann::json m = nlohmann::json::array();
      for (std::size_t i = 0; i < f.truth.centrelinePx[b].size(); ++i) {
        px.push_back({f.truth.centrelinePx[b][i].x, f.truth.centrelinePx[b][i].y, f.truth.widthsPx[b][i]});
        const glm::vec3 p = f.truth.centrelineMetres[b][i];
        m.push_back({p.x, p.y, p.z, f.truth.widthsMetres[b][i]});
      }
      blade["centrelinePx"] = std::move(px);
      blade["centrelineMetres"] = std::move(m);
      blades.push_back(std::move(blade));
    }
    list.push_back({{"frame", f.frame.frame}, {"blades", std::move(blades)}});
  }
  j["frames"] = std::move(list);
  return j;
}

std::vector<std::string> saveSyntheticFrames(const std::string& out,
                                             const std::vector<SyntheticFrame>& frames) {
  if (lowerExtension(out) != ".png") {
    FakenectWriter writer(out);
    for (const SyntheticFrame& f : frames) {
      const double t = f.frame.timestamp;
      if (!f.frame.colour.empty()) {
        writer.addRgb(f.frame.colour, t);
      }
      writer.addDepth(f.frame, t + 1e-3);
    }
    writer.finish();
    return {};
  }
  saveDepthPng(out, frames.front().frame);
  if (frames.front().frame.colour.empty()) {
    return {};
  }
  std::filesystem::path colour(out);
  colour.replace_filename(colour.stem().string() + "-colour.png");
  saveImage(colour, frames.front().frame.colour);
  return {colour.string()};
}

} // namespace sylva::capture

// `sylva capture`: grass blades from depth (docs/capture.md). `sylva capture INPUT` reads a 16-bit depth PNG,
// a Middlebury disparity map or a fakenect recording (or, with --kinect, a Kinect v1 through libfreenect,
// which the `fakenect` wrapper can replay), finds the blades, refines them and writes blade models and a
// debug overlay. `sylva capture synth` draws synthetic blade clusters with known truth. Every input and
// option error is one line naming the file, frame or option, found before any output is written; outputs are
// written atomically.
#include "Commands.hpp"
#include "flags/SourceOptions.hpp"

#include <sylva/blades/BladeModel.hpp>
#include <sylva/capture/Depth.hpp>
#include <sylva/capture/Extract.hpp>
#include <sylva/capture/Fakenect.hpp>
#include <sylva/capture/Input.hpp>
#include <sylva/capture/Kinect.hpp>
#include <sylva/capture/Pipeline.hpp>
#include <sylva/capture/Synthetic.hpp>
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Progress.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::app {
namespace {

namespace fs = std::filesystem;
using namespace sylva::capture;

struct CaptureOptions {
  std::string input;
  std::string format = "auto";
  bool kinect = false;
  int kinectFrames = 0;
  // depth PNG
  double unit = 0.001;
  std::string intrinsics;
  std::string colour;
  // Middlebury
  double focal = MiddleburyOptions{}.focalPx;
  double baseline = MiddleburyOptions{}.baselineMetres;
  double doffs = MiddleburyOptions{}.doffsPx;
  double disparityScale = MiddleburyOptions{}.disparityScale;
  // extraction
  double nearM = 0.0;
  double farM = 0.0;
  std::string roi;
  std::string contour = "mask";
  std::string canny;
  std::string centre = "auto";
  double prominence = ExtractOptions{}.prominence;
  double notchProminence = ExtractOptions{}.notchProminence;
  double notchMin = ExtractOptions{}.notchMinPx;
  double notchSigma = ExtractOptions{}.notchSigmaPx;
  double pointedTip = ExtractOptions{}.pointedTipFraction;
  bool noDepthSplit = false;
  double depthSplitOuter = ExtractOptions{}.depthSplitOuterShare;
  double tipSurfaces = ExtractOptions{}.tipSurfacesOuterShare;
  bool noOccludedWidths = false;
  bool noSurfaceWidths = false;
  double widthSmooth = ExtractOptions{}.widthSmoothKnots;
  bool noJoin = false;
  double smooth = ExtractOptions{}.smoothSigmaPx;
  double minLength = ExtractOptions{}.minBladeLengthPx;
  double minElongation = ExtractOptions{}.minElongation;
  int minArea = ExtractOptions{}.minClusterAreaPx;
  int clean = ExtractOptions{}.cleanRadiusPx;
  int knots = ExtractOptions{}.knots;
  double symmetry = ExtractOptions{}.symmetryRatio;
  bool noColour = false;
  bool noExtend = false;
  // recordings
  std::string frames;
  // models
  std::string levels = "64,32,16";
  double mu = 0.5;
  std::string variance = "displacement";
  bool rawMetres = false;
  std::string motion = "auto";
  std::string name;
  double scaleTo = 0.0;
  std::string out;
  std::string overlay;
  std::string stages;
  bool quiet = false;
  bool explain = false;
};

/** Parses "A-B" (inclusive) or "N" into a frame range; throws naming --frames. */
std::pair<int, int> parseFrameRange(const std::string& text) {
  int a = 0;
  int b = 0;
  char dash = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &a, &dash, &b, &extra) == 3 && dash == '-' && a >= 0 && b >= a) {
    return {a, b};
  }
  if (std::sscanf(text.c_str(), "%d%c", &a, &extra) == 1 && a >= 0) {
    return {a, a};
  }
  fail("--frames: expected A-B or N (0-based, inclusive), got '{}'", text);
}

ExtractOptions extractOptions(const CaptureOptions& o) {
  ExtractOptions e;
  e.nearMetres = static_cast<float>(o.nearM);
  e.farMetres = static_cast<float>(o.farM);
  if (!o.roi.empty()) {
    const std::vector<float> v = parseNumbers("--roi", o.roi, 4, "x0,y0,x1,y1");
    for (int i = 0; i < 4; ++i) {
      if (v[i] < 0.0f || v[i] > 65536.0f) {
        fail("--roi: coordinates must be in 0..65536 pixels, got '{}'", o.roi);
      }
      e.roi[i] = static_cast<int>(v[i]);
    }
    if (e.roi[2] <= e.roi[0] || e.roi[3] <= e.roi[1]) {
      fail("--roi: need x0 < x1 and y0 < y1, got '{}'", o.roi);
    }
  }
  e.contour = o.contour == "canny" ? ContourMethod::Canny : ContourMethod::Mask;
  if (!o.canny.empty()) {
    const std::vector<float> v = parseNumbers("--canny", o.canny, 2, "low,high metres");
    e.cannyLowMetres = v[0];
    e.cannyHighMetres = v[1];
  }
  if (o.centre == "auto") {
    e.centre = CentreMode::Auto;
  } else if (o.centre == "core") {
    e.centre = CentreMode::Core;
  } else if (o.centre == "centroid") {
    e.centre = CentreMode::Centroid;
  } else if (o.centre == "base") {
    e.centre = CentreMode::Base;
  } else {
    const std::vector<float> v = parseNumbers("--centre", o.centre, 2, "auto, core, centroid, base or X,Y");
    e.centre = CentreMode::Manual;
    e.centrePx = {v[0], v[1]};
  }
  e.prominence = o.prominence;
  e.notchProminence = o.notchProminence;
  e.notchMinPx = o.notchMin;
  e.notchSigmaPx = o.notchSigma;
  e.pointedTipFraction = o.pointedTip;
  e.depthSplit = !o.noDepthSplit;
  e.depthSplitOuterShare = o.depthSplitOuter;
  e.tipSurfacesOuterShare = o.tipSurfaces;
  e.occludedWidths = !o.noOccludedWidths;
  e.surfaceWidths = !o.noSurfaceWidths;
  e.widthSmoothKnots = o.widthSmooth;
  e.joinBroken = !o.noJoin;
  e.smoothSigmaPx = o.smooth;
  e.minBladeLengthPx = o.minLength;
  e.minElongation = o.minElongation;
  e.minClusterAreaPx = o.minArea;
  e.cleanRadiusPx = o.clean;
  e.knots = o.knots;
  e.symmetryRatio = o.symmetry;
  e.colourRefine = !o.noColour;
  e.extendToCentre = !o.noExtend;
  return e;
}

/** The input the options name, opened (errors name the option or the file). */
DepthInput openSource(const CaptureOptions& o) {
  DepthInputOptions in;
  in.input = o.input;
  in.format = o.format;
  in.kinect = o.kinect;
  in.kinectFrames = o.kinectFrames;
  in.kinectColour = !o.noColour;
  in.png.unitMetres = o.unit;
  if (!o.intrinsics.empty()) {
    const std::vector<float> v = parseNumbers("--intrinsics", o.intrinsics, 4, "fx,fy,cx,cy");
    if (v[0] <= 0.0f || v[1] <= 0.0f) {
      fail("--intrinsics: focal lengths must be > 0, got '{}'", o.intrinsics);
    }
    in.png.intrinsics = {v[0], v[1], v[2], v[3]};
  }
  in.colour = o.colour;
  in.middlebury.focalPx = o.focal;
  in.middlebury.baselineMetres = o.baseline;
  in.middlebury.doffsPx = o.doffs;
  in.middlebury.disparityScale = o.disparityScale;
  if (!o.frames.empty()) {
    in.frames = parseFrameRange(o.frames);
    in.framesText = o.frames;
  }
  DepthInput source = openDepthInput(in);
  for (const std::string& w : source.warnings) {
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  return source;
}

void runCapture(const CaptureOptions& o) {
  const ExtractOptions extract = extractOptions(o);
  const std::vector<int> levels = parseIntegers("--levels", o.levels, 2, 4096, "a knot count");
  for (std::size_t i = 1; i < levels.size(); ++i) {
    if (levels[i] >= levels[i - 1]) {
      fail("--levels: counts must decrease strictly, got '{}'", o.levels);
    }
  }
  if (levels.front() > o.knots) {
    fail("--levels: {} knots is more than --knots {}", levels.front(), o.knots);
  }
  DepthInput source = openSource(o);
  const std::string base = o.name.empty() ? inputStem(source.label) : o.name;
  std::string out = o.out;
  std::string overlay = o.overlay;
  if (out.empty() && overlay.empty()) {
    out = "out/capture/" + base + ".blades.json";
    overlay = "out/capture/" + base + "-overlay.png";
  }

  CaptureSettings settings;
  settings.extract = extract;
  settings.model.levels = levels;
  settings.model.mu = o.mu;
  settings.model.measure =
      o.variance == "distance" ? RefineOptions::Measure::Distance : RefineOptions::Measure::Displacement;
  settings.model.rawMetres = o.rawMetres;
  settings.motion = o.motion == "recording" ? CaptureMotion::Recording
                    : o.motion == "sway"    ? CaptureMotion::Sway
                    : o.motion == "none"    ? CaptureMotion::None
                                            : CaptureMotion::Auto;
  if (settings.motion == CaptureMotion::Recording && source.count() < 2) {
    fail("--motion recording: needs a recording with at least 2 frames in --frames");
  }
  settings.name = base;
  settings.scaleToMetres = o.scaleTo;
  settings.generator = fmt::format("sylva capture {}: {}", SYLVA_VERSION, source.label);
  const CaptureRun run = captureBlades(
      source.count(), [&](int i) { return source.frame(source.first + i); }, settings, source.label,
      "capturing " + source.label);
  const std::vector<std::string>& warnings = run.warnings;
  const std::size_t shownWarnings = 8;
  for (std::size_t i = 0; i < warnings.size() && i < shownWarnings; ++i) {
    std::fprintf(stderr, "warning: %s\n", warnings[i].c_str());
  }
  if (warnings.size() > shownWarnings) {
    std::fprintf(stderr, "warning: … and %zu more\n", warnings.size() - shownWarnings);
  }
  blades::BladeModelFile file = run.file;
  if (run.scale != 1.0f) {
    file.generator += fmt::format(" (scaled by {:.4g} so the longest blade is {} m)", run.scale, o.scaleTo);
  }
  if (!o.quiet) {
    std::fputs(describeCapture(run, source.kind, o.levels, o.explain).c_str(), stdout);
  }

  // Outputs last, each written atomically.
  if (!o.stages.empty()) {
    writeCaptureStages(o.stages, run.reference, run.results.front());
  }
  if (!overlay.empty()) {
    saveImage(overlay, overlayImage(run.reference, run.results.front()));
  }
  if (!out.empty()) {
    blades::saveBladeModels(out, file);
  }
  if (!o.quiet) {
    for (const std::string& path : {out, overlay, o.stages}) {
      if (!path.empty()) {
        std::printf("wrote %s\n", path.c_str());
      }
    }
  }
}

struct SynthOptions {
  std::string shape = "slim";
  int count = 5;
  std::string layout = "fan";
  double roll = 0.0;
  double pitch = 0.0;
  double dropout = 0.15;
  int sweep = 0;
  std::optional<std::uint64_t> sweepCluster;
  bool layoutGiven = false; ///< --layout on the command line: --sweep draws only that layout
  double bend = 0.3;
  double orientation = 0.0;
  double spread = 1.4;
  double lobe = 0.0;
  double distance = 0.65;
  std::uint64_t seed = 1;
  bool noNoise = false;
  bool noColour = false;
  int frames = 1;
  double amplitude = 0.25;
  double frequency = 0.8;
  double fps = 30.0;
  std::string out;
  std::string truth;
  bool evaluate = false;
};

/** `--sweep N`: N random clusters of every class captured and tallied, as the capture sweep test does. */
void runSweep(int clusters, std::uint64_t seed, std::optional<ClusterLayout> only) {
  SweepReport report;
  {
    Progress progress("capturing random clusters", static_cast<std::size_t>(clusters));
    report = captureSweep(clusters, seed, &progress, only);
  }
  std::fputs(describeSweep(report, only).c_str(), stdout);
}

void runSynth(const SynthOptions& o) {
  const std::optional<BladeShape> shape = parseBladeShape(o.shape);
  if (!shape) {
    fail("--shape: unknown shape '{}' (slim, quadratic, slender, bamboo, sharp)", o.shape);
  }
  const std::optional<ClusterLayout> layout = parseClusterLayout(o.layout);
  if (!layout) {
    fail("--layout: unknown layout '{}' (fan, occluded, crossing, dense)", o.layout);
  }
  if (o.sweep > 0) {
    runSweep(o.sweep, o.seed, o.layoutGiven ? layout : std::nullopt);
    return;
  }
  SyntheticScene scene;
  ClusterLayout drawn = *layout;
  if (o.sweepCluster) {
    // Exactly the cluster the sweep draws for this seed, from depth alone as the sweep captures it.
    scene = makeSweepCluster(*o.sweepCluster, &drawn, o.layoutGiven ? layout : std::nullopt);
    scene.colour = false;
  } else {
    scene = makeLayoutCluster(*layout, *shape, o.count, static_cast<float>(o.bend),
                              static_cast<float>(o.orientation), o.seed, static_cast<float>(o.spread));
    for (SyntheticBlade& b : scene.blades) {
      b.lobe = static_cast<float>(o.lobe);
    }
    scene.rootMetres = {0.0f, 0.2f * static_cast<float>(o.distance) / 0.65f, static_cast<float>(o.distance)};
    scene.rollRadians = static_cast<float>(o.roll);
    scene.pitchRadians = static_cast<float>(o.pitch);
    scene.edgeDropout = static_cast<float>(o.dropout);
    scene.noise = !o.noNoise;
    scene.colour = !o.noColour;
  }
  std::string out = o.out;
  if (out.empty()) {
    const std::string stem = o.sweepCluster ? fmt::format("sweep-{}", *o.sweepCluster) : "synth-" + o.shape;
    out = o.frames > 1 ? "out/capture/" + stem : "out/capture/" + stem + ".png";
  }
  const bool recording = lowerExtension(out) != ".png";
  if (!recording && o.frames > 1) {
    fail("--out {}: a PNG holds one frame; give a folder for a {}-frame recording", out, o.frames);
  }
  std::vector<SyntheticFrame> frames;
  {
    Progress progress("drawing synthetic frames", static_cast<std::size_t>(o.frames));
    if (o.frames == 1) {
      frames.push_back(renderScene(scene));
      progress.advance();
    } else {
      frames = swaySequence(scene, o.frames, o.fps, static_cast<float>(o.amplitude), o.frequency);
      progress.advance(static_cast<std::size_t>(o.frames));
    }
  }
  if (!recording) {
    // Evaluated as the PNG holds it (whole millimetres), so that capturing the file gives the same blades.
    roundToDepthPng(frames.front().frame);
  }
  if (o.evaluate) {
    for (const SyntheticFrame& f : frames) {
      const AccuracyReport r = evaluateCapture(f.truth, extractBlades(f.frame));
      std::printf(
          "frame %d: blades %d/%d, silhouette IoU %.3f, width error %.1f %% (worst %.1f %%), skeleton "
          "error %.2f px (worst %.2f px)\n",
          f.frame.frame, r.bladesFound, r.bladesExpected, r.silhouetteIoU, 100.0 * r.widthError,
          100.0 * r.widthErrorMax, r.skeletonErrorPx, r.skeletonErrorMaxPx);
    }
  }
  for (const std::string& file : saveSyntheticFrames(out, frames)) {
    std::printf("wrote %s\n", file.c_str());
  }
  if (!o.truth.empty()) {
    saveJsonFile(o.truth, syntheticTruthJson(scene, frames));
    std::printf("wrote %s\n", o.truth.c_str());
  }
  const std::size_t count = scene.blades.size();
  std::printf("wrote %s (%d frame%s, %zu %s blade%s, %s layout)\n", out.c_str(), o.frames,
              o.frames == 1 ? "" : "s", count, bladeShapeName(scene.blades.front().shape),
              count == 1 ? "" : "s", clusterLayoutName(drawn));
}

void registerCaptureSynth(CLI::App& capture) {
  auto* command = capture.add_subcommand(
      "synth",
      "Draw a synthetic blade cluster of known shape into a depth frame with Kinect-like noise: a 16-bit "
      "depth PNG (with a registered colour PNG), or a fakenect recording of it swaying");
  auto o = std::make_shared<SynthOptions>();
  command->add_option("--shape", o->shape, "Blade shape: slim, quadratic, slender, bamboo, sharp")
      ->check(CLI::IsMember({"slim", "quadratic", "slender", "bamboo", "sharp"}))
      ->capture_default_str();
  command->add_option("--count", o->count, "Blades in the cluster")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command
      ->add_option(
          "--layout", o->layout,
          "fan (one root), occluded (one blade in front of a neighbour, inside its outline), crossing "
          "(two roots, fans crossing), dense (the blades within 60 degrees)")
      ->check(CLI::IsMember({"fan", "occluded", "crossing", "dense"}))
      ->capture_default_str();
  command->add_option("--roll", o->roll, "Camera roll about its optical axis, radians (positive: clockwise)")
      ->check(finiteRange(-3.2, 3.2))
      ->capture_default_str();
  command->add_option("--pitch", o->pitch, "Camera pitch, radians (positive: looking down on the cluster)")
      ->check(finiteRange(-1.2, 1.2))
      ->capture_default_str();
  command->add_option("--dropout", o->dropout, "Fraction of depth-edge pixels that lose their depth")
      ->check(finiteRange(0.0, 1.0))
      ->capture_default_str();
  command
      ->add_option("--sweep", o->sweep,
                   "Instead of drawing one cluster: capture N random clusters (seeds from --seed; of every "
                   "layout, or of --layout when given) and print how many came out exact")
      ->check(CLI::Range(1, 100000));
  command
      ->add_option(
          "--sweep-cluster", o->sweepCluster,
          "Instead of the options above: draw the cluster the sweep draws for this seed (depth only; "
          "with --layout, of that layout), to capture it on its own")
      ->check(unsignedInteger())
      ->excludes("--sweep");
  command
      ->add_option("--bend", o->bend, "Turn of each blade from root to tip, radians (away from the centre)")
      ->check(finiteRange(-3.0, 3.0))
      ->capture_default_str();
  command->add_option("--orientation", o->orientation, "Lean of the whole cluster from vertical, radians")
      ->check(finiteRange(-1.5, 1.5))
      ->capture_default_str();
  command->add_option("--spread", o->spread, "Angle the blades fan over, radians")
      ->check(finiteRange(0.0, 3.0))
      ->capture_default_str();
  command
      ->add_option("--lobe", o->lobe, "A one-sided lobe on every blade, in blade widths (asymmetric blades)")
      ->check(finiteRange(0.0, 5.0))
      ->capture_default_str();
  command->add_option("--distance", o->distance, "Depth of the cluster's root, metres")
      ->check(finiteRange(0.4, 4.0))
      ->capture_default_str();
  command->add_option("--seed", o->seed, "Seed of the blade variation and the noise")
      ->check(unsignedInteger());
  command->add_flag("--no-noise", o->noNoise, "No sensor noise or quantisation (exact depth)");
  command->add_flag("--no-colour", o->noColour, "No colour frame");
  command->add_option("--frames", o->frames, "Frames of a swaying sequence (written as a fakenect recording)")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  command->add_option("--amplitude", o->amplitude, "Sway: extra tip bend amplitude, radians")
      ->check(finiteRange(0.0, 2.0))
      ->capture_default_str();
  command->add_option("--frequency", o->frequency, "Sway frequency, Hz")
      ->check(finiteRange(0.0, 30.0))
      ->capture_default_str();
  command->add_option("--fps", o->fps, "Frames per second of the sequence")
      ->check(finiteRange(1.0, 120.0))
      ->capture_default_str();
  command->add_option(
      "-o,--out", o->out,
      "A .png (one frame) or a folder (fakenect recording); default out/capture/synth-<shape>[.png]");
  command->add_option("--truth", o->truth, "Also write the ground truth (centrelines and widths) as JSON");
  command->add_flag("--evaluate", o->evaluate, "Capture each frame and print its accuracy against the truth");
  command->callback([o, command] {
    o->layoutGiven = command->count("--layout") > 0;
    runSynth(*o);
  });
}

} // namespace

void registerCapture(CLI::App& app) {
  auto* command = app.add_subcommand(
      "capture",
      "Capture grass blades from depth: a 16-bit depth PNG (mm), a Middlebury disparity map, a fakenect "
      "recording or a Kinect v1; writes blade models (JSON) and a debug overlay (docs/capture.md)");
  auto o = std::make_shared<CaptureOptions>();
  command->add_option("input", o->input, "Depth PNG, Middlebury disparity PNG or fakenect folder");
  command->add_option("--format", o->format, "Input format: auto (by file), png, middlebury, fakenect")
      ->check(CLI::IsMember({"auto", "png", "middlebury", "fakenect"}))
      ->capture_default_str();
  command->add_flag(
      "--kinect", o->kinect,
      "Capture from a Kinect v1 through libfreenect (replay a recording with `fakenect DIR sylva "
      "capture --kinect`)");
  command
      ->add_option("--kinect-frames", o->kinectFrames, "Kinect frames to grab (0: 1 live, all in a replay)")
      ->check(CLI::Range(0, 100000));
  command->add_option("--unit", o->unit, "Depth PNG: metres per stored unit")
      ->check(finiteRange(1e-6, 10.0))
      ->capture_default_str();
  command->add_option("--intrinsics", o->intrinsics,
                      "Depth PNG: fx,fy,cx,cy in pixels (default: Kinect v1 scaled)");
  command->add_option("--colour", o->colour,
                      "Depth PNG: a registered colour image to refine the blade edges with");
  command->add_option("--focal", o->focal, "Middlebury: focal length, pixels")
      ->check(finiteRange(1.0, 1e6))
      ->capture_default_str();
  command->add_option("--baseline", o->baseline, "Middlebury: stereo baseline, metres")
      ->check(finiteRange(1e-6, 100.0))
      ->capture_default_str();
  command->add_option("--doffs", o->doffs, "Middlebury: disparity offset, pixels")
      ->check(finiteRange(0.0, 1e5))
      ->capture_default_str();
  command
      ->add_option("--disparity-scale", o->disparityScale, "Middlebury: stored value to disparity in pixels")
      ->check(finiteRange(1e-6, 1e3))
      ->capture_default_str();
  command->add_option("--near", o->nearM, "Nearest depth of the blades, metres (0: automatic)")
      ->check(finiteRange(0.0, 1e4));
  command->add_option("--far", o->farM, "Farthest depth of the blades, metres (0: automatic, Otsu)")
      ->check(finiteRange(0.0, 1e4));
  command->add_option("--roi", o->roi, "Region of interest x0,y0,x1,y1 in pixels");
  command
      ->add_option("--contour", o->contour, "Outline: mask (trace the depth-range mask) or canny (on depth)")
      ->check(CLI::IsMember({"mask", "canny"}))
      ->capture_default_str();
  command->add_option("--canny", o->canny,
                      "Canny thresholds low,high in metres of depth step (default 0.02,0.06)");
  command->add_option("--centre", o->centre, "Cluster centre: auto, core, centroid, base or X,Y pixels")
      ->capture_default_str();
  command->add_option("--prominence", o->prominence, "Junction prominence, fraction of the largest distance")
      ->check(finiteRange(1e-4, 0.99))
      ->capture_default_str();
  command
      ->add_option(
          "--notch-prominence", o->notchProminence,
          "Junctions also at notches between tips this prominent, fraction of the largest distance (0: "
          "off)")
      ->check(finiteRange(0.0, 0.99))
      ->capture_default_str();
  command->add_option("--notch-min", o->notchMin, "Least depth of a notch and height of its tip, pixels")
      ->check(finiteRange(0.0, 1000.0))
      ->capture_default_str();
  command
      ->add_option("--notch-sigma", o->notchSigma,
                   "Smoothing of the distance signal notches are found in, sigma in pixels")
      ->check(finiteRange(0.0, 100.0))
      ->capture_default_str();
  command
      ->add_option(
          "--pointed-tip", o->pointedTip,
          "A pointed tip is a blade from this fraction of --min-length beyond its junctions (1: off)")
      ->check(finiteRange(0.01, 1.0))
      ->capture_default_str();
  command->add_flag("--no-depth-split", o->noDepthSplit,
                    "Keep blades whose outer halves part in depth as one (blades merged in the outline)");
  command
      ->add_option("--depth-split-outer", o->depthSplitOuter,
                   "Where a blade's visible end holds one surface, look for surfaces parting in depth over "
                   "this share of its length from the tip (0: off)")
      ->check(finiteRange(0.0, 0.99))
      ->capture_default_str();
  command
      ->add_option(
          "--tip-surfaces", o->tipSurfaces,
          "Over this outer share of the cluster, a depth surface ending in a free tip where no blade "
          "ends is one blade more (0: off)")
      ->check(finiteRange(0.0, 0.99))
      ->capture_default_str();
  command->add_flag("--no-occluded-widths", o->noOccludedWidths,
                    "Measure a blade only as wide as it shows where a nearer blade hides one of its edges");
  command
      ->add_option(
          "--width-smooth", o->widthSmooth,
          "Smoothing of each blade's final widths along it: a running median over +/- this many knots of "
          "a 128-knot line, then a Gaussian of 0.3 times that (0: none)")
      ->check(finiteRange(0.0, 64.0))
      ->capture_default_str();
  command->add_flag("--no-surface-widths", o->noSurfaceWidths,
                    "Measure a blade found on a medial axis across its whole region, not over its own depth "
                    "surface (blades in front of a neighbour then measure as wide as both)");
  command->add_flag("--no-join", o->noJoin,
                    "Keep the outer part of a blade that a nearer blade crosses as a blade of its own");
  command->add_option("--smooth", o->smooth, "Smoothing of the distance signal, sigma in pixels")
      ->check(finiteRange(0.0, 100.0))
      ->capture_default_str();
  command->add_option("--min-length", o->minLength, "Shortest blade beyond its junctions, pixels")
      ->check(finiteRange(0.0, 1e5))
      ->capture_default_str();
  command->add_option("--min-elongation", o->minElongation, "Least length/width ratio of a blade")
      ->check(finiteRange(0.0, 1e3))
      ->capture_default_str();
  command->add_option("--min-area", o->minArea, "Smallest cluster, pixels")
      ->check(CLI::Range(1, 1 << 30))
      ->capture_default_str();
  command->add_option("--clean", o->clean, "Radius of the mask's morphological close, pixels")
      ->check(CLI::Range(0, 32))
      ->capture_default_str();
  command->add_option("--knots", o->knots, "Knots of each captured skeleton before refining")
      ->check(CLI::Range(4, 4096))
      ->capture_default_str();
  command
      ->add_option("--symmetry", o->symmetry,
                   "Side-length ratio above which the medial axis replaces matching")
      ->check(finiteRange(1.0, 1e9))
      ->capture_default_str();
  command->add_flag("--no-colour", o->noColour, "Ignore colour frames (depth edges only)");
  command->add_flag("--no-extend", o->noExtend, "Do not extend skeletons to the cluster centre");
  command->add_option("--frames", o->frames, "Recording: frames A-B to use (0-based, inclusive)");
  command->add_option("--levels", o->levels, "Refined knot counts, finest first")->capture_default_str();
  command->add_option("--mu", o->mu, "Refining: weight of distance against movement variance (paper eq. 1)")
      ->check(finiteRange(0.0, 1.0))
      ->capture_default_str();
  command
      ->add_option(
          "--variance", o->variance,
          "Refining: variance of the relative position (displacement: sees bending) or of the distance "
          "(distance: the paper's eq. 3)")
      ->check(CLI::IsMember({"displacement", "distance"}))
      ->capture_default_str();
  command->add_flag(
      "--raw-metres", o->rawMetres,
      "Refining: form D in metres as the paper does (default: in mean knot spacings, so --mu weighs "
      "comparable terms)");
  command
      ->add_option("--motion", o->motion,
                   "Refining motion: auto (recording if several frames, else sway), recording, sway, none")
      ->check(CLI::IsMember({"auto", "recording", "sway", "none"}))
      ->capture_default_str();
  command->add_option("--name", o->name, "Name prefix of the blade models (default: the input's name)");
  command
      ->add_option("--scale-to", o->scaleTo,
                   "Scale the models so the longest blade is this long, metres (for relative depth)")
      ->check(finiteRange(1e-4, 100.0));
  command->add_option(
      "-o,--out", o->out,
      "Blade-model JSON (default, with neither -o nor --overlay: out/capture/<name>.blades.json)");
  command->add_option(
      "--overlay", o->overlay,
      "Debug overlay PNG (default, with neither -o nor --overlay: out/capture/<name>-overlay.png)");
  command->add_option("--stages", o->stages, "Folder for a picture of every pipeline stage (for docs)");
  command->add_flag("-q,--quiet", o->quiet, "No summary");
  command->add_flag(
      "--explain", o->explain,
      "Also print each cluster's centre, junctions and the segments that were not blades, and why");
  registerCaptureSynth(*command);
  command->callback([o, command] {
    if (command->get_subcommands().empty()) {
      runCapture(*o);
    }
  });
}

} // namespace sylva::app

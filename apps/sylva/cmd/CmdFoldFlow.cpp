// `sylva fold flow`: motion from a reference video. Reads two frames, computes the forward and backward
// optical flow, suggests point anchors inside one zone of a project, prints what it found, and with --out
// writes the project with the suggestion applied as a points tool (one "motion from video" edit). Every input
// error is one line naming the file or option, found before any output is written.
#include "cmd/CmdFoldFlow.hpp"
#include "Commands.hpp"
#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Flow.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/ProjectFile.hpp>
#include <sylva/folding/Synthesis.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace sylva::app {
namespace {

namespace fs = std::filesystem;
using namespace sylva::folding;

struct FlowOptions {
  std::string video;
  std::string project;
  std::string zone;
  std::vector<int> frames{0, 1};
  std::string method = "dis";
  double spacing = FlowSuggestOptions{}.spacingPx;
  double minMagnitude = FlowSuggestOptions{}.minMagnitudePx;
  double scale = 1.0;
  std::string map = "zone";
  int maxAnchors = FlowSuggestOptions{}.maxAnchors;
  std::string picture;
  std::string out;
};

void run(const FlowOptions& o) {
  requireExtension("--picture", o.picture, ".png");
  requireExtension("--out", o.out, ".json");
  if (o.frames.size() != 2 || o.frames[0] == o.frames[1]) {
    fail("--frames: expected two different frame indices A,B (from 0), got {}",
         o.frames.size() == 2 ? std::to_string(o.frames[0]) + "," + std::to_string(o.frames[1])
                              : "a wrong count");
  }
  const Project project = loadProject(o.project);
  const int zone = zoneIndexOption(project, o.project, o.zone);
  const Zone& z = project.zones[static_cast<std::size_t>(zone)];
  // Loads and checks every image of the project, as synth would, so --out never writes a project that fails.
  const ProjectImages images = loadProjectImages(project, o.project);
  const Image& image = images.images[static_cast<std::size_t>(project.imageIndex(z.image))];
  const glm::ivec2 imageSize(image.width(), image.height());

  const int a = o.frames[0];
  const int b = o.frames[1];
  const FlowMethod method = o.method == "farneback" ? FlowMethod::Farneback : FlowMethod::Dis;
  const VideoFlow flow = videoFlow(o.video, a, b, method);
  const FlowField& forward = flow.forward;
  const FlowField& backward = flow.backward;

  FlowSuggestOptions options;
  options.mapping = o.map == "image" ? FlowSuggestOptions::Mapping::Image : FlowSuggestOptions::Mapping::Zone;
  options.spacingPx = o.spacing;
  options.minMagnitudePx = o.minMagnitude;
  options.scale = o.scale;
  options.maxAnchors = o.maxAnchors;
  FlowSuggestStats stats;
  const auto pairs = suggestAnchors(forward, z.shape, imageSize, options, &backward, &stats);
  if (!o.out.empty() && pairs.empty()) {
    fail("{}: no anchors suggested for zone '{}' ({} grid points: {} irregular, {} inconsistent, {} still); "
         "try other --frames, a smaller --min-magnitude or --spacing",
         o.video, o.zone, stats.samples, stats.irregular, stats.inconsistent, stats.still);
  }

  std::fputs(describeVideoFlow(o.video, flow, a, b, method).c_str(), stdout);
  std::printf("  zone '%s' on '%s' (%dx%d), mapping %s: %.3g x %.3g image px per frame px\n", o.zone.c_str(),
              z.image.c_str(), imageSize.x, imageSize.y, o.map.c_str(), stats.imagePerFramePx.x,
              stats.imagePerFramePx.y);
  std::printf("  anchors: %zu suggested of %zu grid points (%zu irregular, %zu inconsistent, %zu still, %zu "
              "thinned)\n",
              pairs.size(), stats.samples, stats.irregular, stats.inconsistent, stats.still, stats.thinned);

  if (!o.picture.empty()) {
    saveImage(o.picture, flowPicture(forward));
    std::printf("%s\n", o.picture.c_str());
  }
  if (!o.out.empty()) {
    EditHistory history(project);
    applyFlowSuggestion(history, zone, pairs);
    saveProject(o.out, rebasedProject(history.project(), o.out));
    std::printf("%s: zone '%s' gets a points tool with %zu anchors\n", o.out.c_str(), o.zone.c_str(),
                pairs.size());
  }
}

} // namespace

void registerFoldFlow(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "flow",
      "Motion from a reference video: optical flow between two frames, suggested as point anchors for "
      "one zone (printed; applied as a points tool with --out)");
  auto o = std::make_shared<FlowOptions>();
  command
      ->add_option("video", o->video,
                   "Video file (any FFmpeg reads) or image sequence pattern (frames/%04d.png)")
      ->required();
  command->add_option("--project", o->project, "Project file (.json, format sylva-fold)")->required();
  command->add_option("--zone", o->zone, "Id of the zone the motion goes to")->required();
  command->add_option("--frames", o->frames, "The two frames A,B (from 0): the flow is A -> B")
      ->delimiter(',')
      ->expected(2)
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  command->add_option("--method", o->method, "Optical flow: dis (fast, large motion) or farneback (smooth)")
      ->check(CLI::IsMember({"dis", "farneback"}))
      ->capture_default_str();
  command->add_option("--spacing", o->spacing, "Image pixels between sampled anchors")
      ->check(finiteRange(1.0, 1e4))
      ->capture_default_str();
  command->add_option("--min-magnitude", o->minMagnitude, "Drop anchors moving less than this, image pixels")
      ->check(finiteRange(0.0, 1e4))
      ->capture_default_str();
  command->add_option("--scale", o->scale, "Multiply every motion (after the mapping); negative reverses it")
      ->check(finiteRange(-100.0, 100.0))
      ->capture_default_str();
  command
      ->add_option("--map", o->map, "Where the frame goes: onto the zone's bounding box, or the whole image")
      ->check(CLI::IsMember({"zone", "image"}))
      ->capture_default_str();
  command->add_option("--max-anchors", o->maxAnchors, "Most anchors kept (thinned evenly)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--picture", o->picture,
                      "Write the flow as a colour picture (.png: hue direction, value "
                      "magnitude)");
  command->add_option("--out", o->out,
                      "Write the project with the suggested anchors as a points tool (.json)");
  command->callback([o] { run(*o); });
}

} // namespace sylva::app

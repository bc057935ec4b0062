#include "Commands.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/render/ImageCompare.hpp>

#include <cstdio>

namespace sylva::app {

void registerImgdiff(CLI::App& app) {
  auto* command = app.add_subcommand(
      "imgdiff", "Compare two images (PNG/EXR); exit 0 if within tolerance, 1 if they differ, 2 on error");
  struct Options {
    std::string actual;
    std::string reference;
    std::string mask;
    std::string diff;
    std::string report;
    render::Tolerance tolerance{2, 0.0};
  };
  auto o = std::make_shared<Options>();
  command->add_option("actual", o->actual, "Image to check")->required();
  command->add_option("reference", o->reference, "Reference image")->required();
  command
      ->add_option("--max-diff", o->tolerance.maxChannelDiff,
                   "Largest per-channel difference (8-bit steps) a pixel may have and still pass")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  command
      ->add_option("--max-fraction", o->tolerance.maxFailingFraction,
                   "Largest fraction of failing pixels for the images to match")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_option("--mask", o->mask, "Grey image; pixels where it is 0 are ignored");
  command->add_option("--diff", o->diff, "Write a diff image (failing pixels red) here");
  command->add_option("--report", o->report, "Write a JSON report here");
  command->callback([o] {
    const Image actual = loadImage(o->actual);
    const Image reference = loadImage(o->reference);
    Image mask;
    if (!o->mask.empty()) {
      mask = loadImage(o->mask);
    }
    const render::CompareResult result =
        render::compareImages(actual, reference, o->tolerance, o->mask.empty() ? nullptr : &mask);
    if (!o->diff.empty() && !result.diff.empty()) {
      saveImage(o->diff, result.diff);
    }
    if (!o->report.empty()) {
      nlohmann::json json = result.toJson(o->tolerance);
      json["actual"] = o->actual;
      json["reference"] = o->reference;
      saveJsonFile(o->report, json);
    }
    if (!result.sizeMatches) {
      std::printf("DIFFER: sizes %dx%d and %dx%d\n", actual.width(), actual.height(), reference.width(),
                  reference.height());
    } else {
      std::printf("%s: %zu of %zu pixels (%.4f%%) differ by more than %d; max diff %d, mean %.3f\n",
                  result.passed ? "MATCH" : "DIFFER", result.failingPixels, result.comparedPixels,
                  100.0 * result.failingFraction(), o->tolerance.maxChannelDiff, result.maxChannelDiff,
                  result.meanChannelDiff);
    }
    exitCode() = result.passed ? 0 : 1;
  });
}

} // namespace sylva::app

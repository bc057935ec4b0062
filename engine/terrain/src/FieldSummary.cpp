#include <sylva/terrain/FieldSummary.hpp>

#include <sylva/terrain/Quadtree.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace sylva::terrain {

namespace {

std::string bytesText(std::size_t bytes) {
  if (bytes >= (std::size_t{1} << 20)) {
    return fmt::format("{:.2f} MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  }
  return fmt::format("{:.1f} KiB", static_cast<double>(bytes) / 1024.0);
}

/** The default quadtree of `sylva terrain info`: 16 roots over the field. */
Quadtree defaultTree(const HeightField& field) {
  return Quadtree(QuadtreeConfig::forRootCount(16, field.extentX(), field.extentZ()), field);
}

} // namespace

nlohmann::json describeHeightFieldJson(const HeightField& field, const LoadReport& report,
                                       const std::string& source) {
  const HeightFieldInfo info = heightFieldInfo(field);
  const Quadtree tree = defaultTree(field);
  const QuadtreeConfig& used = tree.config();
  nlohmann::json out = {{"source", source},
                        {"width", field.width()},
                        {"height", field.height()},
                        {"spacingX", field.spacingX()},
                        {"spacingZ", field.spacingZ()},
                        {"extentX", field.extentX()},
                        {"extentZ", field.extentZ()},
                        {"minHeight", info.minHeight},
                        {"maxHeight", info.maxHeight},
                        {"validSamples", info.validCount},
                        {"absentSamples", info.absentCount},
                        {"horizontalUnits", report.units},
                        {"horizontalUnitsReason", report.reason},
                        {"orientation", report.orientation},
                        {"warnings", report.warnings},
                        {"quadtree",
                         {{"roots", 16},
                          {"rootsX", used.rootsX},
                          {"rootsZ", used.rootsZ},
                          {"rootSize", used.rootSize},
                          {"maxDepth", used.maxDepth},
                          {"leafSize", tree.nodeSize(used.maxDepth)},
                          {"minMaxBytes", tree.memoryBytes()}}}};
  if (report.units == "degrees") {
    out["latitude"] = {{"centre", report.centreLatitude},
                       {"south", report.southLatitude},
                       {"north", report.northLatitude},
                       {"eastWestError", report.eastWestError}};
  }
  return out;
}

std::string describeHeightField(const HeightField& field, const LoadReport& report,
                                const std::string& source) {
  const HeightFieldInfo info = heightFieldInfo(field);
  const Quadtree tree = defaultTree(field);
  const QuadtreeConfig& used = tree.config();
  const std::size_t total = field.samples().size();
  std::string text = fmt::format("source    {}\n", source);
  text += fmt::format("size      {} x {} samples\n", field.width(), field.height());
  text += fmt::format("spacing   {:.6g} x {:.6g} m\n", field.spacingX(), field.spacingZ());
  text += fmt::format("units     {}: {}\n", report.units == "none" ? "none (1 m per sample)" : report.units,
                      report.reason);
  if (report.units == "degrees") {
    text += fmt::format("latitude  {:.4f} .. {:.4f}, converted at {:.4f} (east-west distances off by up to "
                        "{:.2f}% on the outer rows)\n",
                        report.southLatitude, report.northLatitude, report.centreLatitude,
                        100.0 * report.eastWestError);
  }
  text += fmt::format("rows      {}\n", report.orientation);
  text += fmt::format("extent    {:.6g} x {:.6g} m\n", field.extentX(), field.extentZ());
  text +=
      fmt::format("height    {:.3f} .. {:.3f} m (range {:.3f} m)\n", static_cast<double>(info.minHeight),
                  static_cast<double>(info.maxHeight), static_cast<double>(info.maxHeight - info.minHeight));
  text += fmt::format("absent    {} of {} samples ({:.2f}%)\n", info.absentCount, total,
                      100.0 * static_cast<double>(info.absentCount) / static_cast<double>(total));
  text +=
      fmt::format("quadtree  16 roots as {} x {} of {:.6g} m, max depth {} (leaves {:.6g} m), min/max memory "
                  "{}\n",
                  used.rootsX, used.rootsZ, used.rootSize, used.maxDepth, tree.nodeSize(used.maxDepth),
                  bytesText(tree.memoryBytes()));
  return text;
}

} // namespace sylva::terrain

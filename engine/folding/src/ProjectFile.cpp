#include <sylva/folding/ProjectFile.hpp>

#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/folding/Session.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace sylva::folding {

LoadedProject loadProjectFile(const std::string& file) {
  LoadedProject l;
  l.file = file;
  l.project = loadProject(file);
  l.images = loadProjectImages(l.project, l.file);
  return l;
}

Textures synthesizeLoaded(const LoadedProject& loaded, SynthesisStats* stats) {
  Progress progress("synthesis", std::max<std::size_t>(synthesisRows(loaded.project, loaded.images), 1));
  SynthesisStats own;
  SynthesisStats& s = stats != nullptr ? *stats : own;
  Textures textures =
      namingFile(loaded.file, [&] { return synthesize(loaded.project, loaded.images, &progress, &s); });
  if (progress.cancelled()) {
    fail("{}: synthesis cancelled", loaded.file);
  }
  for (const std::string& warning : stillZoneWarnings(loaded.project, s)) {
    log::warn("{}: {}", loaded.file, warning);
  }
  return textures;
}

int imageIndexOption(const Project& project, const std::string& option, const std::string& id) {
  if (id.empty()) {
    return project.canvasIndex();
  }
  const int index = project.imageIndex(id);
  if (index < 0) {
    std::string ids;
    for (const ImageEntry& e : project.images) {
      ids += (ids.empty() ? "" : ", ") + e.id;
    }
    fail("{}: no image '{}' in the project (images: {})", option, id, ids);
  }
  return index;
}

int zoneIndexOption(const Project& project, const std::string& file, const std::string& id) {
  std::string ids;
  for (std::size_t z = 0; z < project.zones.size(); ++z) {
    if (project.zones[z].id == id) {
      return static_cast<int>(z);
    }
    ids += (ids.empty() ? "" : ", ") + project.zones[z].id;
  }
  fail("--zone: {} has no zone '{}' (zones: {})", file, id, ids.empty() ? "none" : ids);
}

std::string describeSynthesis(const LoadedProject& loaded, const Textures& textures,
                              const SynthesisStats& stats, double seconds) {
  return fmt::format("{}: atlas {}x{}, {} images, {} zones, {} jump layer{}{}\n"
                     "  {} anchors, {} zone texels, {} folded, {} with several intervals; jumpMax {:.3f} px; "
                     "{:.2f} s\n",
                     loaded.file, textures.width(), textures.height(), loaded.project.images.size(),
                     loaded.project.zones.size(), textures.jump.size(), textures.jump.size() == 1 ? "" : "s",
                     textures.fold.empty() ? "" : ", extra fold intervals", stats.anchors, stats.zonePixels,
                     stats.foldedPixels, stats.multiInterval, textures.jumpMax(), seconds);
}

nlohmann::json describeProjectJson(const LoadedProject& loaded, const Atlas& atlas) {
  nlohmann::json images = nlohmann::json::array();
  for (const AtlasEntry& e : atlas.entries) {
    images.push_back({{"id", e.id},
                      {"size", {e.imageSize.x, e.imageSize.y}},
                      {"crop", {e.crop.min.x, e.crop.min.y, e.crop.max.x, e.crop.max.y}},
                      {"atlas_pos", {e.atlasPos.x, e.atlasPos.y}}});
  }
  return {{"file", loaded.file},
          {"project", toJson(loaded.project)},
          {"atlas", {{"size", {atlas.color.width(), atlas.color.height()}}, {"images", images}}}};
}

std::string describeProject(const LoadedProject& loaded, const Atlas& atlas) {
  const Project& p = loaded.project;
  // Names as the file format writes them (toJson), so the description and the file use the same words.
  const nlohmann::json json = toJson(p);
  std::string text =
      fmt::format("{}: sylva-fold version {}, seed {}\n", loaded.file, kProjectVersion, p.seed);
  text += fmt::format("atlas: {}x{}, gutter {} px, canvas '{}'\n", atlas.color.width(), atlas.color.height(),
                      p.gutter, p.images[static_cast<std::size_t>(p.canvasIndex())].id);
  text += "images:\n";
  for (std::size_t i = 0; i < p.images.size(); ++i) {
    const AtlasEntry& e = atlas.entries[i];
    text += fmt::format("  {:<12} {}  {}x{}, kept [{},{})-[{},{}) at atlas ({}, {})\n", e.id,
                        p.images[i].file.string(), e.imageSize.x, e.imageSize.y, e.crop.min.x, e.crop.min.y,
                        e.crop.max.x, e.crop.max.y, e.atlasPos.x, e.atlasPos.y);
  }
  text += "profiles:\n";
  for (std::size_t i = 0; i < p.profiles.size(); ++i) {
    const Profile& pr = p.profiles[i];
    const nlohmann::json& j = json["profiles"][i];
    text +=
        fmt::format("  {:<12} {}, period {:g} s, shift {:g}, loop {}\n", pr.id,
                    j["fn"]["type"].get<std::string>(), pr.periodS, pr.shift, j["loop"].get<std::string>());
  }
  std::string layers;
  for (double b : p.jumpLayers) {
    layers += (layers.empty() ? "" : ", ") + fmt::format("{:g}", b);
  }
  text += fmt::format("jump layers: {} (breakpoints {})\n", p.jumpLayers.size() - 1, layers);
  text += "zones:\n";
  for (std::size_t zi = 0; zi < p.zones.size(); ++zi) {
    const Zone& z = p.zones[zi];
    const nlohmann::json& j = json["zones"][zi];
    std::string tools;
    for (const nlohmann::json& t : j["tools"]) {
      tools += (tools.empty() ? "" : ", ") + t["type"].get<std::string>();
    }
    Vec2 lo(1e300);
    Vec2 hi(-1e300);
    for (const Vec2& v : z.shape.outline()) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    text +=
        fmt::format("  {:<12} on '{}', {} ({:g}, {:g})-({:g}, {:g}), profile '{}', layer {}, {} (R {:g}), "
                    "tools: {}; folding: {}\n",
                    z.id, z.image, z.shape.type == Shape::Type::Rect ? "rect" : "polygon", lo.x, lo.y, hi.x,
                    hi.y, z.profile, z.layer, j["interp"]["type"].get<std::string>(), z.interp.radius,
                    tools.empty() ? "none" : tools,
                    j.contains("folding") ? j["folding"]["type"].get<std::string>() : "none");
  }
  return text;
}

} // namespace sylva::folding

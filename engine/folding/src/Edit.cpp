// The editing layer: every change to a project is a named, validated, undoable edit on the model.
#include <sylva/folding/Edit.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/JsonNode.hpp>
#include <sylva/core/Files.hpp>

#include <nlohmann/json.hpp>

#include <set>
#include <stdexcept>

namespace sylva::folding {

EditHistory::EditHistory(Project project) : mProject(std::move(project)) {}

void EditHistory::apply(const std::string& name, int zone, const std::function<void(Project&)>& edit,
                        bool coalesce) {
  Project next = mProject;
  try {
    edit(next);
  } catch (const std::out_of_range&) {
    fail("edit '{}': no such zone, vertex, tool or anchor", name);
  }
  // The same validation as a file on disk, so an edit can never produce a project that would not load.
  Project checked = parseProject(toJson(next), "edit '" + name + "'");
  checked.baseDir = next.baseDir;
  if (mValidator) {
    mValidator(checked);
  }
  const bool merge = coalesce && mCoalescing && !mUndo.empty() && mUndo.back().change.name == name &&
                     mUndo.back().change.zone == zone;
  if (!merge) {
    mUndo.push_back({{name, zone}, std::move(mProject), mRevision});
  }
  mCoalescing = coalesce;
  mRedo.clear();
  mProject = std::move(checked);
  mRevision = ++mNextRevision;
}

EditHistory::Change EditHistory::undo() {
  mCoalescing = false;
  if (mUndo.empty()) {
    return {};
  }
  Entry entry = std::move(mUndo.back());
  mUndo.pop_back();
  mRedo.push_back({entry.change, mProject, mRevision});
  mProject = std::move(entry.before);
  mRevision = entry.beforeRevision;
  return entry.change;
}

EditHistory::Change EditHistory::redo() {
  mCoalescing = false;
  if (mRedo.empty()) {
    return {};
  }
  Entry entry = std::move(mRedo.back());
  mRedo.pop_back();
  mUndo.push_back({entry.change, mProject, mRevision});
  mProject = std::move(entry.before);
  mRevision = entry.beforeRevision;
  return entry.change;
}

std::vector<std::string> EditHistory::undoNames() const {
  std::vector<std::string> names;
  for (const Entry& e : mUndo) {
    names.push_back(e.change.name);
  }
  return names;
}

namespace {
Zone& zoneAt(Project& p, int zone) {
  if (zone < 0 || zone >= static_cast<int>(p.zones.size())) {
    fail("edit: no zone {}", zone);
  }
  return p.zones[static_cast<std::size_t>(zone)];
}
} // namespace

void moveZoneVertex(EditHistory& history, int zone, int vertex, Vec2 position) {
  history.apply("move zone vertex", zone, [&](Project& p) {
    Shape& shape = zoneAt(p, zone).shape;
    if (shape.type == Shape::Type::Rect) {
      // Rect corners 0..3 as in Shape::outline(): moving one keeps the rectangle axis-aligned.
      const std::vector<Vec2> corners = shape.outline();
      const Vec2 opposite = corners.at(static_cast<std::size_t>((vertex + 2) % 4));
      shape.min = glm::min(opposite, position);
      shape.max = glm::max(opposite, position);
    } else {
      shape.pts.at(static_cast<std::size_t>(vertex)) = position;
    }
  });
}

void addTool(EditHistory& history, int zone, Tool tool) {
  history.apply("add tool", zone, [&](Project& p) { zoneAt(p, zone).tools.push_back(tool); });
}

void removeTool(EditHistory& history, int zone, int tool) {
  history.apply("remove tool", zone, [&](Project& p) {
    auto& tools = zoneAt(p, zone).tools;
    if (tool < 0 || tool >= static_cast<int>(tools.size())) {
      fail("edit: zone {} has no tool {}", zone, tool);
    }
    tools.erase(tools.begin() + tool);
  });
}

void movePointAnchor(EditHistory& history, int zone, int tool, int pair, int end, Vec2 position) {
  history.apply("move anchor", zone, [&](Project& p) {
    auto& tools = zoneAt(p, zone).tools;
    auto* points = tool >= 0 && tool < static_cast<int>(tools.size())
                       ? std::get_if<PointsTool>(&tools[static_cast<std::size_t>(tool)])
                       : nullptr;
    if (!points) {
      fail("edit: zone {} tool {} is not a points tool", zone, tool);
    }
    points->pairs.at(static_cast<std::size_t>(pair))[end == 0 ? 0 : 1] = position;
  });
}

void setInterpolation(EditHistory& history, int zone, const Interpolation& interp) {
  history.apply("set interpolation", zone, [&](Project& p) { zoneAt(p, zone).interp = interp; });
}

void setProfileFunction(EditHistory& history, int profile, const PositionFunction& fn) {
  history.apply("set position function", -1,
                [&](Project& p) { p.profiles.at(static_cast<std::size_t>(profile)).fn = fn; });
}

void setProfileTiming(EditHistory& history, int profile, double periodS, double shift) {
  history.apply("set profile timing", -1, [&](Project& p) {
    Profile& pr = p.profiles.at(static_cast<std::size_t>(profile));
    pr.periodS = periodS;
    pr.shift = shift;
  });
}

namespace {
std::string freeId(const std::string& id, const std::set<std::string>& taken) {
  if (!taken.count(id)) {
    return id;
  }
  for (int n = 2;; ++n) {
    const std::string candidate = id + "-" + std::to_string(n);
    if (!taken.count(candidate)) {
      return candidate;
    }
  }
}

template <typename T> std::set<std::string> idsOf(const std::vector<T>& items) {
  std::set<std::string> ids;
  for (const T& item : items) {
    ids.insert(item.id);
  }
  return ids;
}
} // namespace

int addZone(EditHistory& history, Zone zone) {
  zone.id = freeId(zone.id.empty() ? "zone" : zone.id, idsOf(history.project().zones));
  const int index = static_cast<int>(history.project().zones.size());
  history.apply("add zone", index, [&](Project& p) { p.zones.push_back(zone); });
  return index;
}

void removeZone(EditHistory& history, int zone) {
  history.apply("remove zone", zone, [&](Project& p) {
    zoneAt(p, zone);
    p.zones.erase(p.zones.begin() + zone);
  });
}

void moveZoneToImage(EditHistory& history, int zone, const std::string& image) {
  history.apply("move zone to image", zone, [&](Project& p) { zoneAt(p, zone).image = image; });
}

void replaceZone(EditHistory& history, int zone, const Zone& value, const std::string& name, bool coalesce) {
  history.apply(
      name, zone, [&](Project& p) { zoneAt(p, zone) = value; }, coalesce);
}

int addProfile(EditHistory& history, Profile profile) {
  profile.id = freeId(profile.id.empty() ? "motion" : profile.id, idsOf(history.project().profiles));
  const int index = static_cast<int>(history.project().profiles.size());
  history.apply("add profile", -1, [&](Project& p) { p.profiles.push_back(profile); });
  return index;
}

void replaceProfile(EditHistory& history, int profile, const Profile& value, bool coalesce) {
  history.apply(
      "edit profile", -1,
      [&](Project& p) {
        Profile& target = p.profiles.at(static_cast<std::size_t>(profile));
        if (target.id != value.id) {
          for (Zone& z : p.zones) {
            if (z.profile == target.id) {
              z.profile = value.id;
            }
          }
        }
        target = value;
      },
      coalesce);
}

int addImage(EditHistory& history, ImageEntry image) {
  image.id = freeId(image.id.empty() ? "image" : image.id, idsOf(history.project().images));
  const int index = static_cast<int>(history.project().images.size());
  history.apply("add image", -1, [&](Project& p) { p.images.push_back(image); });
  return index;
}

// ---------------------------------------------------------------------------------------------------------
// Files of an editing session

std::filesystem::path autosavePath(const std::filesystem::path& projectFile) {
  return projectFile.parent_path() / ("." + projectFile.filename().string() + ".autosave");
}

void autosave(const EditHistory& history, const std::filesystem::path& projectFile) {
  saveJsonFile(autosavePath(projectFile), toJson(history.project()));
}

std::optional<Project> recoverAutosave(const std::filesystem::path& projectFile, std::string* warning) {
  const std::filesystem::path sidecar = autosavePath(projectFile);
  if (!std::filesystem::exists(sidecar)) {
    return std::nullopt;
  }
  Project recovered;
  try {
    recovered = parseProject(loadJsonFile(sidecar), sidecar.string());
  } catch (const Error& e) {
    if (warning) {
      *warning = e.what();
    }
    return std::nullopt;
  }
  recovered.baseDir = projectFile.parent_path();
  if (std::filesystem::exists(projectFile)) {
    try {
      if (loadProject(projectFile) == recovered) {
        return std::nullopt; // saved after the last autosave: nothing to recover
      }
    } catch (const Error&) {
      // An unreadable project file: the sidecar is the better copy.
    }
  }
  return recovered;
}

void saveEdited(EditHistory& history, const std::filesystem::path& projectFile) {
  saveProject(projectFile, history.project());
  history.markSaved();
  std::error_code ignored;
  std::filesystem::remove(autosavePath(projectFile), ignored);
}

namespace {

/** `project` as JSON with its zones or profiles replaced by `part`'s, for validation in context. */
Project parseInContext(const Project& project, const nlohmann::json& part, const char* field,
                       const char* format, const std::string& where) {
  requireJsonVersion(part, 1, where);
  const JsonNode root(part, where);
  root.object({"format", "version", field});
  if (root["format"].value() != format) {
    root["format"].error(fmt::format("expected \"{}\"", format));
  }
  (void)root[field]; // missing field
  nlohmann::json combined = toJson(project);
  combined[field] = part[field];
  if (std::string(field) == "profiles") {
    combined["zones"] = nlohmann::json::array(); // zones may name profiles the import replaces
  }
  return parseProject(combined, where);
}

} // namespace

nlohmann::json exportZones(const Project& project, const std::vector<int>& zones) {
  const nlohmann::json all = toJson(project);
  nlohmann::json out = {{"format", "sylva-fold-zones"}, {"version", 1}, {"zones", nlohmann::json::array()}};
  for (int z : zones) {
    out["zones"].push_back(all["zones"].at(static_cast<std::size_t>(z)));
  }
  return out;
}

void importZones(EditHistory& history, const nlohmann::json& json, const std::string& where) {
  const Project parsed = parseInContext(history.project(), json, "zones", "sylva-fold-zones", where);
  history.apply("import zones", -1, [&](Project& p) {
    std::set<std::string> taken;
    for (const Zone& z : p.zones) {
      taken.insert(z.id);
    }
    for (Zone zone : parsed.zones) {
      zone.id = freeId(zone.id, taken);
      taken.insert(zone.id);
      p.zones.push_back(std::move(zone));
    }
  });
}

nlohmann::json exportProfiles(const Project& project) {
  return {{"format", "sylva-fold-profiles"}, {"version", 1}, {"profiles", toJson(project)["profiles"]}};
}

void importProfiles(EditHistory& history, const nlohmann::json& json, const std::string& where) {
  const Project parsed = parseInContext(history.project(), json, "profiles", "sylva-fold-profiles", where);
  history.apply("import profiles", -1, [&](Project& p) {
    for (const Profile& profile : parsed.profiles) {
      const int existing = p.profileIndex(profile.id);
      if (existing >= 0) {
        p.profiles[static_cast<std::size_t>(existing)] = profile;
      } else {
        p.profiles.push_back(profile);
      }
    }
  });
}

} // namespace sylva::folding

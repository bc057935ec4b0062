// The editing layer: every change to a project is a named, validated, undoable edit on the model.
#include <sylva/folding/Edit.hpp>

#include <sylva/core/Error.hpp>

#include <nlohmann/json.hpp>

namespace sylva::folding {

EditHistory::EditHistory(Project project) : mProject(std::move(project)) {}

void EditHistory::apply(const std::string& name, int zone, const std::function<void(Project&)>& edit) {
  Project next = mProject;
  edit(next);
  // The same validation as a file on disk, so an edit can never produce a project that would not load.
  Project checked = parseProject(toJson(next), "edit '" + name + "'");
  checked.baseDir = next.baseDir;
  mUndo.push_back({{name, zone}, std::move(mProject)});
  mRedo.clear();
  mProject = std::move(checked);
}

EditHistory::Change EditHistory::undo() {
  if (mUndo.empty()) {
    return {};
  }
  Entry entry = std::move(mUndo.back());
  mUndo.pop_back();
  mRedo.push_back({entry.change, mProject});
  mProject = std::move(entry.before);
  return entry.change;
}

EditHistory::Change EditHistory::redo() {
  if (mRedo.empty()) {
    return {};
  }
  Entry entry = std::move(mRedo.back());
  mRedo.pop_back();
  mUndo.push_back({entry.change, mProject});
  mProject = std::move(entry.before);
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

} // namespace sylva::folding

#pragma once

#include <sylva/folding/Project.hpp>

#include <functional>
#include <string>
#include <vector>

namespace sylva::folding {

/**
 * Every change to a project is an edit: a named function on the model, checked by the same validation as a
 * loaded file (an edit that would make the project invalid throws sylva::Error and changes nothing). The
 * history keeps snapshots, so undo and redo restore the exact earlier state. Never touches GL; the editor's
 * widgets, the CLI and the tests call the same edits.
 */
class EditHistory {
public:
  explicit EditHistory(Project project);

  const Project& project() const { return mProject; }

  /** What an edit touched: the zone index (−1: project-wide, e.g. a profile) for region re-synthesis. */
  struct Change {
    std::string name;
    int zone = -1;
  };

  /** Applies `edit` to a copy, validates it, then commits it and clears the redo stack. */
  void apply(const std::string& name, int zone, const std::function<void(Project&)>& edit);
  bool canUndo() const { return !mUndo.empty(); }
  bool canRedo() const { return !mRedo.empty(); }
  /** Undoes/redoes the last edit; returns what changed (name empty when there was nothing to do). */
  Change undo();
  Change redo();
  /** Names of the edits on the undo stack, oldest first. */
  std::vector<std::string> undoNames() const;

private:
  struct Entry {
    Change change;
    Project before;
  };
  Project mProject;
  std::vector<Entry> mUndo;
  std::vector<Entry> mRedo;
};

/** Common edits (each a call to EditHistory::apply with a descriptive name). */
void moveZoneVertex(EditHistory& history, int zone, int vertex, Vec2 position);
void addTool(EditHistory& history, int zone, Tool tool);
void removeTool(EditHistory& history, int zone, int tool);
/** Moves one point of a points tool: `end` 0 = from (a), 1 = to (b). */
void movePointAnchor(EditHistory& history, int zone, int tool, int pair, int end, Vec2 position);
void setInterpolation(EditHistory& history, int zone, const Interpolation& interp);
void setProfileFunction(EditHistory& history, int profile, const PositionFunction& fn);
void setProfileTiming(EditHistory& history, int profile, double periodS, double shift);

} // namespace sylva::folding

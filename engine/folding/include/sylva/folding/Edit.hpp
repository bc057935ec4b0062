#pragma once

#include <sylva/folding/Project.hpp>

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
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
  /** Starts the history at `project` (nothing to undo). */
  explicit EditHistory(Project project);

  /** The current state. */
  const Project& project() const { return mProject; }

  /** What an edit touched: the zone index (−1: project-wide, e.g. a profile) for region re-synthesis. */
  struct Change {
    /** The edit's name (as shown in the Edit menu), empty when nothing changed. */
    std::string name;
    /** The zone it touched; −1: project-wide. */
    int zone = -1;
  };

  /**
   * Applies `edit` to a copy, validates it (as a file would be, then with the validator if one is set), then
   * commits it and clears the redo stack. With `coalesce`, an edit of the same name right after another
   * coalescing one (a mouse drag: one edit per motion event) replaces the state without a new undo entry, so
   * the whole drag undoes in one step; any other edit, undo, redo or endCoalescing() ends the run.
   */
  void apply(const std::string& name, int zone, const std::function<void(Project&)>& edit,
             bool coalesce = false);
  /** Ends a run of coalescing edits (the mouse button went up). */
  void endCoalescing() { mCoalescing = false; }
  /**
   * An extra check every edit must pass before it commits (the editor checks zones against the loaded
   * image sizes); it throws sylva::Error to refuse the edit.
   */
  void setValidator(std::function<void(const Project&)> validator) { mValidator = std::move(validator); }
  /** Whether there is an edit to undo. */
  bool canUndo() const { return !mUndo.empty(); }
  /** Whether there is an undone edit to redo. */
  bool canRedo() const { return !mRedo.empty(); }
  /** Undoes/redoes the last edit; returns what changed (name empty when there was nothing to do). */
  Change undo();
  /** Redoes the last undone edit; returns what changed (name empty when there was nothing to do). */
  Change redo();
  /** Names of the edits on the undo stack, oldest first. */
  std::vector<std::string> undoNames() const;

  /** True when the project differs from the state last marked saved (undoing back to it clears the mark). */
  bool dirty() const { return mRevision != mSavedRevision; }
  /** Records the current state as saved (call after writing the file). */
  void markSaved() { mSavedRevision = mRevision; }

private:
  struct Entry {
    Change change;
    Project before;
    std::uint64_t beforeRevision = 0;
  };
  Project mProject;
  std::uint64_t mRevision = 0;
  std::uint64_t mNextRevision = 0;
  std::uint64_t mSavedRevision = 0;
  std::vector<Entry> mUndo;
  std::vector<Entry> mRedo;
  bool mCoalescing = false;
  std::function<void(const Project&)> mValidator;
};

/** Common edits (each a call to EditHistory::apply with a descriptive name). */
void moveZoneVertex(EditHistory& history, int zone, int vertex, Vec2 position);
/** Appends `tool` to zone `zone`'s tools. */
void addTool(EditHistory& history, int zone, Tool tool);
/** Removes tool `tool` of zone `zone`. */
void removeTool(EditHistory& history, int zone, int tool);
/** Moves one point of a points tool: `end` 0 = from (a), 1 = to (b). */
void movePointAnchor(EditHistory& history, int zone, int tool, int pair, int end, Vec2 position);
/** Sets zone `zone`'s interpolation. */
void setInterpolation(EditHistory& history, int zone, const Interpolation& interp);
/** Sets profile `profile`'s position function. */
void setProfileFunction(EditHistory& history, int profile, const PositionFunction& fn);
/** Sets profile `profile`'s period (seconds) and shift (cycles). */
void setProfileTiming(EditHistory& history, int profile, double periodS, double shift);
/** Appends a zone (its id made unique: "zone" → "zone-2"); returns its index. */
int addZone(EditHistory& history, Zone zone);
/** Removes zone `zone`. */
void removeZone(EditHistory& history, int zone);
/**
 * Moves a zone to another image (the thesis's motion-zone panel): geometry keeps its pixel coordinates, so
 * the edit is refused when the zone does not fit the new image.
 */
void moveZoneToImage(EditHistory& history, int zone, const std::string& image);
/** Replaces a zone wholesale (the properties panel edits a copy); `coalesce` as in EditHistory::apply. */
void replaceZone(EditHistory& history, int zone, const Zone& value, const std::string& name,
                 bool coalesce = false);
/** Appends a profile (id made unique); returns its index. */
int addProfile(EditHistory& history, Profile profile);
/** Replaces a profile wholesale (live sliders coalesce); zones keep naming it by its (new) id. */
void replaceProfile(EditHistory& history, int profile, const Profile& value, bool coalesce = false);
/** Appends an input image (id made unique); returns its index. */
int addImage(EditHistory& history, ImageEntry image);

// ---------------------------------------------------------------------------------------------------------
// Files of an editing session

/** The autosave sidecar of a project file: `.NAME.autosave` (NAME the project file's name) in the same
 * directory. */
std::filesystem::path autosavePath(const std::filesystem::path& projectFile);
/** Writes the current project to the sidecar, atomically (an editor calls it every few seconds when dirty).
 */
void autosave(const EditHistory& history, const std::filesystem::path& projectFile);
/**
 * Crash recovery: the sidecar's project when the sidecar exists, is valid, and differs from the project file
 * (or that file is missing); nullopt otherwise. A sidecar that does not load is ignored and its error
 * returned in `warning` (if given). The recovered project resolves files against the project file's
 * directory.
 */
std::optional<Project> recoverAutosave(const std::filesystem::path& projectFile,
                                       std::string* warning = nullptr);
/** Saves the project to `projectFile` (atomically), marks the history saved, and removes the sidecar. */
void saveEdited(EditHistory& history, const std::filesystem::path& projectFile);

/** Motion zones on their own (the thesis's "export motion zones"): format `sylva-fold-zones`, version 1. */
nlohmann::json exportZones(const Project& project, const std::vector<int>& zones);
/**
 * Appends the zones of an exported file as one edit. Their images and profiles must exist in the project;
 * ids that are taken get a suffix ("eyeL" → "eyeL-2"). Errors name `where` and the JSON path.
 */
void importZones(EditHistory& history, const nlohmann::json& json, const std::string& where);
/** Motion profiles on their own: format `sylva-fold-profiles`, version 1. */
nlohmann::json exportProfiles(const Project& project);
/** Replaces the profiles with the same id and appends the others, as one edit. */
void importProfiles(EditHistory& history, const nlohmann::json& json, const std::string& where);

} // namespace sylva::folding

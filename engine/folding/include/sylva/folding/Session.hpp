#pragma once

// An editing session: a project file, its edit history, its loaded images and its synthesised textures,
// kept in step. The editor (`sylva fold edit`) is a view of one Session; no GL here.

#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/Synthesis.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sylva {
class Progress;
}

namespace sylva::folding {

/** An open folding project in the editor: the file, its undo history, its images and textures kept up to date
 * with the edits, and autosave. */
class Session {
public:
  /**
   * Opens a project file. With `recover`, a valid autosave sidecar that differs from the file
   * (recoverAutosave) becomes the current state as one undoable edit "recover autosave", so the session is
   * dirty and undo returns to the file's state; `notice` (if given) then says so. Errors name the file.
   */
  static std::unique_ptr<Session> open(const std::filesystem::path& file, bool recover = true,
                                       std::string* notice = nullptr);
  /**
   * A new project over `images` (ids from the file stems), with one profile "motion" (sine, 2 s) and no
   * zones, to be saved as `projectFile` (image paths are written relative to its directory). Not on disk
   * until save(); starts dirty.
   */
  static std::unique_ptr<Session> fromImages(const std::vector<std::filesystem::path>& images,
                                             const std::filesystem::path& projectFile);

  /**
   * A session over a project and images already in memory (generated content, benchmarks): nothing is read
   * from disk until images are reloaded; it will be saved as `projectFile`. The images must fit the zones.
   */
  static std::unique_ptr<Session> fromMemory(Project project, ProjectImages images,
                                             const std::filesystem::path& projectFile);

  /** The project file (absolute). */
  const std::filesystem::path& file() const { return mFile; }
  /** The undo history (edits go through it). */
  EditHistory& history() { return mHistory; }
  /** The current project. */
  const Project& project() const { return mHistory.project(); }
  /** The loaded images. */
  const ProjectImages& images() const { return mImages; }
  /** Image `index` in pixels. */
  glm::ivec2 imageSize(int index) const;
  /** The input image files, absolute, in project order (what an external editor changes). */
  std::vector<std::filesystem::path> imageFiles() const;

  /** The textures of the last synthesis (nullptr before the first). */
  const Textures* textures() const { return mTextures.get(); }
  /** True when the project changed since the textures were made (or there are none). */
  bool stale() const;

  /** What synthesize() did. */
  struct Update {
    Rect region;       ///< atlas texels that changed (the whole atlas after a full synthesis)
    bool full = false; ///< a new atlas: upload everything
    double ms = 0.0;   ///< wall time
  };
  /**
   * Brings the textures up to date: nothing when they are current; when the atlas layout is unchanged, only
   * the atlas boxes of the zones that differ (before and after the edits) are re-synthesised, or `hint`
   * (atlas texels, e.g. anchorMoveAtlasRect of a dragged anchor) when given; otherwise a full synthesis
   * (counted by `progress`). Deterministic: the result always equals a full synthesis of the project.
   */
  Update synthesize(std::optional<Rect> hint = std::nullopt, Progress* progress = nullptr);

  /**
   * True when the next synthesize() cannot update regions: no textures yet, or the images, canvas, jump
   * layers or zone count changed. (An atlas layout change is found only inside synthesize().) The editor runs
   * such a synthesis in the background with a snapshot() and install()s the result.
   */
  bool needsFullSynthesis() const;
  /** What a background full synthesis needs: copies, so edits may go on meanwhile. */
  struct Snapshot {
    /** The project as it is. */
    Project project;
    /** Its images. */
    ProjectImages images;
  };
  /** Copies of the project and images for a background synthesis. */
  Snapshot snapshot();
  /**
   * Installs textures synthesised from `from` (a snapshot's project). Edits made since leave the session
   * stale, and the next synthesize() updates only what they changed. Ignored (returns false) when the images
   * were reloaded meanwhile.
   */
  bool install(Textures textures, const Project& from, const ProjectImages& images);

  /**
   * Re-reads every input image and mask from disk (an external editor saved one), keeping zones and
   * anchors; the next synthesize() is a full one. When a zone no longer fits a resized image the old
   * images stay and sylva::Error says which zone and file.
   */
  void reloadImages();

  /**
   * Re-reads the masks after zone `zone`'s freeze or fold mask file was rewritten in place (the freeze
   * brush): the next synthesize() redoes that zone.
   */
  void masksChanged(int zone);

  /** Saves to file() (atomically), marks the history saved and removes the autosave sidecar. */
  void save();
  /** Saves under a new name; relative image paths are rewritten against the new directory. */
  void saveAs(const std::filesystem::path& file);
  /** Writes the autosave sidecar of file() (Edit.hpp autosavePath). */
  void autosaveNow() const;

private:
  Session(std::filesystem::path file, Project project);
  void loadImages();
  /** Edits must keep every zone inside the loaded images. */
  void installValidator();
  /** Reloads the per-zone masks when zones came, went or name other mask files since they were loaded. */
  void syncMasks();
  /** Per zone: the freeze mask and fold mask files its loaded masks came from. */
  using MaskKey = std::pair<std::filesystem::path, std::filesystem::path>;
  static std::vector<MaskKey> maskKeys(const Project& project);

  std::filesystem::path mFile;
  EditHistory mHistory;
  ProjectImages mImages;
  std::unique_ptr<Textures> mTextures;
  Project mSynthesized;           ///< the project mTextures were made from
  std::vector<MaskKey> mMaskKeys; ///< what mImages' per-zone masks were loaded for
};

/** Rows synthesize() counts on its Progress (each zone's box clipped to its image): a progress total. */
std::size_t synthesisRows(const Project& project, const ProjectImages& images);

} // namespace sylva::folding

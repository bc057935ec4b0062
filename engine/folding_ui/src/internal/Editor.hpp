#pragma once
// `sylva fold edit` internals (engine/folding_ui/src/): the FoldEditor class, shared by the screen files
// (Editor.cpp, Canvas.cpp, Chrome.cpp, Panels.cpp, Preview.cpp, Input.cpp, Files.cpp), and the helpers they
// share.

#include <sylva/folding_ui/Editor.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/folding/Canvas.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Flow.hpp>
#include <sylva/folding/Handles.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Session.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/folding/Templates.hpp>
#include <sylva/folding/Workspace.hpp>
#include <sylva/folding/gpu/FoldRenderer.hpp>
#include <sylva/folding/gpu/ShaderExport.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/media/Export.hpp>
#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/ui/ImageCanvas.hpp>
#include <sylva/ui/WindowShell.hpp>

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace sylva::folding_ui {

namespace fs = std::filesystem;
using ui::imageTexture;
using ui::textureId;

using namespace sylva::folding;
using namespace sylva::media;

// ---------------------------------------------------------------------------------------------------------
// Tools

enum class ToolKind : int {
  Select,
  Rectangle,
  Polygon,
  Translate,
  Scale,
  Points,
  Curve,
  Lasso,
  Fold,
  Mask,
  Freeze,
  Zero,
  Count
};

struct ToolInfo {
  const char* name;
  const char* key; ///< shortcut shown in the toolbox
  int glfwKey;
  const char* help; ///< one line in the properties panel
};

constexpr std::array<ToolInfo, static_cast<std::size_t>(ToolKind::Count)> kTools{{
    {"Select / move", "V", GLFW_KEY_V,
     "Click a zone to select it; drag any point (zone corner, anchor, curve "
     "point) to move it. Right or middle drag pans, the wheel zooms."},
    {"Rectangle zone", "R", GLFW_KEY_R, "Drag a rectangle: a new motion zone on this image."},
    {"Polygon zone", "P", GLFW_KEY_P, "Click the vertices; Enter or a double click closes the polygon."},
    {"Translate", "T", GLFW_KEY_T, "Drag inside the selected zone: the whole zone moves by the drag."},
    {"Scale", "S", GLFW_KEY_S, "Press at the centre, drag right to grow, left to shrink."},
    {"Point mapping", "A", GLFW_KEY_A, "Drag from where content is to where it should go (an anchor pair)."},
    {"Curve mapping", "C", GLFW_KEY_C,
     "Click 4 control points of the source curve, then 4 of the destination."},
    {"Lasso deform", "L", GLFW_KEY_L, "Click a polygon, Enter closes it; then drag its orange 'to' points."},
    {"Folding zone", "F", GLFW_KEY_F, "Click the polygon the jump paths fold into; Enter closes it."},
    {"Alpha mask", "M", GLFW_KEY_M, "Import a grey/alpha image as the fold region of the selected zone."},
    {"Freeze brush", "B", GLFW_KEY_B, "Paint where nothing may move (Shift erases)."},
    {"Still line", "Z", GLFW_KEY_Z, "Click a polyline of still points; Enter ends it."},
}};

constexpr const char* kFunctionNames[] = {"linear", "piecewise", "exponential", "sigmoid", "sine"};
constexpr const char* kLoopNames[] = {"none", "ping-pong", "crossfade"};
constexpr const char* kInterpNames[] = {"Shepard (IDW)", "modified Shepard", "modified Shepard + randomness"};
constexpr const char* kFoldingNames[] = {"none", "polygons", "alpha mask", "object"};

/** Workflow steps of the thesis (§4): the bar highlights the first one not yet done. */
constexpr const char* kSteps[] = {"1 Zones",      "2 Motion",  "3 Profiles",
                                  "4 Synthesise", "5 Preview", "6 Export"};

constexpr ImU32 kZoneColour = IM_COL32(255, 220, 60, 255);
constexpr ImU32 kZoneSelected = IM_COL32(255, 255, 255, 255);
constexpr ImU32 kFromColour = IM_COL32(80, 200, 255, 255);
constexpr ImU32 kToColour = IM_COL32(255, 140, 40, 255);
constexpr ImU32 kFoldColour = IM_COL32(230, 80, 230, 255);
constexpr ImU32 kStillColour = IM_COL32(120, 255, 120, 255);
constexpr ImU32 kSuggestColour = IM_COL32(255, 90, 90, 255);

// ---------------------------------------------------------------------------------------------------------
// The editor

/** A prompt for a path (ImGui has no file dialog; a path field with the last directory is quicker anyway). */
struct PathPrompt {
  enum class Action {
    None,
    Open,
    NewFromImage,
    SaveAs,
    ImportZones,
    ExportZones,
    ImportProfiles,
    ExportProfiles,
    MaskImport,
    ExportTextures,
    ExportGif,
    ExportVideo,
    ExportSprites,
    ExportShader,
    ExportWeb,
    Video
  };
  Action action = Action::None;
  std::string title;
  char path[1024] = {};
  bool open = false;
};

struct Gesture {
  bool active = false;
  ToolKind tool = ToolKind::Select;
  Vec2 start{0.0};
  Vec2 current{0.0};
  std::optional<Handle> handle;
  Vec2 handleLast{0.0}; ///< the handle's position at the last synthesis (drag hint)
};

struct FlowPanel {
  bool open = false;
  std::string file;
  VideoClip clip;
  int frameA = 0;
  int frameB = 1;
  int method = 0;
  FlowSuggestOptions options;
  bool mapImage = false;
  FlowField flow;
  std::vector<std::array<Vec2, 2>> suggestions;
  FlowSuggestStats stats;
  int zone = -1;
  gl::Texture thumbA{gl::NoCreate};
  gl::Texture thumbB{gl::NoCreate};
  gl::Texture flowTex{gl::NoCreate};
};

const ToolInfo& info(ToolKind kind);
void arrow(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 colour, float thickness = 1.5f);
/** HSV colouring of layer 0's jump field over `rect` (atlas texels): hue = direction, value = length. */
Image jumpHsvPicture(const Textures& tex, Rect rect);
/** A painted freeze mask as a translucent blue overlay (RGBA8). */
Image maskPicture(const std::vector<float>& mask, glm::ivec2 size);
/** Default project file for a new project over `image`: <stem>.fold.json next to it. */
fs::path defaultProjectFile(const fs::path& image);

/**
 * The editor window: one project Session at a time, its GPU textures and preview, the canvas view and the
 * state of every panel. Each screen's drawing and input lives in its own file (see the header comment).
 */
class FoldEditor {
public:
  explicit FoldEditor(const EditorOptions& o);

  void run();

private:
  // --- model ------------------------------------------------------------------------------------------
  void openProject(const fs::path& file, bool recover);

  void newProject(const std::vector<fs::path>& images, const fs::path& file);

  /** Stops a background synthesis (another project opens, or the editor closes). */
  void cancelBackground();

  void adopt(std::unique_ptr<Session> session);

  /** Runs an edit; an error becomes the status line (the edit changed nothing). */
  template <typename F> bool edit(F&& f) {
    try {
      f();
      return true;
    } catch (const Error& e) {
      setStatus(e.what(), true);
      return false;
    }
  }

  /** Picks up a finished background synthesis; true while one is still running. */
  bool backgroundBusy();

  /**
   * A full synthesis of a large project runs on a worker thread (the status bar shows its progress and the
   * editor stays usable); edits made meanwhile are re-synthesised by region once it is installed. Scripted
   * runs (--frames, --fixed-step) stay synchronous so their frames are reproducible.
   */
  bool startBackground();

  /** Re-synthesises what changed and updates the GPU copy. */
  void refresh(std::optional<Rect> hint = std::nullopt);

  void synthesizeNow();

  void save();

  void undo();
  void redo();
  void deleteSelectedZone();
  /** The window title shows the file and the dirty marker; selecting a zone shows its profile. */
  void updateTitleAndSelection();
  void clampSelection();

  void setStatus(const std::string& text, bool error);

  double mClockNow() const { return mShell.clock().time(); }

  /** A wall-clock duration for display; hidden under --fixed-step, whose screenshots must be reproducible. */
  std::string timing(double ms) const;

  /**
   * Replaces a texture the current frame's ImGui draw lists may still name: the old one is deleted only at
   * the start of the next frame, after those lists were rendered.
   */
  void replaceTexture(gl::Texture& slot, gl::Texture fresh);
  void retireImageTextures();

  /** The window: at most 60 frames/s while interactive; Esc and Tab are the editor's keys. */
  static ui::ShellOptions shellOptions(const EditorOptions& o);

  // --- input ------------------------------------------------------------------------------------------
  void onKey(int key, int mods);

  void selectTool(ToolKind tool);

  void prompt(PathPrompt::Action action, const std::string& title);

  void runPrompt(const std::string& path);

  void requireZone() const;

  // --- exports ----------------------------------------------------------------------------------------
  /** Frames of the canvas image over the longest period at `fps` (CPU reference renderer, all cores). */
  std::vector<Image> frames(double fps);

  void runExport(PathPrompt::Action action, const fs::path& p);

  // --- external image editor and file watching ---------------------------------------------------------
  void editImageExternally();

  void pollFiles();

  void autosaveTick();

  // --- motion from a reference video ---------------------------------------------------------------------
  void loadFlowVideo(const fs::path& p);

  void updateFlowThumbs();

  void computeSuggestions();

  // --- frame --------------------------------------------------------------------------------------------
  void drawMenuBar();
  void drawWorkflowBar(float y, float height);
  void drawToolbox(ImVec2 pos, ImVec2 size);
  void drawCanvas(ImVec2 pos, ImVec2 size);
  void drawPreview(ImVec2 pos, ImVec2 size);
  void drawPanels(ImVec2 pos, ImVec2 size);
  void drawZonePanel();
  void drawJumpTree();
  void drawProfilePanel();
  void drawStatusBar(ImVec2 pos, ImVec2 size);
  void drawPrompt();
  void drawFlowWindow();
  void drawStartScreen(ImVec2 size);
  void drawHelp();
  void canvasInput();
  void drawOverlays(ImDrawList* dl);
  void updateOverlays();
  void finishClicks();
  void addPoints(Vec2 a, Vec2 b);
  void paintFreeze(Vec2 centre, bool erase, bool finish);
  int workflowStep() const;

  EditorOptions mOptions;
  ui::WindowShell mShell;
  shader::Library mLibrary;
  folding::gpu::FoldRenderer mRenderer;
  RecentFiles mRecent;
  FileWatcher mWatcher;

  std::unique_ptr<Session> mSession;
  int mImage = 0;
  int mZone = -1;
  int mProfile = 0;
  int mShownZone = -1; ///< the zone selected last frame (the profile panel follows the selection)
  std::string mTitle;  ///< the window title set last
  ToolKind mTool = ToolKind::Select;
  std::vector<gl::Texture> mImageTextures;
  std::vector<gl::Texture> mRetired; ///< textures replaced this frame, deleted at the start of the next

  ui::ImageCanvas mCanvas;
  bool mSnapEnabled = true;
  SnapOptions mSnap;
  Vec2 mCursor{-1.0};
  bool mCursorInImage = false;
  Gesture mGesture;
  std::vector<Vec2> mClicks;

  // overlays
  bool mShowOutlines = true;
  bool mShowAnchors = true;
  bool mShowVectors = false;
  int mVectorStep = 16;
  bool mShowHsv = false;
  bool mShowHeat0 = false;
  bool mShowHeat1 = false;
  bool mShowFreeze = true;
  bool mOverlaysStale = true;
  gl::Texture mHsvTex{gl::NoCreate};
  gl::Texture mHeat0Tex{gl::NoCreate};
  gl::Texture mHeat1Tex{gl::NoCreate};
  gl::Texture mFreezeTex{gl::NoCreate};
  Rect mOverlayRect; ///< atlas texels the overlay textures cover (the image's atlas rect)

  // freeze brush
  float mBrushRadius = 8.0f;
  std::vector<float> mFreezePaint;
  glm::ivec2 mFreezeSize{0};
  int mFreezeZone = -1;

  // preview
  bool mUploaded = false;
  std::vector<Profile> mUploadedProfiles;
  bool mAutoSynth = true;
  bool mPlaying = true;
  float mSpeed = 1.0f;
  double mTime = 0.0;
  ui::CanvasImage mPreview;
  double mLastSynthMs = 0.0;
  Rect mLastRegion;

  // background full synthesis
  static constexpr std::size_t kBackgroundPixels = 1u << 19; ///< larger projects synthesise in the background
  struct Job {
    Session::Snapshot snapshot;
    std::unique_ptr<Progress> progress;
    std::size_t total = 0;
    std::chrono::steady_clock::time_point start;
    std::future<Textures> result;
  };
  std::unique_ptr<Job> mJob;

  // files
  PathPrompt mPrompt;
  double mLastAutosave = 0.0;
  double mLastPoll = 0.0;
  float mExportFps = 15.0f;
  FlowPanel mFlow;
  bool mShowHelp = false;
  int mPanelTab = 0;
  int mTemplate = 0;

  std::string mStatus = "Open a project (Ctrl+O) or start from an image (Ctrl+N)";
  bool mStatusError = false;
};

} // namespace sylva::folding_ui

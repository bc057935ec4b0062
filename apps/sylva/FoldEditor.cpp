// `sylva fold edit`: the folding-texture editor (thesis FoldingGen, Fig. 28 layout). A menu bar, the workflow
// bar (zones → motion → profiles → synthesise → preview → export), the toolbox and the current tool's
// properties on the left, the canvas in the middle, the live GPU preview with its timeline and the
// zone / jump-path / profile panels on the right, and a status bar. Every change goes through the GL-free
// model (Session, EditHistory, Handles); the window loop and the canvas are engine/ui's (WindowShell,
// ImageCanvas), so this file only maps input to edits and draws.
#include "FoldEditor.hpp"

#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/ui/ImageCanvas.hpp>
#include <sylva/ui/WindowShell.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/folding/Canvas.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/media/Export.hpp>
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
#include <sylva/gl/Texture.hpp>
#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>

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

namespace sylva::app {
namespace {

namespace fs = std::filesystem;
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

const ToolInfo& info(ToolKind kind) {
  return kTools[static_cast<std::size_t>(kind)];
}

constexpr const char* kFunctionNames[] = {"linear", "piecewise", "exponential", "sigmoid", "sine"};
constexpr const char* kLoopNames[] = {"none", "ping-pong", "crossfade"};
constexpr const char* kInterpNames[] = {"Shepard (IDW)", "modified Shepard", "modified Shepard + randomness"};
constexpr const char* kFoldingNames[] = {"none", "polygons", "alpha mask", "object"};

/** Workflow steps of the thesis (§4): the bar highlights the first one not yet done. */
constexpr const char* kSteps[] = {"1 Zones",      "2 Motion",  "3 Profiles",
                                  "4 Synthesise", "5 Preview", "6 Export"};

ImTextureID textureId(const gl::Texture& t) {
  return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(t.id()));
}

constexpr ImU32 kZoneColour = IM_COL32(255, 220, 60, 255);
constexpr ImU32 kZoneSelected = IM_COL32(255, 255, 255, 255);
constexpr ImU32 kFromColour = IM_COL32(80, 200, 255, 255);
constexpr ImU32 kToColour = IM_COL32(255, 140, 40, 255);
constexpr ImU32 kFoldColour = IM_COL32(230, 80, 230, 255);
constexpr ImU32 kStillColour = IM_COL32(120, 255, 120, 255);
constexpr ImU32 kSuggestColour = IM_COL32(255, 90, 90, 255);

void arrow(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 colour, float thickness = 1.5f) {
  dl->AddLine(a, b, colour, thickness);
  const float dx = b.x - a.x;
  const float dy = b.y - a.y;
  const float len = std::sqrt(dx * dx + dy * dy);
  if (len < 3.0f) {
    return;
  }
  const float ux = dx / len;
  const float uy = dy / len;
  const float h = std::min(8.0f, 0.4f * len);
  dl->AddTriangleFilled(b, ImVec2(b.x - h * ux + 0.5f * h * uy, b.y - h * uy - 0.5f * h * ux),
                        ImVec2(b.x - h * ux - 0.5f * h * uy, b.y - h * uy + 0.5f * h * ux), colour);
}

/** An RGBA8 texture for ImGui::Image, nearest filtering when zoomed in. */
gl::Texture imageTexture(const Image& image) {
  gl::Texture t = gl::Texture::fromImage(image.channels() == 4 ? image : image.converted(PixelType::U8));
  t.setSampler({GL_LINEAR, GL_NEAREST, GL_CLAMP_TO_EDGE});
  return t;
}

/** HSV colouring of layer 0's jump field over `rect` (atlas texels): hue = direction, value = length. */
Image jumpHsvPicture(const Textures& tex, Rect rect) {
  Image out(rect.width(), rect.height(), 4, PixelType::U8);
  const std::span<const float> j = tex.jump.at(0).values<float>();
  const double scale = std::max(tex.jumpMax(), 1e-6);
  std::uint8_t* o = reinterpret_cast<std::uint8_t*>(out.data());
  for (int y = 0; y < rect.height(); ++y) {
    for (int x = 0; x < rect.width(); ++x) {
      const std::size_t i = (static_cast<std::size_t>(y + rect.min.y) * tex.width() + x + rect.min.x) * 4;
      // Forward motion (where content goes) is −J.
      const double fx = -j[i];
      const double fy = -j[i + 1];
      const double mag = std::min(1.0, std::hypot(fx, fy) / scale);
      const double hue = (std::atan2(fy, fx) / (2.0 * M_PI) + 0.5) * 6.0;
      const double c = mag;
      const double xx = c * (1.0 - std::abs(std::fmod(hue, 2.0) - 1.0));
      double r = 0, g = 0, b = 0;
      switch (static_cast<int>(hue) % 6) {
      case 0:
        r = c, g = xx;
        break;
      case 1:
        r = xx, g = c;
        break;
      case 2:
        g = c, b = xx;
        break;
      case 3:
        g = xx, b = c;
        break;
      case 4:
        r = xx, b = c;
        break;
      default:
        r = c, b = xx;
        break;
      }
      std::uint8_t* p = o + (static_cast<std::size_t>(y) * rect.width() + x) * 4;
      p[0] = static_cast<std::uint8_t>(std::lround(255.0 * r));
      p[1] = static_cast<std::uint8_t>(std::lround(255.0 * g));
      p[2] = static_cast<std::uint8_t>(std::lround(255.0 * b));
      p[3] = static_cast<std::uint8_t>(mag > 0.0 ? 200 : 0);
    }
  }
  return out;
}

/** A painted freeze mask as a translucent blue overlay (RGBA8). */
Image maskPicture(const std::vector<float>& mask, glm::ivec2 size) {
  Image out(size.x, size.y, 4, PixelType::U8);
  std::uint8_t* o = reinterpret_cast<std::uint8_t*>(out.data());
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const bool frozen = mask[i] >= 0.5f;
    o[i * 4 + 0] = 40;
    o[i * 4 + 1] = 120;
    o[i * 4 + 2] = 255;
    o[i * 4 + 3] = frozen ? 110 : 0;
  }
  return out;
}

/** Default project file for a new project over `image`: <stem>.fold.json next to it. */
fs::path defaultProjectFile(const fs::path& image) {
  return image.parent_path() / (image.stem().string() + ".fold.json");
}

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

class FoldEditor {
public:
  explicit FoldEditor(const FoldEditOptions& o)
      : mOptions(o), mShell(shellOptions(o)), mLibrary(o.shaderDir), mRenderer(mLibrary),
        mRecent(o.recentFile.empty() ? RecentFiles::defaultPath() : fs::path(o.recentFile)) {
    if (o.pausedAt >= 0.0) {
      mPlaying = false;
      mTime = o.pausedAt;
    }
    std::string warning;
    mRecent.load(&warning);
    if (!warning.empty()) {
      setStatus(warning, true);
    }
    if (!o.inputs.empty()) {
      const fs::path first = o.inputs.front();
      const std::string ext = lowerExtension(first);
      if (ext == ".json") {
        if (o.inputs.size() > 1) {
          fail("fold edit: give one project file, or images to start a new project");
        }
        openProject(first, !o.noRecover);
      } else {
        std::vector<fs::path> images(o.inputs.begin(), o.inputs.end());
        newProject(images, o.project.empty() ? defaultProjectFile(first) : fs::path(o.project));
      }
    }
    mCanvas.fitZoom = o.zoom;
    mShell.setKeyHandler([this](int key, int mods) {
      onKey(key, mods);
      return true;
    });
  }

  void run();

private:
  // --- model ------------------------------------------------------------------------------------------
  void openProject(const fs::path& file, bool recover) {
    std::string notice;
    std::unique_ptr<Session> s = Session::open(file, recover, &notice);
    adopt(std::move(s));
    mRecent.add(mSession->file());
    mRecent.save();
    setStatus(notice.empty() ? "opened " + mSession->file().string() : notice, false);
  }

  void newProject(const std::vector<fs::path>& images, const fs::path& file) {
    adopt(Session::fromImages(images, file));
    setStatus(
        fmt::format("new project {} (unsaved): draw a zone with R", mSession->file().filename().string()),
        false);
  }

  /** Stops a background synthesis (another project opens, or the editor closes). */
  void cancelBackground() {
    if (mJob) {
      mJob->progress->cancel();
      mJob->result.wait();
      mJob.reset();
    }
  }

  void adopt(std::unique_ptr<Session> session) {
    cancelBackground();
    mSession = std::move(session);
    mImage = mSession->project().canvasIndex();
    mZone = mSession->project().zones.empty() ? -1 : 0;
    mProfile = 0;
    retireImageTextures();
    for (const Image& image : mSession->images().images) {
      mImageTextures.push_back(imageTexture(image));
    }
    mWatcher.clear();
    for (const fs::path& f : mSession->imageFiles()) {
      mWatcher.watch(f);
    }
    mCanvas.requestFit();
    mUploaded = false;
    mOverlaysStale = true;
    mLastAutosave = mClockNow();
    refresh();
  }

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
  bool backgroundBusy() {
    if (!mJob) {
      return false;
    }
    if (mJob->result.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      return true;
    }
    std::unique_ptr<Job> job = std::move(mJob);
    try {
      Textures textures = job->result.get();
      if (mSession->install(std::move(textures), job->snapshot.project, job->snapshot.images)) {
        mRenderer.upload(*mSession->textures(), mSession->project().profiles, mSession->project().jumpLayers);
        mUploadedProfiles = mSession->project().profiles;
        mUploaded = true;
        mOverlaysStale = true;
        mLastSynthMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - job->start).count();
        mLastRegion = {{0, 0}, {mSession->textures()->width(), mSession->textures()->height()}};
      }
    } catch (const Error& e) {
      setStatus(e.what(), true);
    }
    return false;
  }

  /**
   * A full synthesis of a large project runs on a worker thread (the status bar shows its progress and the
   * editor stays usable); edits made meanwhile are re-synthesised by region once it is installed. Scripted
   * runs (--frames, --fixed-step) stay synchronous so their frames are reproducible.
   */
  bool startBackground() {
    std::size_t pixels = 0;
    for (const Image& image : mSession->images().images) {
      pixels += static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height());
    }
    if (mOptions.frames > 0 || mShell.clock().fixed() || pixels < kBackgroundPixels ||
        !mSession->needsFullSynthesis()) {
      return false;
    }
    auto job = std::make_unique<Job>();
    job->snapshot = mSession->snapshot();
    job->total = std::max<std::size_t>(synthesisRows(job->snapshot.project, job->snapshot.images), 1);
    job->progress = std::make_unique<Progress>("synthesis", job->total);
    job->start = std::chrono::steady_clock::now();
    job->result = std::async(std::launch::async, [s = &job->snapshot, progress = job->progress.get()] {
      return folding::synthesize(s->project, s->images, progress);
    });
    mJob = std::move(job);
    return true;
  }

  /** Re-synthesises what changed and updates the GPU copy. */
  void refresh(std::optional<Rect> hint = std::nullopt) {
    if (!mSession || backgroundBusy()) {
      return;
    }
    try {
      // With live synthesis off, only the first synthesis and Ctrl+Enter run; timing changes still show.
      if ((mAutoSynth || !mUploaded) && mSession->stale() && !startBackground()) {
        const Session::Update u = mSession->synthesize(hint);
        mLastSynthMs = u.ms;
        mLastRegion = u.region;
        if (u.full || !mUploaded) {
          mRenderer.upload(*mSession->textures(), mSession->project().profiles,
                           mSession->project().jumpLayers);
          mUploaded = true;
        } else if (!u.region.empty()) {
          mRenderer.updateRegion(*mSession->textures(), u.region);
        }
        mOverlaysStale = true;
      }
      if (mUploaded && mSession->project().profiles != mUploadedProfiles) {
        mRenderer.setProfiles(mSession->project().profiles);
      }
      mUploadedProfiles = mSession->project().profiles;
    } catch (const Error& e) {
      setStatus(e.what(), true);
    }
  }

  void synthesizeNow() {
    const bool autoSynth = mAutoSynth;
    mAutoSynth = true;
    refresh();
    mAutoSynth = autoSynth;
    if (mSession && mSession->textures()) {
      setStatus(fmt::format("synthesised {}x{} atlas in {}", mSession->textures()->width(),
                            mSession->textures()->height(), timing(mLastSynthMs)),
                false);
    }
  }

  void save() {
    if (!mSession) {
      return;
    }
    if (edit([&] { mSession->save(); })) {
      mRecent.add(mSession->file());
      mRecent.save();
      setStatus("saved " + mSession->file().filename().string(), false);
    }
  }

  void undo() {
    if (mSession && mSession->history().canUndo()) {
      const EditHistory::Change c = mSession->history().undo();
      clampSelection();
      setStatus("undo: " + c.name, false);
    }
  }
  void redo() {
    if (mSession && mSession->history().canRedo()) {
      const EditHistory::Change c = mSession->history().redo();
      clampSelection();
      setStatus("redo: " + c.name, false);
    }
  }
  void deleteSelectedZone() {
    if (mZone < 0) {
      return;
    }
    const std::string id = mSession->project().zones[static_cast<std::size_t>(mZone)].id;
    if (edit([&] { removeZone(mSession->history(), mZone); })) {
      mZone = -1;
      setStatus("deleted zone '" + id + "' (Ctrl+Z brings it back)", false);
    }
  }
  /** The window title shows the file and the dirty marker; selecting a zone shows its profile. */
  void updateTitleAndSelection() {
    std::string title = "Sylva fold editor";
    if (mSession) {
      title += ": " + mSession->file().filename().string() + (mSession->history().dirty() ? " *" : "");
      if (mZone != mShownZone && mZone >= 0 && mZone < static_cast<int>(mSession->project().zones.size())) {
        mProfile = std::max(0, mSession->project().profileIndex(
                                   mSession->project().zones[static_cast<std::size_t>(mZone)].profile));
      }
      mShownZone = mZone;
    }
    if (title != mTitle) {
      glfwSetWindowTitle(mShell.window().handle(), title.c_str());
      mTitle = title;
    }
  }
  void clampSelection() {
    const int zones = static_cast<int>(mSession->project().zones.size());
    if (mZone >= zones) {
      mZone = zones - 1;
    }
    mProfile = std::clamp(mProfile, 0, static_cast<int>(mSession->project().profiles.size()) - 1);
  }

  void setStatus(const std::string& text, bool error) {
    mStatus = text;
    mStatusError = error;
    if (error) {
      log::warn("{}", text);
    } else {
      log::info("{}", text);
    }
  }

  double mClockNow() const { return mShell.clock().time(); }

  /** A wall-clock duration for display; hidden under --fixed-step, whose screenshots must be reproducible. */
  std::string timing(double ms) const {
    return mShell.clock().fixed() ? "- ms" : fmt::format("{:.1f} ms", ms);
  }

  /**
   * Replaces a texture the current frame's ImGui draw lists may still name: the old one is deleted only at
   * the start of the next frame, after those lists were rendered.
   */
  void replaceTexture(gl::Texture& slot, gl::Texture fresh) {
    mRetired.push_back(std::move(slot));
    slot = std::move(fresh);
  }
  void retireImageTextures() {
    for (gl::Texture& t : mImageTextures) {
      mRetired.push_back(std::move(t));
    }
    mImageTextures.clear();
  }

  /** The window: at most 60 frames/s while interactive; Esc and Tab are the editor's keys. */
  static ui::ShellOptions shellOptions(const FoldEditOptions& o) {
    ui::ShellOptions s;
    s.width = o.width;
    s.height = o.height;
    s.title = "Sylva fold editor";
    s.frames = o.frames;
    s.screenshot = o.screenshot;
    s.fixedStep = o.fixedStep;
    s.maxFps = 60.0;
    s.tabTogglesPanel = false;
    s.escapeQuits = false;
    s.keysBesideWidgets = true;
    return s;
  }

  // --- input ------------------------------------------------------------------------------------------
  void onKey(int key, int mods) {
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    const bool shift = (mods & GLFW_MOD_SHIFT) != 0;
    if (ctrl) {
      switch (key) {
      case GLFW_KEY_S:
        shift ? prompt(PathPrompt::Action::SaveAs, "Save project as") : save();
        return;
      case GLFW_KEY_O:
        prompt(PathPrompt::Action::Open, "Open project");
        return;
      case GLFW_KEY_N:
        prompt(PathPrompt::Action::NewFromImage, "New project from image(s)");
        return;
      case GLFW_KEY_Z:
        shift ? redo() : undo();
        return;
      case GLFW_KEY_Y:
        redo();
        return;
      case GLFW_KEY_E:
        editImageExternally();
        return;
      case GLFW_KEY_ENTER:
        synthesizeNow();
        return;
      case GLFW_KEY_Q:
        glfwSetWindowShouldClose(mShell.window().handle(), GLFW_TRUE);
        return;
      default:
        return;
      }
    }
    if (!mSession) {
      return;
    }
    for (std::size_t i = 0; i < kTools.size(); ++i) {
      if (kTools[i].glfwKey == key) {
        selectTool(static_cast<ToolKind>(i));
        return;
      }
    }
    switch (key) {
    case GLFW_KEY_SPACE:
      mPlaying = !mPlaying;
      break;
    case GLFW_KEY_ENTER:
    case GLFW_KEY_KP_ENTER:
      finishClicks();
      break;
    case GLFW_KEY_ESCAPE:
      mClicks.clear();
      mGesture = {};
      break;
    case GLFW_KEY_HOME:
      mCanvas.requestFit();
      break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
      mCanvas.zoomAtCentre(2.0);
      break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
      mCanvas.zoomAtCentre(0.5);
      break;
    case GLFW_KEY_1:
      mCanvas.actualSize();
      break;
    case GLFW_KEY_DELETE:
      deleteSelectedZone();
      break;
    case GLFW_KEY_G:
      mSnap.pixelCentres = !mSnap.pixelCentres;
      break;
    default:
      break;
    }
  }

  void selectTool(ToolKind tool) {
    mTool = tool;
    mClicks.clear();
    mGesture = {};
    if (tool == ToolKind::Mask) {
      prompt(PathPrompt::Action::MaskImport, "Alpha mask image for the selected zone's folding");
    }
  }

  void prompt(PathPrompt::Action action, const std::string& title) {
    mPrompt.action = action;
    mPrompt.title = title;
    std::string initial;
    if (mSession) {
      const fs::path dir = mSession->file().parent_path();
      switch (action) {
      case PathPrompt::Action::SaveAs:
        initial = mSession->file().string();
        break;
      case PathPrompt::Action::ExportZones:
        initial = (dir / "zones.json").string();
        break;
      case PathPrompt::Action::ExportProfiles:
        initial = (dir / "profiles.json").string();
        break;
      case PathPrompt::Action::ExportTextures:
        initial = (dir / (mSession->file().stem().string() + "-textures")).string();
        break;
      case PathPrompt::Action::ExportGif:
        initial = (dir / (mSession->file().stem().string() + ".gif")).string();
        break;
      case PathPrompt::Action::ExportVideo:
        initial = (dir / (mSession->file().stem().string() + ".mp4")).string();
        break;
      case PathPrompt::Action::ExportSprites:
        initial = (dir / (mSession->file().stem().string() + "-sprites.png")).string();
        break;
      case PathPrompt::Action::ExportShader:
        initial = (dir / (mSession->file().stem().string() + "-shader")).string();
        break;
      case PathPrompt::Action::ExportWeb:
        initial = (dir / (mSession->file().stem().string() + ".html")).string();
        break;
      default:
        initial = dir.string() + "/";
        break;
      }
    } else {
      initial = fs::current_path().string() + "/";
    }
    std::snprintf(mPrompt.path, sizeof(mPrompt.path), "%s", initial.c_str());
    mPrompt.open = true;
  }

  void runPrompt(const std::string& path) {
    const fs::path p(path);
    try {
      switch (mPrompt.action) {
      case PathPrompt::Action::Open:
        openProject(p, true);
        break;
      case PathPrompt::Action::NewFromImage: {
        std::vector<fs::path> images;
        std::size_t start = 0;
        while (start < path.size()) {
          const std::size_t end = path.find(';', start);
          const std::string part = path.substr(start, end == std::string::npos ? end : end - start);
          if (!part.empty()) {
            images.emplace_back(part);
          }
          start = end == std::string::npos ? path.size() : end + 1;
        }
        if (images.empty()) {
          fail("new project: give one or more image files (separated by ';')");
        }
        newProject(images, defaultProjectFile(images.front()));
        break;
      }
      case PathPrompt::Action::SaveAs:
        mSession->saveAs(p);
        mRecent.add(mSession->file());
        mRecent.save();
        setStatus("saved as " + mSession->file().string(), false);
        break;
      case PathPrompt::Action::ImportZones:
        importZones(mSession->history(), loadJsonFile(p), p.string());
        setStatus("imported zones from " + p.string(), false);
        break;
      case PathPrompt::Action::ExportZones: {
        std::vector<int> all(mSession->project().zones.size());
        for (std::size_t i = 0; i < all.size(); ++i) {
          all[i] = static_cast<int>(i);
        }
        saveJsonFile(p, exportZones(mSession->project(), mZone >= 0 ? std::vector<int>{mZone} : all));
        setStatus("exported " + std::string(mZone >= 0 ? "the selected zone" : "all zones") + " to " +
                      p.string(),
                  false);
        break;
      }
      case PathPrompt::Action::ImportProfiles:
        importProfiles(mSession->history(), loadJsonFile(p), p.string());
        setStatus("imported profiles from " + p.string(), false);
        break;
      case PathPrompt::Action::ExportProfiles:
        saveJsonFile(p, exportProfiles(mSession->project()));
        setStatus("exported profiles to " + p.string(), false);
        break;
      case PathPrompt::Action::MaskImport: {
        requireZone();
        Zone z = mSession->project().zones[static_cast<std::size_t>(mZone)];
        z.folding.type = Folding::Type::Mask;
        const fs::path full = fs::absolute(p);
        const fs::path rel = full.lexically_relative(mSession->file().parent_path());
        z.folding.mask = rel.empty() ? full : rel;
        z.folding.polygons.clear();
        replaceZone(mSession->history(), mZone, z, "import alpha mask");
        setStatus("fold region of '" + z.id + "' from " + p.string(), false);
        break;
      }
      case PathPrompt::Action::Video:
        loadFlowVideo(p);
        break;
      default:
        runExport(mPrompt.action, p);
        break;
      }
    } catch (const Error& e) {
      setStatus(e.what(), true);
    }
  }

  void requireZone() const {
    if (mZone < 0) {
      fail("select a zone first (or draw one with R)");
    }
  }

  // --- exports ----------------------------------------------------------------------------------------
  /** Frames of the canvas image over the longest period at `fps` (CPU reference renderer, all cores). */
  std::vector<Image> frames(double fps) {
    synthesizeNow();
    const Textures& tex = *mSession->textures();
    const double period = longestPeriod(mSession->project().profiles);
    const int count = std::clamp(static_cast<int>(std::lround(period * fps)), 1, 600);
    std::vector<Image> out;
    const AtlasEntry& entry = tex.atlas.entries[static_cast<std::size_t>(mImage)];
    for (int i = 0; i < count; ++i) {
      out.push_back(cropToEntry(renderFrame(tex, mSession->project().profiles, mSession->project().jumpLayers,
                                            i / fps, std::max(1u, std::thread::hardware_concurrency())),
                                entry));
    }
    return out;
  }

  void runExport(PathPrompt::Action action, const fs::path& p) {
    if (!mSession) {
      return;
    }
    synthesizeNow();
    const Textures& tex = *mSession->textures();
    switch (action) {
    case PathPrompt::Action::ExportTextures:
      saveTextures(p, mSession->project(), tex);
      break;
    case PathPrompt::Action::ExportGif:
      writeGif(p, frames(mExportFps), static_cast<int>(std::lround(100.0 / mExportFps)));
      break;
    case PathPrompt::Action::ExportVideo:
      writeVideo(p, frames(mExportFps), mExportFps);
      break;
    case PathPrompt::Action::ExportSprites: {
      fs::path json = p;
      json.replace_extension(".json");
      writeSpriteSheet(p, json, frames(mExportFps), 8, mExportFps);
      break;
    }
    case PathPrompt::Action::ExportShader:
      saveTextures(p, mSession->project(), tex);
      folding::gpu::exportShader(p, mLibrary, mSession->project(),
                                 folding::gpu::encodedInfo(mSession->project(), tex));
      break;
    case PathPrompt::Action::ExportWeb:
      folding::gpu::writeWebPreview(p, mLibrary, mSession->project(), tex);
      break;
    default:
      return;
    }
    setStatus("exported " + p.string(), false);
  }

  // --- external image editor and file watching ---------------------------------------------------------
  void editImageExternally() {
    if (!mSession) {
      return;
    }
    const fs::path file = mSession->imageFiles().at(static_cast<std::size_t>(mImage));
    std::string why;
    const std::optional<std::vector<std::string>> command = imageEditorCommand(file, &why);
    if (!command) {
      setStatus(why, true);
      return;
    }
    std::string error;
    if (launchDetached(*command, &error) <= 0) {
      setStatus(error, true);
      return;
    }
    setStatus(fmt::format("opened {} in {}; saving it there reloads it here", file.filename().string(),
                          command->front()),
              false);
  }

  void pollFiles() {
    reapChildren();
    if (!mSession || mShell.clock().time() - mLastPoll < 0.5) {
      return;
    }
    mLastPoll = mShell.clock().time();
    const std::vector<fs::path> changed = mWatcher.poll();
    if (changed.empty()) {
      return;
    }
    try {
      mSession->reloadImages();
      retireImageTextures();
      for (const Image& image : mSession->images().images) {
        mImageTextures.push_back(imageTexture(image));
      }
      mUploaded = false;
      refresh();
      setStatus(
          fmt::format("reloaded {} (changed on disk); zones and anchors kept", changed.front().string()),
          false);
    } catch (const Error& e) {
      setStatus(e.what(), true);
    }
  }

  void autosaveTick() {
    if (!mSession || mOptions.autosaveSeconds <= 0.0 || !mSession->history().dirty()) {
      mLastAutosave = mShell.clock().time();
      return;
    }
    if (mShell.clock().time() - mLastAutosave >= mOptions.autosaveSeconds) {
      mLastAutosave = mShell.clock().time();
      try {
        mSession->autosaveNow();
      } catch (const Error& e) {
        setStatus(e.what(), true);
      }
    }
  }

  // --- motion from a reference video ---------------------------------------------------------------------
  void loadFlowVideo(const fs::path& p) {
    FlowPanel& f = mFlow;
    f.clip = loadVideo(p, 600);
    f.file = p.string();
    f.frameA = 0;
    f.frameB = std::min<int>(1, static_cast<int>(f.clip.frames.size()) - 1);
    f.suggestions.clear();
    f.flow = {};
    f.open = true;
    updateFlowThumbs();
    setStatus(fmt::format("{}: {} frames {}×{}", p.filename().string(), f.clip.frames.size(), f.clip.size.x,
                          f.clip.size.y),
              false);
  }

  void updateFlowThumbs() {
    if (mFlow.clip.frames.empty()) {
      return;
    }
    replaceTexture(mFlow.thumbA, imageTexture(mFlow.clip.frames[static_cast<std::size_t>(mFlow.frameA)]));
    replaceTexture(mFlow.thumbB, imageTexture(mFlow.clip.frames[static_cast<std::size_t>(mFlow.frameB)]));
  }

  void computeSuggestions() {
    FlowPanel& f = mFlow;
    requireZone();
    const Image& a = f.clip.frames.at(static_cast<std::size_t>(f.frameA));
    const Image& b = f.clip.frames.at(static_cast<std::size_t>(f.frameB));
    const FlowMethod method = f.method == 0 ? FlowMethod::Dis : FlowMethod::Farneback;
    f.flow = computeFlow(a, b, method);
    const FlowField backward = computeFlow(b, a, method);
    f.options.mapping = f.mapImage ? FlowSuggestOptions::Mapping::Image : FlowSuggestOptions::Mapping::Zone;
    const Zone& zone = mSession->project().zones[static_cast<std::size_t>(mZone)];
    const int image = mSession->project().imageIndex(zone.image);
    f.suggestions =
        suggestAnchors(f.flow, zone.shape, mSession->imageSize(image), f.options, &backward, &f.stats);
    f.zone = mZone;
    replaceTexture(f.flowTex, imageTexture(flowPicture(f.flow)));
    setStatus(fmt::format("{} anchors suggested (mean flow {:.2f} px); Accept adds them to '{}'",
                          f.suggestions.size(), f.flow.meanMagnitude(), zone.id),
              false);
  }

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

  FoldEditOptions mOptions;
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

// ---------------------------------------------------------------------------------------------------------

int FoldEditor::workflowStep() const {
  if (!mSession || mSession->project().zones.empty()) {
    return 0;
  }
  bool motion = false;
  for (const Zone& z : mSession->project().zones) {
    motion |= !z.tools.empty();
  }
  if (!motion) {
    return 1;
  }
  if (mSession->stale() || !mSession->textures()) {
    return 3;
  }
  return mSession->history().dirty() ? 5 : 4;
}

void FoldEditor::drawMenuBar() {
  if (!ImGui::BeginMainMenuBar()) {
    return;
  }
  const bool has = mSession != nullptr;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New from image...", "Ctrl+N")) {
      prompt(PathPrompt::Action::NewFromImage, "New project from image(s) (separate several with ';')");
    }
    if (ImGui::MenuItem("Open...", "Ctrl+O")) {
      prompt(PathPrompt::Action::Open, "Open project");
    }
    if (ImGui::BeginMenu("Open recent", !mRecent.entries().empty())) {
      for (const fs::path& f : mRecent.entries()) {
        if (ImGui::MenuItem(f.string().c_str())) {
          edit([&] { openProject(f, true); });
        }
      }
      ImGui::Separator();
      if (ImGui::MenuItem("Clear list")) {
        mRecent.clear();
        mRecent.save();
      }
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Save", "Ctrl+S", false, has)) {
      save();
    }
    if (ImGui::MenuItem("Save as...", "Ctrl+Shift+S", false, has)) {
      prompt(PathPrompt::Action::SaveAs, "Save project as");
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Import motion zones...", nullptr, false, has)) {
      prompt(PathPrompt::Action::ImportZones, "Import motion zones (sylva-fold-zones)");
    }
    if (ImGui::MenuItem("Export motion zones...", nullptr, false,
                        has && !mSession->project().zones.empty())) {
      prompt(PathPrompt::Action::ExportZones, "Export motion zones (the selected one, or all)");
    }
    if (ImGui::MenuItem("Import motion profiles...", nullptr, false, has)) {
      prompt(PathPrompt::Action::ImportProfiles, "Import motion profiles (sylva-fold-profiles)");
    }
    if (ImGui::MenuItem("Export motion profiles...", nullptr, false, has)) {
      prompt(PathPrompt::Action::ExportProfiles, "Export motion profiles");
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Edit image in external editor", "Ctrl+E", false, has)) {
      editImageExternally();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) {
      glfwSetWindowShouldClose(mShell.window().handle(), GLFW_TRUE);
    }
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit", has)) {
    const EditHistory& h = mSession->history();
    const std::vector<std::string> names = h.undoNames();
    const std::string undoLabel = names.empty() ? "Undo" : "Undo " + names.back();
    if (ImGui::MenuItem(undoLabel.c_str(), "Ctrl+Z", false, h.canUndo())) {
      undo();
    }
    if (ImGui::MenuItem("Redo", "Ctrl+Y", false, h.canRedo())) {
      redo();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Delete selected zone", "Del", false, mZone >= 0)) {
      deleteSelectedZone();
    }
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View", has)) {
    ImGui::MenuItem("Zone outlines", nullptr, &mShowOutlines);
    ImGui::MenuItem("Anchors and curves", nullptr, &mShowAnchors);
    ImGui::MenuItem("Vector field (arrows)", nullptr, &mShowVectors);
    ImGui::MenuItem("Vector field (HSV colours)", nullptr, &mShowHsv);
    ImGui::MenuItem("t0 heat map", nullptr, &mShowHeat0);
    ImGui::MenuItem("t1 heat map", nullptr, &mShowHeat1);
    ImGui::MenuItem("Freeze mask", nullptr, &mShowFreeze);
    ImGui::MenuItem("Pixel grid (high zoom)", nullptr, &mCanvas.showGrid);
    ImGui::Separator();
    ImGui::MenuItem("Snapping", nullptr, &mSnapEnabled);
    ImGui::MenuItem("Snap to pixel centres", "G", &mSnap.pixelCentres);
    ImGui::Separator();
    if (ImGui::MenuItem("Fit image", "Home")) {
      mCanvas.requestFit();
    }
    if (ImGui::MenuItem("Zoom in", "+")) {
      mCanvas.zoomAtCentre(2.0);
    }
    if (ImGui::MenuItem("Zoom out", "-")) {
      mCanvas.zoomAtCentre(0.5);
    }
    if (ImGui::MenuItem("Actual pixels", "1")) {
      mCanvas.actualSize();
    }
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Motion", has)) {
    if (ImGui::BeginMenu("Template for the selected zone", mZone >= 0)) {
      for (MotionTemplate t : motionTemplates()) {
        if (ImGui::MenuItem(motionTemplateName(t))) {
          edit([&] { applyMotionTemplate(mSession->history(), mZone, t); });
        }
      }
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Motion from a reference video...")) {
      mFlow.open = true;
      if (mFlow.clip.frames.empty()) {
        prompt(PathPrompt::Action::Video, "Reference video (a file OpenCV reads, or frames/%04d.png)");
      }
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Synthesise now", "Ctrl+Enter")) {
      synthesizeNow();
    }
    ImGui::MenuItem("Synthesise while editing", nullptr, &mAutoSynth);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Export", has)) {
    ImGui::SetNextItemWidth(120);
    ImGui::SliderFloat("frames/s", &mExportFps, 5.0f, 60.0f, "%.0f");
    if (ImGui::MenuItem("Data textures (PNG16 / EXR)...")) {
      prompt(PathPrompt::Action::ExportTextures, "Write the folding textures into directory");
    }
    if (ImGui::MenuItem("GIF...")) {
      prompt(PathPrompt::Action::ExportGif, "Animated GIF of one loop");
    }
    if (ImGui::MenuItem("MP4 video...", nullptr, false, ffmpegAvailable())) {
      prompt(PathPrompt::Action::ExportVideo, "Video of one loop (ffmpeg)");
    }
    if (!ffmpegAvailable() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
      ImGui::SetTooltip("needs ffmpeg on PATH (apt install ffmpeg)");
    }
    if (ImGui::MenuItem("Sprite sheet...")) {
      prompt(PathPrompt::Action::ExportSprites, "Sprite sheet PNG (+ JSON)");
    }
    if (ImGui::MenuItem("Shader snippet and textures...")) {
      prompt(PathPrompt::Action::ExportShader, "Write folding.glsl, README and textures into directory");
    }
    if (ImGui::MenuItem("Web preview (HTML)...")) {
      prompt(PathPrompt::Action::ExportWeb, "Self-contained WebGL 2 page");
    }
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    if (ImGui::MenuItem("Shortcuts and workflow", "F1")) {
      mShowHelp = true;
    }
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void FoldEditor::drawWorkflowBar(float y, float height) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, y));
  ImGui::SetNextWindowSize(ImVec2(vp->Size.x, height));
  ImGui::Begin("##workflow", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  const int step = workflowStep();
  for (int i = 0; i < 6; ++i) {
    if (i > 0) {
      ImGui::SameLine();
      ImGui::TextUnformatted(">");
      ImGui::SameLine();
    }
    const bool current = i == step;
    if (current) {
      ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.85f, 0.55f, 0.1f, 1.0f));
    }
    if (ImGui::Button(kSteps[i]) && mSession) {
      switch (i) {
      case 0:
        selectTool(ToolKind::Rectangle);
        break;
      case 1:
        selectTool(ToolKind::Points);
        break;
      case 2:
        mPanelTab = 2;
        break;
      case 3:
        synthesizeNow();
        break;
      case 4:
        mPlaying = true;
        break;
      default:
        prompt(PathPrompt::Action::ExportGif, "Animated GIF of one loop");
        break;
      }
    }
    if (current) {
      ImGui::PopStyleColor();
    }
  }
  if (mSession) {
    ImGui::SameLine(0, 30);
    ImGui::TextDisabled("%s%s", mSession->file().filename().string().c_str(),
                        mSession->history().dirty() ? " *" : "");
  }
  ImGui::End();
}

void FoldEditor::drawToolbox(ImVec2 pos, ImVec2 size) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::Begin("Tools", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  for (std::size_t i = 0; i < kTools.size(); ++i) {
    const auto kind = static_cast<ToolKind>(i);
    const bool current = mTool == kind;
    if (current) {
      ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.2f, 0.45f, 0.8f, 1.0f));
    }
    const std::string label = fmt::format("{}  ({})", kTools[i].name, kTools[i].key);
    if (ImGui::Button(label.c_str(), ImVec2(-1, 0))) {
      selectTool(kind);
    }
    if (current) {
      ImGui::PopStyleColor();
    }
  }
  ImGui::Separator();
  ImGui::TextUnformatted("Properties");
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("%s", info(mTool).help);
  ImGui::PopTextWrapPos();
  if (mTool == ToolKind::Freeze) {
    ImGui::SliderFloat("radius (px)", &mBrushRadius, 1.0f, 64.0f, "%.0f");
  }
  if (mTool == ToolKind::Polygon || mTool == ToolKind::Lasso || mTool == ToolKind::Fold ||
      mTool == ToolKind::Zero || mTool == ToolKind::Curve) {
    ImGui::Text("%zu point(s) clicked", mClicks.size());
    if (!mClicks.empty() && ImGui::Button("Finish (Enter)")) {
      finishClicks();
    }
    ImGui::SameLine();
    if (!mClicks.empty() && ImGui::Button("Cancel (Esc)")) {
      mClicks.clear();
    }
  }
  ImGui::Checkbox("snap", &mSnapEnabled);
  ImGui::SameLine();
  ImGui::Checkbox("pixel centres (G)", &mSnap.pixelCentres);
  ImGui::Separator();
  ImGui::TextUnformatted("Overlays");
  ImGui::Checkbox("outlines", &mShowOutlines);
  ImGui::SameLine();
  ImGui::Checkbox("anchors", &mShowAnchors);
  ImGui::Checkbox("arrows", &mShowVectors);
  ImGui::SameLine();
  ImGui::Checkbox("HSV", &mShowHsv);
  if (mShowVectors) {
    ImGui::SliderInt("every (px)", &mVectorStep, 2, 64);
  }
  ImGui::Checkbox("t0", &mShowHeat0);
  ImGui::SameLine();
  ImGui::Checkbox("t1", &mShowHeat1);
  ImGui::SameLine();
  ImGui::Checkbox("freeze", &mShowFreeze);
  ImGui::End();
}

void FoldEditor::updateOverlays() {
  if (!mOverlaysStale || !mSession || !mSession->textures()) {
    return;
  }
  mOverlaysStale = false;
  const Textures& tex = *mSession->textures();
  const AtlasEntry& entry = tex.atlas.entries.at(static_cast<std::size_t>(mImage));
  mOverlayRect = entry.atlasRect();
  if (mShowHsv) {
    replaceTexture(mHsvTex, imageTexture(jumpHsvPicture(tex, mOverlayRect)));
  }
  auto crop = [&](const Image& atlasSized) {
    Image out(mOverlayRect.width(), mOverlayRect.height(), 4, PixelType::U8);
    for (int y = 0; y < out.height(); ++y) {
      std::memcpy(out.data() + static_cast<std::size_t>(y) * out.rowBytes(),
                  atlasSized.data() +
                      static_cast<std::size_t>(y + mOverlayRect.min.y) * atlasSized.rowBytes() +
                      static_cast<std::size_t>(mOverlayRect.min.x) * 4,
                  out.rowBytes());
    }
    return out;
  };
  if (mShowHeat0) {
    replaceTexture(mHeat0Tex, imageTexture(crop(thresholdHeatMap(tex, 0))));
  }
  if (mShowHeat1) {
    replaceTexture(mHeat1Tex, imageTexture(crop(thresholdHeatMap(tex, 1))));
  }
}

void FoldEditor::drawOverlays(ImDrawList* dl) {
  const Project& p = mSession->project();
  const std::string& imageId = p.images[static_cast<std::size_t>(mImage)].id;
  auto screen = [&](Vec2 v) { return mCanvas.toScreen(v); };
  const glm::ivec2 size = mSession->imageSize(mImage);
  // Texture overlays over the image's crop (atlas rect) in image pixels.
  if (mSession->textures() && !mSession->stale()) {
    const AtlasEntry& entry = mSession->textures()->atlas.entries[static_cast<std::size_t>(mImage)];
    const ImVec2 a = screen(Vec2(entry.crop.min));
    const ImVec2 b = screen(Vec2(entry.crop.max));
    if (mShowHsv && mHsvTex.id() != 0) {
      dl->AddImage(textureId(mHsvTex), a, b);
    }
    if (mShowHeat0 && mHeat0Tex.id() != 0) {
      dl->AddImage(textureId(mHeat0Tex), a, b, ImVec2(0, 0), ImVec2(1, 1), IM_COL32(255, 255, 255, 200));
    }
    if (mShowHeat1 && mHeat1Tex.id() != 0) {
      dl->AddImage(textureId(mHeat1Tex), a, b, ImVec2(0, 0), ImVec2(1, 1), IM_COL32(255, 255, 255, 200));
    }
    if (mShowVectors) {
      const Textures& tex = *mSession->textures();
      const std::span<const float> j = tex.jump.at(0).values<float>();
      const std::span<const float> init = tex.init.values<float>();
      const int step = std::max(2, mVectorStep);
      for (int y = entry.crop.min.y + step / 2; y < entry.crop.max.y; y += step) {
        for (int x = entry.crop.min.x + step / 2; x < entry.crop.max.x; x += step) {
          const glm::ivec2 t = entry.origin() + glm::ivec2(x, y);
          const std::size_t i = (static_cast<std::size_t>(t.y) * tex.width() + t.x) * 4;
          if (init[i + 3] < 0.0f || (j[i] == 0.0f && j[i + 1] == 0.0f)) {
            continue;
          }
          const Vec2 c(x + 0.5, y + 0.5);
          // Content at c + J arrives at c at full progress: draw that forward motion.
          arrow(dl, screen(c + Vec2(j[i], j[i + 1])), screen(c), IM_COL32(255, 255, 255, 200), 1.0f);
        }
      }
    }
  }
  if (mShowFreeze && mFreezeTex.id() != 0) {
    dl->AddImage(textureId(mFreezeTex), screen(Vec2(0.0)), screen(Vec2(size)));
  }
  // Pixel grid at high zoom.
  mCanvas.drawPixelGrid(dl);
  for (std::size_t z = 0; z < p.zones.size(); ++z) {
    const Zone& zone = p.zones[z];
    if (zone.image != imageId) {
      continue;
    }
    const bool selected = static_cast<int>(z) == mZone;
    if (mShowOutlines) {
      std::vector<ImVec2> pts;
      for (const Vec2& v : zone.shape.outline()) {
        pts.push_back(screen(v));
      }
      dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), selected ? kZoneSelected : kZoneColour,
                      ImDrawFlags_Closed, selected ? 2.5f : 1.5f);
      dl->AddText(ImVec2(pts[0].x + 3, pts[0].y + 2), selected ? kZoneSelected : kZoneColour,
                  zone.id.c_str());
      for (const std::vector<Vec2>& poly : zone.folding.polygons) {
        std::vector<ImVec2> f;
        for (const Vec2& v : poly) {
          f.push_back(screen(v));
        }
        dl->AddPolyline(f.data(), static_cast<int>(f.size()), kFoldColour, ImDrawFlags_Closed, 1.5f);
      }
    }
    if (!mShowAnchors) {
      continue;
    }
    for (const Tool& tool : zone.tools) {
      if (const auto* points = std::get_if<PointsTool>(&tool)) {
        for (const auto& pair : points->pairs) {
          arrow(dl, screen(pair[0]), screen(pair[1]), kToColour, 2.0f);
        }
      } else if (const auto* curve = std::get_if<CurveTool>(&tool)) {
        auto bezier = [&](const std::array<Vec2, 4>& c, ImU32 colour) {
          dl->AddBezierCubic(screen(c[0]), screen(c[1]), screen(c[2]), screen(c[3]), colour, 2.0f);
          dl->AddLine(screen(c[0]), screen(c[1]), IM_COL32(200, 200, 200, 120));
          dl->AddLine(screen(c[3]), screen(c[2]), IM_COL32(200, 200, 200, 120));
        };
        bezier(curve->source, kFromColour);
        if (curve->dest) {
          bezier(*curve->dest, kToColour);
        }
      } else if (const auto* lasso = std::get_if<LassoTool>(&tool)) {
        std::vector<ImVec2> from;
        std::vector<ImVec2> to;
        for (std::size_t i = 0; i < lasso->from.size(); ++i) {
          from.push_back(screen(lasso->from[i]));
          to.push_back(screen(lasso->to[i]));
          if (lasso->from[i] != lasso->to[i]) {
            arrow(dl, from.back(), to.back(), kToColour, 1.0f);
          }
        }
        dl->AddPolyline(from.data(), static_cast<int>(from.size()), kFromColour, ImDrawFlags_Closed, 1.0f);
        dl->AddPolyline(to.data(), static_cast<int>(to.size()), kToColour, ImDrawFlags_Closed, 1.5f);
      } else if (const auto* zero = std::get_if<ZeroTool>(&tool)) {
        std::vector<ImVec2> pts;
        for (const Vec2& v : zero->pts) {
          pts.push_back(screen(v));
        }
        dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), kStillColour, 0, 2.0f);
      } else if (const auto* translate = std::get_if<TranslateTool>(&tool)) {
        const std::vector<Vec2> outline = zone.shape.outline();
        Vec2 c(0.0);
        for (const Vec2& v : outline) {
          c += v / static_cast<double>(outline.size());
        }
        arrow(dl, screen(c), screen(c + translate->v), kToColour, 3.0f);
      } else if (const auto* scale = std::get_if<ScaleTool>(&tool)) {
        const ImVec2 c = screen(scale->centre);
        dl->AddCircle(c, 10.0f, kToColour, 0, 2.0f);
        dl->AddCircle(c, static_cast<float>(10.0 * scale->factor), kToColour, 0, 1.0f);
      }
    }
    for (const Handle& h : zoneHandles(p, static_cast<int>(z))) {
      const ImU32 colour = h.kind == Handle::Kind::ZoneVertex   ? kZoneColour
                           : h.kind == Handle::Kind::FoldVertex ? kFoldColour
                           : h.kind == Handle::Kind::ZeroPoint  ? kStillColour
                           : (h.kind == Handle::Kind::PointFrom || h.kind == Handle::Kind::CurveSource ||
                              h.kind == Handle::Kind::LassoFrom)
                               ? kFromColour
                               : kToColour;
      dl->AddCircleFilled(screen(h.pos), selected ? 4.5f : 3.0f, colour);
    }
  }
  // Suggested anchors from a video, until accepted or rejected.
  if (mFlow.open && mFlow.zone >= 0 && mFlow.zone < static_cast<int>(p.zones.size()) &&
      p.zones[static_cast<std::size_t>(mFlow.zone)].image == imageId) {
    for (const auto& pair : mFlow.suggestions) {
      arrow(dl, screen(pair[0]), screen(pair[1]), kSuggestColour, 1.5f);
    }
  }
  // The gesture in progress.
  if (mGesture.active) {
    const ImVec2 a = screen(mGesture.start);
    const ImVec2 b = screen(mGesture.current);
    switch (mGesture.tool) {
    case ToolKind::Rectangle:
      dl->AddRect(ImVec2(std::min(a.x, b.x), std::min(a.y, b.y)),
                  ImVec2(std::max(a.x, b.x), std::max(a.y, b.y)), kZoneSelected, 0.0f, 0, 2.0f);
      break;
    case ToolKind::Translate:
    case ToolKind::Points:
    case ToolKind::Scale:
      arrow(dl, a, b, kToColour, 2.0f);
      break;
    default:
      break;
    }
  }
  if (!mClicks.empty()) {
    std::vector<ImVec2> pts;
    for (const Vec2& v : mClicks) {
      pts.push_back(screen(v));
      dl->AddCircleFilled(pts.back(), 3.5f, kZoneSelected);
    }
    if (mCursorInImage) {
      pts.push_back(screen(mCursor));
    }
    dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), kZoneSelected, 0, 1.5f);
  }
  if (mTool == ToolKind::Freeze && mCursorInImage) {
    dl->AddCircle(screen(mCursor), static_cast<float>(mBrushRadius * mCanvas.view.zoom),
                  IM_COL32(40, 120, 255, 255));
  }
}

void FoldEditor::addPoints(Vec2 a, Vec2 b) {
  const Zone& zone = mSession->project().zones[static_cast<std::size_t>(mZone)];
  for (std::size_t t = 0; t < zone.tools.size(); ++t) {
    if (std::holds_alternative<PointsTool>(zone.tools[t])) {
      Zone z = zone;
      std::get<PointsTool>(z.tools[t]).pairs.push_back({a, b});
      replaceZone(mSession->history(), mZone, z, "add anchor");
      return;
    }
  }
  addTool(mSession->history(), mZone, PointsTool{{{a, b}}});
}

void FoldEditor::finishClicks() {
  if (!mSession || mClicks.empty()) {
    return;
  }
  const std::vector<Vec2> clicks = mClicks;
  mClicks.clear();
  edit([&] {
    switch (mTool) {
    case ToolKind::Polygon: {
      if (clicks.size() < 3) {
        fail("a polygon zone needs at least 3 points");
      }
      Zone z;
      z.id = "zone";
      z.image = mSession->project().images[static_cast<std::size_t>(mImage)].id;
      z.profile = mSession->project().profiles[static_cast<std::size_t>(mProfile)].id;
      z.shape.type = Shape::Type::Polygon;
      z.shape.pts = clicks;
      z.zeroBoundary = true;
      mZone = addZone(mSession->history(), z);
      setStatus("zone added: now give it motion (A: point mapping, T: translate, templates in Motion)",
                false);
      break;
    }
    case ToolKind::Lasso: {
      requireZone();
      if (clicks.size() < 3) {
        fail("a lasso needs at least 3 points");
      }
      addTool(mSession->history(), mZone, LassoTool{clicks, clicks, true});
      mTool = ToolKind::Select;
      setStatus("lasso added: drag its orange points to deform", false);
      break;
    }
    case ToolKind::Fold: {
      requireZone();
      if (clicks.size() < 3) {
        fail("a folding zone needs at least 3 points");
      }
      Zone z = mSession->project().zones[static_cast<std::size_t>(mZone)];
      if (z.folding.type != Folding::Type::Polygons) {
        z.folding = {};
        z.folding.type = Folding::Type::Polygons;
      }
      z.folding.polygons.push_back(clicks);
      replaceZone(mSession->history(), mZone, z, "add folding zone");
      break;
    }
    case ToolKind::Zero: {
      requireZone();
      addTool(mSession->history(), mZone,
              ZeroTool{clicks.size() == 1 ? std::vector<Vec2>{clicks[0], clicks[0]} : clicks});
      break;
    }
    case ToolKind::Curve: {
      requireZone();
      if (clicks.size() != 8) {
        fail("a curve mapping needs 4 source and 4 destination control points");
      }
      CurveTool c;
      std::copy(clicks.begin(), clicks.begin() + 4, c.source.begin());
      std::array<Vec2, 4> d{};
      std::copy(clicks.begin() + 4, clicks.end(), d.begin());
      c.dest = d;
      addTool(mSession->history(), mZone, c);
      break;
    }
    default:
      break;
    }
  });
}

void FoldEditor::paintFreeze(Vec2 centre, bool erase, bool finish) {
  const glm::ivec2 size = mSession->imageSize(mImage);
  if (mFreezeZone != mZone || mFreezeSize != size || mFreezePaint.empty()) {
    mFreezeZone = mZone;
    mFreezeSize = size;
    const std::vector<float>& existing = mSession->images().freezeMasks.at(static_cast<std::size_t>(mZone));
    mFreezePaint =
        existing.empty() ? std::vector<float>(static_cast<std::size_t>(size.x) * size.y, 0.0f) : existing;
  }
  const int r = static_cast<int>(std::ceil(mBrushRadius));
  for (int y = std::max(0, static_cast<int>(centre.y) - r);
       y < std::min(size.y, static_cast<int>(centre.y) + r + 1); ++y) {
    for (int x = std::max(0, static_cast<int>(centre.x) - r);
         x < std::min(size.x, static_cast<int>(centre.x) + r + 1); ++x) {
      if (glm::distance(Vec2(x + 0.5, y + 0.5), centre) <= mBrushRadius) {
        mFreezePaint[static_cast<std::size_t>(y) * size.x + x] = erase ? 0.0f : 1.0f;
      }
    }
  }
  replaceTexture(mFreezeTex, imageTexture(maskPicture(mFreezePaint, size)));
  if (!finish) {
    return;
  }
  // The stroke ends: write the mask next to the project and point the zone at it.
  edit([&] {
    Zone z = mSession->project().zones[static_cast<std::size_t>(mZone)];
    const fs::path file = z.freezeMask.empty()
                              ? fs::path(mSession->file().stem().string() + "." + z.id + ".freeze.png")
                              : z.freezeMask;
    Image mask(size.x, size.y, 1, PixelType::U8);
    auto* m = reinterpret_cast<std::uint8_t*>(mask.data());
    for (std::size_t i = 0; i < mFreezePaint.size(); ++i) {
      m[i] = mFreezePaint[i] >= 0.5f ? 255 : 0;
    }
    saveImage(mSession->project().resolve(file), mask);
    if (z.freezeMask.empty()) {
      z.freezeMask = file;
      replaceZone(mSession->history(), mZone, z, "freeze mask");
    }
    mSession->masksChanged(mZone);
  });
}

void FoldEditor::canvasInput() {
  ImGuiIO& io = ImGui::GetIO();
  const bool hovered = mCanvas.input(); // zooms and pans; the canvas button is the last item
  const Vec2 raw = mCanvas.toImage(io.MousePos);
  const Project& p = mSession->project(); // the same object after edits (its contents change)
  const std::string imageId = p.images[static_cast<std::size_t>(mImage)].id;
  const std::vector<Handle> handles = imageHandles(p, imageId);
  std::vector<Vec2> candidates;
  for (const Handle& h : handles) {
    if (!mGesture.handle || !(h == *mGesture.handle)) {
      candidates.push_back(h.pos);
    }
  }
  candidates.insert(candidates.end(), mClicks.begin(), mClicks.end());
  const glm::ivec2 imageSize = mSession->imageSize(mImage);
  Vec2 at = mSnapEnabled && !io.KeyAlt ? snapPoint(raw, mCanvas.view, candidates, mSnap) : raw;
  at = glm::clamp(at, Vec2(0.0), Vec2(imageSize));
  mCursor = at;
  mCursorInImage = hovered && raw.x >= 0 && raw.y >= 0 && raw.x <= imageSize.x && raw.y <= imageSize.y;

  const bool pressed = hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left);
  const bool released = mGesture.active && ImGui::IsMouseReleased(ImGuiMouseButton_Left);
  const bool dragging = mGesture.active && ImGui::IsMouseDown(ImGuiMouseButton_Left);
  const bool doubleClick = hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);

  if (pressed) {
    mGesture = {};
    mGesture.tool = mTool;
    mGesture.start = at;
    mGesture.current = at;
    switch (mTool) {
    case ToolKind::Select: {
      const std::vector<Handle> grabbable = imageHandles(p, imageId);
      if (std::optional<Handle> h = nearestHandle(grabbable, raw, 7.0 / mCanvas.view.zoom)) {
        mGesture.active = true;
        mGesture.handle = h;
        mGesture.handleLast = h->pos;
        mZone = h->zone;
      } else {
        // Select the topmost zone under the cursor.
        mZone = -1;
        for (std::size_t z = p.zones.size(); z-- > 0;) {
          const std::vector<Vec2> o = p.zones[z].shape.outline();
          bool inside = false;
          for (std::size_t i = 0, j = o.size() - 1; i < o.size(); j = i++) {
            if ((o[i].y > raw.y) != (o[j].y > raw.y) &&
                raw.x < (o[j].x - o[i].x) * (raw.y - o[i].y) / (o[j].y - o[i].y) + o[i].x) {
              inside = !inside;
            }
          }
          if (p.zones[z].image == imageId && inside) {
            mZone = static_cast<int>(z);
            break;
          }
        }
      }
      break;
    }
    case ToolKind::Rectangle:
    case ToolKind::Translate:
    case ToolKind::Scale:
    case ToolKind::Points:
      mGesture.active = true;
      break;
    case ToolKind::Freeze:
      if (mZone < 0) {
        setStatus("select a zone first (or draw one with R)", true);
      } else {
        mGesture.active = true;
        paintFreeze(at, io.KeyShift, false);
      }
      break;
    case ToolKind::Polygon:
    case ToolKind::Lasso:
    case ToolKind::Fold:
    case ToolKind::Zero:
    case ToolKind::Curve:
      if (doubleClick) {
        finishClicks();
      } else {
        mClicks.push_back(at);
        if (mTool == ToolKind::Curve && mClicks.size() == 8) {
          finishClicks();
        }
      }
      break;
    case ToolKind::Mask:
    case ToolKind::Count:
      break;
    }
  } else if (dragging || released) {
    // The frame that reads the release may also read the pointer's last move (GLFW polls once a frame and
    // ImGui applies a move and a button change of one frame together): apply the move before finishing, or
    // a fast drag loses its end.
    mGesture.current = at;
    if (mGesture.handle && at != mGesture.handleLast) {
      const Handle h = *mGesture.handle;
      if (edit([&] { moveHandle(mSession->history(), h, at, true); })) {
        std::optional<Rect> hint;
        if ((h.kind == Handle::Kind::PointTo || h.kind == Handle::Kind::PointFrom) && mSession->textures()) {
          // Only the anchor at b moves (PointTo) or changes its vector (PointFrom).
          const auto& pair =
              std::get<PointsTool>(
                  p.zones[static_cast<std::size_t>(h.zone)].tools[static_cast<std::size_t>(h.tool)])
                  .pairs[static_cast<std::size_t>(h.index)];
          const Vec2 before = h.kind == Handle::Kind::PointTo ? mGesture.handleLast : pair[1];
          const Vec2 after = h.kind == Handle::Kind::PointTo ? at : pair[1];
          hint = anchorMoveAtlasRect(mSession->project(), mSession->textures()->atlas, h.zone, before, after);
        }
        mGesture.handleLast = at;
        refresh(hint);
      }
    } else if (mGesture.tool == ToolKind::Freeze && !released) {
      paintFreeze(at, io.KeyShift, false); // the release paints at the end and writes the mask
    }
  }
  if (released) {
    const Gesture g = mGesture;
    mGesture = {};
    mSession->history().endCoalescing();
    const Vec2 d = g.current - g.start;
    edit([&] {
      switch (g.tool) {
      case ToolKind::Rectangle: {
        if (std::abs(d.x) < 2.0 || std::abs(d.y) < 2.0) {
          return;
        }
        Zone z;
        z.id = "zone";
        z.image = imageId;
        z.profile = p.profiles[static_cast<std::size_t>(mProfile)].id;
        z.shape.type = Shape::Type::Rect;
        z.shape.min = glm::min(g.start, g.current);
        z.shape.max = glm::max(g.start, g.current);
        z.interp.radius = std::clamp(0.5 * std::min(std::abs(d.x), std::abs(d.y)), 8.0, 128.0);
        z.zeroBoundary = true;
        mZone = addZone(mSession->history(), z);
        setStatus("zone added: now give it motion (A: point mapping, T: translate, templates in Motion)",
                  false);
        break;
      }
      case ToolKind::Translate:
        requireZone();
        if (glm::length(d) > 0.0) {
          addTool(mSession->history(), mZone, TranslateTool{d});
        }
        break;
      case ToolKind::Scale:
        requireZone();
        addTool(mSession->history(), mZone, ScaleTool{std::exp(d.x / 100.0), g.start});
        break;
      case ToolKind::Points:
        requireZone();
        if (glm::length(d) > 0.0) {
          addPoints(g.start, g.current);
          setStatus(fmt::format("anchor ({:.1f}, {:.1f}) -> ({:.1f}, {:.1f})", g.start.x, g.start.y,
                                g.current.x, g.current.y),
                    false);
        }
        break;
      case ToolKind::Freeze:
        paintFreeze(g.current, io.KeyShift, true);
        break;
      default:
        break;
      }
    });
  }
}

void FoldEditor::drawCanvas(ImVec2 pos, ImVec2 size) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::Begin("Canvas", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoScrollbar |
                   ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoTitleBar);
  ImGui::PopStyleVar();
  const Project& p = mSession->project();
  // Image tabs when there are several.
  if (p.images.size() > 1 && ImGui::BeginTabBar("images")) {
    for (std::size_t i = 0; i < p.images.size(); ++i) {
      if (ImGui::BeginTabItem(p.images[i].id.c_str())) {
        if (mImage != static_cast<int>(i)) {
          mImage = static_cast<int>(i);
          mCanvas.requestFit();
          mOverlaysStale = true;
          replaceTexture(mFreezeTex, gl::Texture(gl::NoCreate));
        }
        ImGui::EndTabItem();
      }
    }
    ImGui::EndTabBar();
  }
  const glm::ivec2 imageSize = mSession->imageSize(mImage);
  ImDrawList* dl = mCanvas.begin(textureId(mImageTextures.at(static_cast<std::size_t>(mImage))), imageSize);
  if (mZone < 0 && mFreezeZone >= 0) {
    replaceTexture(mFreezeTex, gl::Texture(gl::NoCreate));
    mFreezeZone = -1;
    mFreezePaint.clear();
  }
  if (mShowFreeze && mZone >= 0 && mFreezeZone != mZone) {
    const std::vector<float>& mask = mSession->images().freezeMasks.at(static_cast<std::size_t>(mZone));
    replaceTexture(mFreezeTex,
                   mask.empty() ? gl::Texture(gl::NoCreate) : imageTexture(maskPicture(mask, imageSize)));
    mFreezeZone = mZone;
    mFreezePaint.clear();
  }
  drawOverlays(dl);
  canvasInput();
  ImGui::End();
}

void FoldEditor::drawPreview(ImVec2 pos, ImVec2 size) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::Begin("Preview", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  const Project& p = mSession->project();
  const double period = longestPeriod(p.profiles);
  if (mUploaded && mSession->textures()) {
    const AtlasEntry& entry = mSession->textures()->atlas.entries.at(static_cast<std::size_t>(mImage));
    const Rect region = entry.atlasRect();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float room =
        avail.y - 2.0f * ImGui::GetFrameHeightWithSpacing() - ImGui::GetTextLineHeightWithSpacing();
    const float scale = std::max(1e-3f, std::min(avail.x / static_cast<float>(region.width()),
                                                 room / static_cast<float>(region.height())));
    // The preview renders at the size it is shown (never above 1:1), so its cost follows the pane, not the
    // image: a 1 MP image in a 400-pixel pane costs a sixth of a full frame (docs/folding-editor.md).
    const glm::ivec2 shown(std::max(1, static_cast<int>(std::lround(region.width() * scale))),
                           std::max(1, static_cast<int>(std::lround(region.height() * scale))));
    const glm::ivec2 want = glm::min(shown, glm::ivec2(region.width(), region.height()));
    mPreview.bindForDraw(want); // re-created at a new size (the last frame's draw list has been drawn)
    mRenderer.draw(mTime, region);
    gl::bindWindowFramebuffer();
    // draw() puts the region's row 0 at the top of the viewport (GL's last row): flip v.
    ImGui::Image(mPreview.texture(), ImVec2(static_cast<float>(shown.x), static_cast<float>(shown.y)),
                 ImVec2(0, 1), ImVec2(1, 0));
  } else {
    ImGui::TextDisabled(mJob ? "(synthesising in the background...)" : "(synthesise to preview: Ctrl+Enter)");
  }
  // Timeline.
  if (ImGui::Button(mPlaying ? "Pause" : "Play")) {
    mPlaying = !mPlaying;
  }
  ImGui::SameLine();
  float t = static_cast<float>(std::fmod(mTime, period));
  ImGui::SetNextItemWidth(-60);
  if (ImGui::SliderFloat("##time", &t, 0.0f, static_cast<float>(period), "t = %.2f s")) {
    mTime = t;
    mPlaying = false;
  }
  ImGui::SameLine();
  ImGui::TextDisabled("/%.1fs", period);
  ImGui::SetNextItemWidth(110);
  ImGui::SliderFloat("speed", &mSpeed, 0.0f, 4.0f, "%.2fx");
  ImGui::SameLine();
  ImGui::Checkbox("live", &mAutoSynth);
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("re-synthesise while editing (off: Ctrl+Enter)");
  }
  ImGui::SameLine();
  ImGui::TextDisabled("re-synthesis %s, %dx%d px", timing(mLastSynthMs).c_str(), mLastRegion.width(),
                      mLastRegion.height());
  ImGui::End();
}

void FoldEditor::drawZonePanel() {
  Project p = mSession->project();
  // Images and their zones (the thesis's motion-zone panel).
  for (std::size_t i = 0; i < p.images.size(); ++i) {
    const glm::ivec2 size = mSession->imageSize(static_cast<int>(i));
    ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    if (ImGui::TreeNode(p.images[i].id.c_str(), "%s  (%d x %d)%s", p.images[i].id.c_str(), size.x, size.y,
                        static_cast<int>(i) == p.canvasIndex() ? "  canvas" : "")) {
      for (std::size_t z = 0; z < p.zones.size(); ++z) {
        if (p.zones[z].image != p.images[i].id) {
          continue;
        }
        const std::string label =
            fmt::format("{} ({} tools)##zone{}", p.zones[z].id, p.zones[z].tools.size(), z);
        if (ImGui::Selectable(label.c_str(), mZone == static_cast<int>(z))) {
          mZone = static_cast<int>(z);
          if (mImage != static_cast<int>(i)) {
            mImage = static_cast<int>(i);
            mCanvas.requestFit();
            mOverlaysStale = true;
          }
        }
      }
      ImGui::TreePop();
    }
  }
  if (mZone < 0 || mZone >= static_cast<int>(p.zones.size())) {
    ImGui::TextDisabled("No zone selected: draw one with R or P.");
    return;
  }
  ImGui::Separator();
  Zone z = p.zones[static_cast<std::size_t>(mZone)];
  const Zone before = z;
  bool changed = false;
  char id[64];
  std::snprintf(id, sizeof(id), "%s", z.id.c_str());
  if (ImGui::InputText("id", id, sizeof(id), ImGuiInputTextFlags_EnterReturnsTrue)) {
    z.id = id;
    changed = true;
  }
  // Move the zone to another image.
  int image = p.imageIndex(z.image);
  std::vector<const char*> imageIds;
  for (const ImageEntry& e : p.images) {
    imageIds.push_back(e.id.c_str());
  }
  if (ImGui::Combo("image", &image, imageIds.data(), static_cast<int>(imageIds.size()))) {
    edit([&] { moveZoneToImage(mSession->history(), mZone, p.images[static_cast<std::size_t>(image)].id); });
    return;
  }
  int profile = p.profileIndex(z.profile);
  std::vector<const char*> profileIds;
  for (const Profile& pr : p.profiles) {
    profileIds.push_back(pr.id.c_str());
  }
  if (ImGui::Combo("profile", &profile, profileIds.data(), static_cast<int>(profileIds.size()))) {
    z.profile = p.profiles[static_cast<std::size_t>(profile)].id;
    changed = true;
  }
  float phase = static_cast<float>(z.phase);
  if (ImGui::SliderFloat("temporal shift", &phase, 0.0f, 1.0f, "%.3f cycles")) {
    z.phase = phase;
    changed = true;
  }
  int interp = static_cast<int>(z.interp.type);
  if (ImGui::Combo("interpolation", &interp, kInterpNames, 3)) {
    z.interp.type = static_cast<Interpolation::Type>(interp);
    changed = true;
  }
  float radius = static_cast<float>(z.interp.radius);
  if (z.interp.type != Interpolation::Type::Shepard &&
      ImGui::SliderFloat("radius R", &radius, 2.0f, 512.0f, "%.0f px", ImGuiSliderFlags_Logarithmic)) {
    z.interp.radius = radius;
    z.interp.ring = std::min(z.interp.ring, 0.9 * radius);
    changed = true;
  }
  float ring = static_cast<float>(z.interp.ring);
  if (z.interp.type == Interpolation::Type::ModifiedShepardRandom &&
      ImGui::SliderFloat("ring", &ring, 0.5f, static_cast<float>(0.9 * z.interp.radius), "%.1f px")) {
    z.interp.ring = ring;
    changed = true;
  }
  float power = static_cast<float>(z.interp.power);
  if (z.interp.type == Interpolation::Type::Shepard && ImGui::SliderFloat("power", &power, 0.5f, 8.0f)) {
    z.interp.power = power;
    changed = true;
  }
  changed |= ImGui::Checkbox("still border", &z.zeroBoundary);
  float feather = static_cast<float>(z.feather);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(100);
  if (ImGui::SliderFloat("feather", &feather, 0.0f, 64.0f, "%.0f px")) {
    z.feather = feather;
    changed = true;
  }
  int folding = static_cast<int>(z.folding.type);
  ImGui::TextDisabled("folding: %s%s", kFoldingNames[folding],
                      z.folding.type == Folding::Type::None ? " (F to draw one)" : "");
  if (z.folding.type != Folding::Type::None) {
    ImGui::SameLine();
    changed |= ImGui::Checkbox("outside warps", &z.folding.outsideWarps);
    ImGui::SameLine();
    if (ImGui::SmallButton("remove folding")) {
      z.folding = {};
      changed = true;
    }
  }
  if (!z.freezeMask.empty()) {
    ImGui::TextDisabled("freeze mask: %s", z.freezeMask.string().c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("clear")) {
      z.freezeMask.clear();
      mFreezePaint.clear();
      mFreezeZone = -1;
      changed = true;
    }
  }
  std::vector<const char*> templates;
  for (MotionTemplate t : motionTemplates()) {
    templates.push_back(motionTemplateName(t));
  }
  ImGui::SetNextItemWidth(150);
  ImGui::Combo("##template", &mTemplate, templates.data(), static_cast<int>(templates.size()));
  ImGui::SameLine();
  if (ImGui::Button("apply template")) {
    edit([&] {
      applyMotionTemplate(mSession->history(), mZone, motionTemplates()[static_cast<std::size_t>(mTemplate)]);
    });
    return;
  }
  if (ImGui::Button("delete zone (Del)")) {
    deleteSelectedZone();
    return;
  }
  if (changed && !(z == before)) {
    // Sliders coalesce while held; any other widget commits one step.
    edit([&] { replaceZone(mSession->history(), mZone, z, "zone properties", ImGui::IsAnyItemActive()); });
  }
}

void FoldEditor::drawJumpTree() {
  const Project p = mSession->project();
  for (std::size_t zi = 0; zi < p.zones.size(); ++zi) {
    const Zone& zone = p.zones[zi];
    const int z = static_cast<int>(zi);
    ImGui::SetNextItemOpen(z == mZone, ImGuiCond_Always);
    if (!ImGui::TreeNode(fmt::format("zone##jt{}", zi).c_str(), "%s", zone.id.c_str())) {
      if (ImGui::IsItemClicked()) {
        mZone = z;
      }
      continue;
    }
    if (ImGui::IsItemClicked()) {
      mZone = -1;
    }
    for (std::size_t ti = 0; ti < zone.tools.size(); ++ti) {
      const Tool& tool = zone.tools[ti];
      const char* names[] = {"translate", "scale", "points", "curve", "lasso", "still line", "fly-over"};
      const bool open = ImGui::TreeNode(fmt::format("tool{}-{}", zi, ti).c_str(), "%s", names[tool.index()]);
      ImGui::SameLine();
      if (ImGui::SmallButton(fmt::format("x##rm{}-{}", zi, ti).c_str())) {
        edit([&] { removeTool(mSession->history(), z, static_cast<int>(ti)); });
        if (open) {
          ImGui::TreePop();
        }
        break;
      }
      if (!open) {
        continue;
      }
      Zone edited = zone;
      bool changed = false;
      if (auto* points = std::get_if<PointsTool>(&edited.tools[ti])) {
        for (std::size_t k = 0; k < points->pairs.size(); ++k) {
          ImGui::PushID(static_cast<int>(k));
          // Init position (where the anchor sits, b) and jump (where it reads from, a − b).
          float b[2] = {static_cast<float>(points->pairs[k][1].x), static_cast<float>(points->pairs[k][1].y)};
          const Vec2 jv = points->pairs[k][0] - points->pairs[k][1];
          float j[2] = {static_cast<float>(jv.x), static_cast<float>(jv.y)};
          ImGui::SetNextItemWidth(120);
          if (ImGui::DragFloat2("init", b, 0.25f, 0.0f, 0.0f, "%.1f")) {
            points->pairs[k][1] = Vec2(b[0], b[1]);
            points->pairs[k][0] = points->pairs[k][1] + jv;
            changed = true;
          }
          ImGui::SameLine();
          ImGui::SetNextItemWidth(120);
          if (ImGui::DragFloat2("jump", j, 0.25f, 0.0f, 0.0f, "%.1f")) {
            points->pairs[k][0] = points->pairs[k][1] + Vec2(j[0], j[1]);
            changed = true;
          }
          ImGui::SameLine();
          if (points->pairs.size() > 1 && ImGui::SmallButton("x")) {
            points->pairs.erase(points->pairs.begin() + static_cast<std::ptrdiff_t>(k));
            changed = true;
            ImGui::PopID();
            break;
          }
          ImGui::PopID();
        }
        if (ImGui::SmallButton("+ pair")) {
          const auto last = points->pairs.back();
          points->pairs.push_back({last[0] + Vec2(4.0, 0.0), last[1] + Vec2(4.0, 0.0)});
          changed = true;
        }
      } else if (auto* translate = std::get_if<TranslateTool>(&edited.tools[ti])) {
        float v[2] = {static_cast<float>(translate->v.x), static_cast<float>(translate->v.y)};
        if (ImGui::DragFloat2("motion", v, 0.25f, 0.0f, 0.0f, "%.1f px")) {
          translate->v = Vec2(v[0], v[1]);
          changed = true;
        }
      } else if (auto* scale = std::get_if<ScaleTool>(&edited.tools[ti])) {
        float f = static_cast<float>(scale->factor);
        if (ImGui::DragFloat("factor", &f, 0.005f, 0.1f, 10.0f, "%.3f")) {
          scale->factor = f;
          changed = true;
        }
      } else if (auto* curve = std::get_if<CurveTool>(&edited.tools[ti])) {
        changed |= ImGui::SliderInt("samples", &curve->samples, 2, 256);
      } else if (auto* lasso = std::get_if<LassoTool>(&edited.tools[ti])) {
        changed |= ImGui::Checkbox("mean-value interior", &lasso->meanValue);
        ImGui::TextDisabled("%zu vertices", lasso->from.size());
      } else {
        ImGui::TextDisabled("drag its points on the canvas");
      }
      if (changed) {
        edit(
            [&] { replaceZone(mSession->history(), z, edited, "edit jump path", ImGui::IsAnyItemActive()); });
      }
      ImGui::TreePop();
    }
    if (zone.tools.empty()) {
      ImGui::TextDisabled("no motion yet: A (points), T, S, C, L or a template");
    }
    ImGui::TreePop();
  }
}

void FoldEditor::drawProfilePanel() {
  const Project& p = mSession->project();
  for (std::size_t i = 0; i < p.profiles.size(); ++i) {
    if (ImGui::Selectable(fmt::format("{}##prof{}", p.profiles[i].id, i).c_str(),
                          mProfile == static_cast<int>(i), 0, ImVec2(120, 0))) {
      mProfile = static_cast<int>(i);
    }
    if (i + 1 < p.profiles.size()) {
      ImGui::SameLine();
    }
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("+ profile")) {
    Profile np = p.profiles[static_cast<std::size_t>(mProfile)];
    np.id = "motion";
    edit([&] { mProfile = addProfile(mSession->history(), np); });
    return;
  }
  Profile pr = p.profiles[static_cast<std::size_t>(mProfile)];
  const Profile before = pr;
  int type = static_cast<int>(pr.fn.type);
  if (ImGui::Combo("p(phi)", &type, kFunctionNames, 5)) {
    pr.fn.type = static_cast<PositionFunction::Type>(type);
    if (pr.fn.type == PositionFunction::Type::Piecewise && pr.fn.knots.size() < 2) {
      pr.fn.knots = {{0.0, 0.0}, {0.3, 1.0}, {0.5, 1.0}, {0.8, 0.0}, {1.0, 0.0}};
    }
  }
  auto slider = [](const char* label, double& v, float lo, float hi, const char* fmt = "%.3f") {
    float f = static_cast<float>(v);
    if (ImGui::SliderFloat(label, &f, lo, hi, fmt)) {
      v = f;
    }
  };
  slider("period", pr.periodS, 0.1f, 20.0f, "%.2f s");
  slider("shift", pr.shift, 0.0f, 1.0f, "%.3f cycles");
  int loop = static_cast<int>(pr.loop);
  if (ImGui::Combo("loop", &loop, kLoopNames, 3)) {
    pr.loop = static_cast<LoopMode>(loop);
  }
  switch (pr.fn.type) {
  case PositionFunction::Type::Linear:
    slider("slope", pr.fn.slope, 0.1f, 10.0f);
    slider("delay", pr.fn.delay, -1.0f, 1.0f);
    break;
  case PositionFunction::Type::Exponential:
    slider("k", pr.fn.k, -10.0f, 10.0f);
    break;
  case PositionFunction::Type::Sigmoid:
    slider("steepness", pr.fn.k, 0.5f, 40.0f);
    slider("centre", pr.fn.centre, 0.05f, 0.95f);
    break;
  case PositionFunction::Type::Sine:
    slider("amplitude", pr.fn.amplitude, 0.0f, 1.0f);
    slider("frequency", pr.fn.frequency, 0.0f, 4.0f);
    slider("phase", pr.fn.phase, 0.0f, 6.2832f);
    slider("offset", pr.fn.offset, -1.0f, 1.0f);
    break;
  case PositionFunction::Type::Piecewise:
    for (std::size_t k = 0; k < pr.fn.knots.size(); ++k) {
      ImGui::PushID(static_cast<int>(k));
      float v[2] = {static_cast<float>(pr.fn.knots[k].x), static_cast<float>(pr.fn.knots[k].y)};
      if (ImGui::DragFloat2("knot", v, 0.005f, 0.0f, 1.0f, "%.3f")) {
        pr.fn.knots[k] = {k == 0 ? 0.0 : k + 1 == pr.fn.knots.size() ? 1.0 : v[0], v[1]};
      }
      ImGui::PopID();
    }
    break;
  }
  // p(φ) plot with the current phase marked.
  const ImVec2 plotSize(ImGui::GetContentRegionAvail().x, 90.0f);
  const ImVec2 o = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(o, ImVec2(o.x + plotSize.x, o.y + plotSize.y), IM_COL32(25, 25, 30, 255));
  std::vector<ImVec2> curve;
  for (int i = 0; i <= 128; ++i) {
    const double phi = i / 128.0;
    const double s = progressAt(pr, phi * pr.periodS - pr.shift * pr.periodS, 0.0);
    curve.emplace_back(o.x + static_cast<float>(phi) * plotSize.x,
                       o.y + plotSize.y - 6.0f -
                           static_cast<float>(std::clamp(s, -0.2, 1.2)) * (plotSize.y - 12.0f));
  }
  dl->AddPolyline(curve.data(), static_cast<int>(curve.size()), IM_COL32(255, 200, 80, 255), 0, 2.0f);
  const double phiNow = std::fmod(mTime / pr.periodS + pr.shift, 1.0);
  const float xNow = o.x + static_cast<float>(phiNow) * plotSize.x;
  dl->AddLine(ImVec2(xNow, o.y), ImVec2(xNow, o.y + plotSize.y), IM_COL32(120, 200, 255, 255));
  dl->AddText(ImVec2(o.x + 4, o.y + 2), IM_COL32(200, 200, 200, 255), "p(phi)");
  ImGui::Dummy(plotSize);
  if (!(pr == before)) {
    edit([&] { replaceProfile(mSession->history(), mProfile, pr, ImGui::IsAnyItemActive()); });
  }
}

void FoldEditor::drawPanels(ImVec2 pos, ImVec2 size) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::Begin("Project", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  if (ImGui::BeginTabBar("panels")) {
    const char* tabs[] = {"Motion zones", "Jump paths", "Profiles"};
    for (int i = 0; i < 3; ++i) {
      const ImGuiTabItemFlags flags = mPanelTab == i ? ImGuiTabItemFlags_SetSelected : 0;
      if (ImGui::BeginTabItem(tabs[i], nullptr, flags)) {
        if (i == 0) {
          drawZonePanel();
        } else if (i == 1) {
          drawJumpTree();
        } else {
          drawProfilePanel();
        }
        ImGui::EndTabItem();
      }
    }
    mPanelTab = -1;
    ImGui::EndTabBar();
  }
  ImGui::End();
}

void FoldEditor::drawStatusBar(ImVec2 pos, ImVec2 size) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);
  if (mSession) {
    const glm::ivec2 s = mSession->imageSize(mImage);
    if (mCursorInImage) {
      ImGui::Text("x %.1f  y %.1f px   u %.4f  v %.4f", mCursor.x, mCursor.y, mCursor.x / s.x,
                  mCursor.y / s.y);
    } else {
      ImGui::TextDisabled("x -  y -");
    }
    ImGui::SameLine(300);
    ImGui::Text("zoom %.0f%%", 100.0 * mCanvas.view.zoom);
    ImGui::SameLine(400);
    if (mJob) {
      const float done = static_cast<float>(mJob->progress->done()) / static_cast<float>(mJob->total);
      ImGui::SetNextItemWidth(180);
      ImGui::ProgressBar(done, ImVec2(180, 0), fmt::format("synthesis {:.0f}%", 100.0f * done).c_str());
    } else if (mSession->stale()) {
      ImGui::TextColored(ImVec4(1, 0.7f, 0.2f, 1), "synthesis pending");
    } else {
      ImGui::Text("synthesised (%s)", timing(mLastSynthMs).c_str());
    }
    ImGui::SameLine(600);
    ImGui::Text("%s", mSession->history().dirty() ? "* unsaved" : "saved");
    ImGui::SameLine(700);
  }
  if (mStatusError) {
    ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "%s", mStatus.c_str());
  } else {
    ImGui::TextUnformatted(mStatus.c_str());
  }
  ImGui::End();
}

void FoldEditor::drawPrompt() {
  if (mPrompt.open) {
    ImGui::OpenPopup("path");
    mPrompt.open = false;
  }
  ImGui::SetNextWindowSize(ImVec2(640, 0), ImGuiCond_Always);
  if (ImGui::BeginPopupModal("path", nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::TextUnformatted(mPrompt.title.c_str());
    if (ImGui::IsWindowAppearing()) {
      ImGui::SetKeyboardFocusHere();
    }
    ImGui::SetNextItemWidth(-1);
    const bool enter =
        ImGui::InputText("##p", mPrompt.path, sizeof(mPrompt.path), ImGuiInputTextFlags_EnterReturnsTrue);
    if (enter || ImGui::Button("OK")) {
      ImGui::CloseCurrentPopup();
      runPrompt(mPrompt.path);
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

void FoldEditor::drawFlowWindow() {
  if (!mFlow.open) {
    return;
  }
  FlowPanel& f = mFlow;
  // Over the panels on the right at first, so the canvas (where the suggestions are drawn) stays visible.
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowSize(ImVec2(460, 520), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos(ImVec2(vp->Size.x - 470.0f, vp->Size.y - 560.0f), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Motion from a reference video", &f.open)) {
    ImGui::End();
    return;
  }
  if (ImGui::Button("Load video...")) {
    prompt(PathPrompt::Action::Video, "Reference video (a file OpenCV reads, or frames/%04d.png)");
  }
  if (f.clip.frames.empty()) {
    ImGui::TextDisabled("No video loaded.");
    ImGui::End();
    return;
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%s: %zu frames", fs::path(f.file).filename().string().c_str(), f.clip.frames.size());
  const int last = static_cast<int>(f.clip.frames.size()) - 1;
  bool thumbs = ImGui::SliderInt("frame A", &f.frameA, 0, last);
  thumbs |= ImGui::SliderInt("frame B", &f.frameB, 0, last);
  if (thumbs) {
    updateFlowThumbs();
  }
  const float w = (ImGui::GetContentRegionAvail().x - 8.0f) / 3.0f;
  const float h = w * static_cast<float>(f.clip.size.y) / static_cast<float>(std::max(1, f.clip.size.x));
  ImGui::Image(textureId(f.thumbA), ImVec2(w, h));
  ImGui::SameLine();
  ImGui::Image(textureId(f.thumbB), ImVec2(w, h));
  if (f.flowTex.id() != 0) {
    ImGui::SameLine();
    ImGui::Image(textureId(f.flowTex), ImVec2(w, h));
  }
  const char* methods[] = {"DIS (fast)", "Farneback"};
  ImGui::Combo("method", &f.method, methods, 2);
  ImGui::Checkbox("map onto the whole image (else the zone's box)", &f.mapImage);
  float spacing = static_cast<float>(f.options.spacingPx);
  if (ImGui::SliderFloat("spacing", &spacing, 2.0f, 64.0f, "%.0f px")) {
    f.options.spacingPx = spacing;
  }
  float minMag = static_cast<float>(f.options.minMagnitudePx);
  if (ImGui::SliderFloat("min motion", &minMag, 0.0f, 8.0f, "%.1f px")) {
    f.options.minMagnitudePx = minMag;
  }
  float scale = static_cast<float>(f.options.scale);
  if (ImGui::SliderFloat("scale", &scale, 0.1f, 8.0f, "%.2fx")) {
    f.options.scale = scale;
  }
  ImGui::SliderInt("max anchors", &f.options.maxAnchors, 1, 2000);
  if (ImGui::Button("Suggest anchors for the selected zone")) {
    edit([&] { computeSuggestions(); });
  }
  if (!f.suggestions.empty()) {
    ImGui::Text("%zu suggested (of %zu samples: %zu still, %zu inconsistent, %zu irregular)",
                f.suggestions.size(), f.stats.samples, f.stats.still, f.stats.inconsistent,
                f.stats.irregular);
    if (ImGui::Button("Accept")) {
      if (edit([&] { applyFlowSuggestion(mSession->history(), f.zone, f.suggestions); })) {
        setStatus(fmt::format("added {} anchors from the video; drag them to edit (V)", f.suggestions.size()),
                  false);
        f.suggestions.clear();
      }
    }
    ImGui::SameLine();
    if (ImGui::Button("Reject")) {
      f.suggestions.clear();
    }
  }
  ImGui::End();
}

void FoldEditor::drawStartScreen(ImVec2 size) {
  ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.4f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::Begin("Sylva fold editor", nullptr,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
  ImGui::TextUnformatted("Animate a still image with folding textures.");
  if (ImGui::Button("New from image... (Ctrl+N)")) {
    prompt(PathPrompt::Action::NewFromImage, "New project from image(s) (separate several with ';')");
  }
  ImGui::SameLine();
  if (ImGui::Button("Open project... (Ctrl+O)")) {
    prompt(PathPrompt::Action::Open, "Open project");
  }
  if (!mRecent.entries().empty()) {
    ImGui::Separator();
    ImGui::TextUnformatted("Recent");
    for (const fs::path& f : mRecent.entries()) {
      if (ImGui::Selectable(f.string().c_str())) {
        edit([&] { openProject(f, true); });
      }
    }
  }
  ImGui::End();
}

void FoldEditor::drawHelp() {
  if (!mShowHelp) {
    return;
  }
  ImGui::SetNextWindowSize(ImVec2(520, 0), ImGuiCond_Always);
  ImGui::Begin("Shortcuts and workflow", &mShowHelp, ImGuiWindowFlags_NoSavedSettings);
  ImGui::TextWrapped(
      "1 draw a motion zone (R, P). 2 give it motion: drag anchors (A), translate (T), scale (S), "
      "curves (C), lasso (L) or a template (Motion menu), optionally a folding zone (F). 3 shape "
      "the timing in Profiles. 4-5 the preview updates while you edit. 6 export.");
  ImGui::Separator();
  for (const ToolInfo& t : kTools) {
    ImGui::Text("%s   %s", t.key, t.name);
  }
  ImGui::Separator();
  ImGui::TextUnformatted(
      "Ctrl+Z / Ctrl+Y undo/redo, Ctrl+S save, Ctrl+O open, Ctrl+N new, Ctrl+E edit image "
      "externally, Ctrl+Enter synthesise, Space play/pause, Home fit, +/- zoom, 1 actual pixels, "
      "G pixel snapping, Alt no snapping, Del delete zone, Enter finish, Esc cancel; wheel zooms "
      "around the cursor, right/middle drag pans.");
  ImGui::End();
}

void FoldEditor::run() {
  ImGui::GetStyle().WindowRounding = 0.0f;
  mShell.run([this](const ui::ShellFrame& f) {
    if (mPlaying) {
      mTime += f.dt * mSpeed;
    }
    mRetired.clear(); // last frame's draw lists are rendered: their old textures can go
    updateTitleAndSelection();
    if (glfwGetKey(mShell.window().handle(), GLFW_KEY_F1) == GLFW_PRESS) {
      mShowHelp = true;
    }
    pollFiles();
    autosaveTick();
    if (mSession && !mGesture.active) {
      refresh();
    }
    updateOverlays();
    mShell.beginUi();
    drawMenuBar();
    const float menu = ImGui::GetFrameHeight();
    const float bar = ImGui::GetFrameHeightWithSpacing() + 8.0f;
    const float status = ImGui::GetFrameHeightWithSpacing() + 6.0f;
    const ImVec2 full(static_cast<float>(f.size.x), static_cast<float>(f.size.y));
    drawWorkflowBar(menu, bar);
    if (mSession) {
      const float top = menu + bar;
      const float height = full.y - top - status;
      const float left = 250.0f;
      const float right = std::min(520.0f, 0.34f * full.x);
      drawToolbox(ImVec2(0, top), ImVec2(left, height));
      drawCanvas(ImVec2(left, top), ImVec2(full.x - left - right, height));
      const float previewHeight = 0.5f * height;
      drawPreview(ImVec2(full.x - right, top), ImVec2(right, previewHeight));
      drawPanels(ImVec2(full.x - right, top + previewHeight), ImVec2(right, height - previewHeight));
      drawFlowWindow();
    } else {
      drawStartScreen(full);
    }
    drawStatusBar(ImVec2(0, full.y - status), ImVec2(full.x, status));
    drawPrompt();
    drawHelp();
    if (mSession && !ImGui::IsAnyItemActive() && !mGesture.active) {
      mSession->history().endCoalescing();
    }
    gl::bindDefaultFramebuffer(f.size.x, f.size.y);
    gl::clear(glm::vec4(0.1f, 0.1f, 0.11f, 1.0f));
    mShell.endUi();
  });
  cancelBackground();
  if (mSession && mSession->history().dirty() && mOptions.autosaveSeconds > 0.0) {
    // Closing with unsaved work: keep it in the sidecar so the next open offers it back.
    try {
      mSession->autosaveNow();
    } catch (const Error&) {
    }
  }
}

} // namespace

void runFoldEditor(const FoldEditOptions& options) {
  FoldEditor editor(options);
  editor.run();
}

void registerFoldEdit(CLI::App& fold) {
  auto* command = fold.add_subcommand(
      "edit",
      "The folding-texture editor: draw motion zones and anchors on an image, shape the timing, watch "
      "the live preview, export (docs/folding-editor.md)");
  auto o = std::make_shared<FoldEditOptions>();
  command->add_option("inputs", o->inputs,
                      "A project file (.json) to open, or image files to start a new project from (none: the "
                      "start screen)");
  command->add_option("--project", o->project,
                      "Where a new project is saved (default: <first image>.fold.json next to it)");
  command->add_option("--width", o->width, "Window width")
      ->check(CLI::Range(640, 16384))
      ->capture_default_str();
  command->add_option("--height", o->height, "Window height")
      ->check(CLI::Range(480, 16384))
      ->capture_default_str();
  command->add_option("--zoom", o->zoom, "Canvas zoom at start (0: fit the image)")
      ->check(CLI::Range(0.0, 32.0));
  command
      ->add_option("--autosave", o->autosaveSeconds, "Seconds between autosaves of unsaved work (0: never)")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  command->add_option("--paused-at", o->pausedAt, "Start with the preview paused at this time (seconds)")
      ->check(CLI::Range(0.0, 1e6));
  command->add_flag("--no-recover", o->noRecover, "Ignore an autosave sidecar newer than the project file");
  command->add_option("--recent-file", o->recentFile,
                      "The recent-files list (default: $XDG_CONFIG_HOME/sylva/recent-folding.json)");
  command->add_option("--shader-dir", o->shaderDir, "Read shaders from this directory")
      ->check(CLI::ExistingDirectory);
  addScriptedWindowOptions(*command, o->frames, o->screenshot, o->fixedStep);
  command->callback([o] { runFoldEditor(*o); });
}

} // namespace sylva::app

#pragma once
// The ui module's window shell (docs/engine.md): the one window loop every windowed command runs (the viewer,
// the fold viewer, the fold editor). It owns the GLFW window and its ImGui layer, the frame clock (real or
// fixed-step), the scripted-run contract (quit after N frames, screenshot of the last), the frame-time ring,
// the key bindings every window shares (Tab: panel, Esc: quit) and the per-frame log lines GUI tests wait on.
// What a window shows is the command's: it draws in the frame callback.

#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/Timing.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/ui/ImGuiLayer.hpp>

#include <glm/glm.hpp>

#include <chrono>
#include <deque>
#include <functional>
#include <string>

namespace sylva::ui {

/** How a shell's window opens and runs. */
struct ShellOptions {
  int width = 1280;       ///< window width, screen pixels
  int height = 720;       ///< window height, screen pixels
  std::string title;      ///< window title
  int frames = 0;         ///< > 0: a scripted run that quits after this many frames
  std::string screenshot; ///< with frames: the last frame's window framebuffer is saved here (path printed)
  double fixedStep = 0.0; ///< > 0: every frame's dt, seconds (scripted runs repeat exactly)
  /**
   * > 0: interactive runs sleep so as not to draw more than this many frames per second (an editor must not
   * spin a core while the user thinks; swap intervals are not honoured everywhere, e.g. under Xvfb).
   */
  double maxFps = 0.0;
  bool panelShown = true;      ///< the panel at start (Tab toggles it when tabTogglesPanel)
  bool tabTogglesPanel = true; ///< Tab shows and hides the panel
  bool escapeQuits = true;     ///< Esc closes the window
  /**
   * Which keys reach the command's handler: false (viewers) drops every key while an ImGui widget has the
   * keyboard; true (editors, whose shortcuts work beside focused panels) drops them only while text is typed.
   */
  bool keysBesideWidgets = false;
  /** Debug line after every shown frame: "<logName>: frame N shown<frameNote>" (empty: none). */
  std::string logName;
};

/** One frame of the loop: the time step and the window's framebuffer. */
struct ShellFrame {
  double dt = 0.0;         ///< seconds since the last frame (the fixed step when scripted)
  glm::ivec2 size{0};      ///< framebuffer pixels, never zero
  float aspect = 1.0f;     ///< size.x / size.y
  long long index = 0;     ///< frames shown before this one
  bool fixedClock = false; ///< dt is the fixed step
  double wallDt = 0.0;     ///< real seconds since the last frame began, fixed clock or not (0 for frame 0)
};

/**
 * A window with an ImGui layer and the loop around the command's frame callback. Construct it before any GL
 * object (it makes the context current); destroy GL objects before it.
 */
class WindowShell {
public:
  /** Opens the window with an ImGui layer as `options` say. Needs a display. */
  explicit WindowShell(const ShellOptions& options);
  WindowShell(const WindowShell&) = delete;
  WindowShell& operator=(const WindowShell&) = delete;

  /** The window (input, framebuffer size). */
  platform::GlfwWindow& window() { return mWindow; }
  /** The GL renderer string (the panel's first line). */
  const std::string& renderer() const { return mRenderer; }

  /**
   * The command's keys: `handler(key, mods)` sees every press the options let through and returns true when
   * it used the key; Tab and Esc keep their shell meaning otherwise.
   */
  void setKeyHandler(std::function<bool(int key, int mods)> handler) { mKeyHandler = std::move(handler); }

  /** Whether the command's panel is shown this frame (Tab toggles it). */
  bool panelShown() const { return mPanelShown; }
  /** Shows or hides the command's panel. */
  void setPanelShown(bool shown) { mPanelShown = shown; }
  /** Ends the loop after the current frame. */
  void requestClose();
  /** The frame clock: seconds since the first frame (frames × step when fixed). */
  const render::FrameClock& clock() const { return mClock; }
  /** Text appended to this frame's debug line (e.g. the scene time). */
  void setFrameNote(std::string note) { mFrameNote = std::move(note); }

  /** The last 120 frame times, milliseconds. */
  const std::deque<float>& frameTimes() const { return mFrameTimes; }
  /** Mean of frameTimes(), milliseconds (0 before the first frame). */
  float meanFrameMs() const;
  /**
   * Opens the viewer-style panel (ui::beginPanel: renderer first, 220-px controls) and writes the frame-time
   * line under it; close with ImGui::PopItemWidth() and ImGui::End().
   */
  void beginPanel(const char* title, const std::string& extra = {});

  /**
   * Shows `target`'s colour (`drawn` pixels of it) over the whole window (`windowSize` pixels), scaled with
   * linear filtering when a frame was drawn at a lower resolution, and leaves the window's framebuffer bound
   * for the panels.
   */
  static void present(const render::RenderTarget& target, glm::ivec2 drawn, glm::ivec2 windowSize);

  /** ImGui frame brackets for the frame callback (ImGuiLayer::begin/end). */
  void beginUi() { mUi.begin(); }
  /** Ends the ImGui frame begun by beginUi() and draws it. */
  void endUi() { mUi.end(); }

  /**
   * Runs until the window closes, Esc, requestClose() or the scripted frames are done. Each frame polls
   * events, ticks the clock, skips a minimised window, calls `frame` (which draws into the window's
   * framebuffer, ImGui included), saves the scripted screenshot, swaps and logs.
   */
  void run(const std::function<void(const ShellFrame&)>& frame);

private:
  void onKey(int key, int mods);

  ShellOptions mOptions;
  platform::GlfwWindow mWindow;
  std::string mRenderer;
  ImGuiLayer mUi;
  render::FrameClock mClock;
  std::deque<float> mFrameTimes;
  std::function<bool(int, int)> mKeyHandler;
  std::string mFrameNote;
  bool mPanelShown;
  std::chrono::steady_clock::time_point mStartup;
};

} // namespace sylva::ui

#include <sylva/ui/WindowShell.hpp>

#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>

namespace sylva::ui {
namespace {

/**
 * Ends one frame: with `screenshot` set, saves the window's framebuffer (size pixels) after the last of
 * `frames` scripted frames and prints its path; swaps; keeps the last 120 frame times (ms) in `frameTimes`.
 * Returns true when `frames` > 0 frames have been shown (the loop should stop).
 */
bool endWindowFrame(platform::GlfwWindow& window, glm::ivec2 size, const std::string& screenshot, int frames,
                    int& frame, double dtSeconds, std::deque<float>& frameTimes) {
  if (!screenshot.empty() && frames > 0 && frame + 1 == frames) {
    gl::finish();
    gl::bindWindowFramebuffer();
    saveImage(screenshot, render::readFramebuffer(size.x, size.y));
    std::printf("%s\n", screenshot.c_str());
  }
  window.swapBuffers();
  frameTimes.push_back(static_cast<float>(dtSeconds * 1000.0));
  if (frameTimes.size() > 120) {
    frameTimes.pop_front();
  }
  return frames > 0 && ++frame >= frames;
}

} // namespace

WindowShell::WindowShell(const ShellOptions& options)
    : mOptions(options), mWindow(options.width, options.height, options.title),
      mRenderer(gl::queryContextInfo().renderer), mUi(mWindow), mClock(options.fixedStep),
      mPanelShown(options.panelShown), mStartup(std::chrono::steady_clock::now()) {
  mWindow.setVsync(options.frames == 0);
  mWindow.setKeyCallback([this](int key, int mods) { onKey(key, mods); });
}

void WindowShell::onKey(int key, int mods) {
  const ImGuiIO& io = ImGui::GetIO();
  if (mOptions.keysBesideWidgets ? io.WantTextInput : io.WantCaptureKeyboard) {
    return;
  }
  if (mKeyHandler && mKeyHandler(key, mods)) {
    return;
  }
  if (key == GLFW_KEY_TAB && mOptions.tabTogglesPanel) {
    mPanelShown = !mPanelShown;
  } else if (key == GLFW_KEY_ESCAPE && mOptions.escapeQuits) {
    requestClose();
  }
}

void WindowShell::requestClose() {
  glfwSetWindowShouldClose(mWindow.handle(), GLFW_TRUE);
}

void WindowShell::present(const render::RenderTarget& target, glm::ivec2 drawn, glm::ivec2 windowSize) {
  gl::blitToWindow(target.framebuffer(), drawn, windowSize);
  gl::bindDefaultFramebuffer(windowSize.x, windowSize.y);
}

float WindowShell::meanFrameMs() const {
  float sum = 0.0f;
  for (float ms : mFrameTimes) {
    sum += ms;
  }
  return mFrameTimes.empty() ? 0.0f : sum / static_cast<float>(mFrameTimes.size());
}

void WindowShell::beginPanel(const char* title, const std::string& extra) {
  const float avg = ui::beginPanel(title, mRenderer, mFrameTimes);
  ImGui::Text("frame %.2f ms (%.0f fps)%s", avg, avg > 0.0f ? 1000.0f / avg : 0.0f, extra.c_str());
}

void WindowShell::run(const std::function<void(const ShellFrame&)>& frame) {
  const bool scripted = mOptions.frames > 0;
  int scriptedFrame = 0;
  long long shown = 0;
  auto frameStart = std::chrono::steady_clock::now();
  std::optional<std::chrono::steady_clock::time_point> lastBegin;
  while (mWindow.pollEvents()) {
    if (!scripted && mOptions.maxFps > 0.0) {
      std::this_thread::sleep_until(frameStart + std::chrono::duration<double>(1.0 / mOptions.maxFps));
      frameStart = std::chrono::steady_clock::now();
    }
    // Frame 0 shows the start; later frames advance by the clock (the fixed step when scripted).
    ShellFrame f;
    f.dt = mClock.tick();
    f.size = mWindow.framebufferSize();
    if (f.size.x == 0 || f.size.y == 0) {
      continue; // minimised
    }
    f.aspect = static_cast<float>(f.size.x) / static_cast<float>(f.size.y);
    f.index = shown;
    f.fixedClock = mClock.fixed();
    const auto begin = std::chrono::steady_clock::now();
    f.wallDt = lastBegin ? std::chrono::duration<double>(begin - *lastBegin).count() : 0.0;
    lastBegin = begin;
    mFrameNote.clear();
    frame(f);
    const bool last = endWindowFrame(mWindow, f.size, mOptions.screenshot, mOptions.frames, scriptedFrame,
                                     f.dt, mFrameTimes);
    // One line a frame at debug level, once swapped: the GUI end-to-end tests wait on frames shown (frames
    // take seconds on llvmpipe).
    if (!mOptions.logName.empty()) {
      log::debug("{}: frame {} shown{}", mOptions.logName, shown, mFrameNote);
      if (shown == 0) {
        log::info("{}: first frame shown after {:.1f} s", mOptions.logName,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - mStartup).count());
      }
    }
    ++shown;
    if (last) {
      break;
    }
  }
}

} // namespace sylva::ui

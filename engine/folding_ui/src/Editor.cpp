// `sylva fold edit`: The editor's lifecycle: opening and creating projects, background synthesis, refreshing
// the GPU copy, saving, undo and the frame loop.
#include "internal/Editor.hpp"

namespace sylva::folding_ui {

const ToolInfo& info(ToolKind kind) {
  return kTools[static_cast<std::size_t>(kind)];
}

void arrow(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 colour, float thickness) {
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

fs::path defaultProjectFile(const fs::path& image) {
  return image.parent_path() / (image.stem().string() + ".fold.json");
}

FoldEditor::FoldEditor(const EditorOptions& o)
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

void FoldEditor::openProject(const fs::path& file, bool recover) {
  std::string notice;
  std::unique_ptr<Session> s = Session::open(file, recover, &notice);
  adopt(std::move(s));
  mRecent.add(mSession->file());
  mRecent.save();
  setStatus(notice.empty() ? "opened " + mSession->file().string() : notice, false);
}

void FoldEditor::newProject(const std::vector<fs::path>& images, const fs::path& file) {
  adopt(Session::fromImages(images, file));
  setStatus(fmt::format("new project {} (unsaved): draw a zone with R", mSession->file().filename().string()),
            false);
}

void FoldEditor::cancelBackground() {
  if (mJob) {
    mJob->progress->cancel();
    mJob->result.wait();
    mJob.reset();
  }
}

void FoldEditor::adopt(std::unique_ptr<Session> session) {
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

bool FoldEditor::backgroundBusy() {
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

bool FoldEditor::startBackground() {
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

void FoldEditor::refresh(std::optional<Rect> hint) {
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
        mRenderer.upload(*mSession->textures(), mSession->project().profiles, mSession->project().jumpLayers);
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

void FoldEditor::synthesizeNow() {
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

void FoldEditor::save() {
  if (!mSession) {
    return;
  }
  if (edit([&] { mSession->save(); })) {
    mRecent.add(mSession->file());
    mRecent.save();
    setStatus("saved " + mSession->file().filename().string(), false);
  }
}

void FoldEditor::undo() {
  if (mSession && mSession->history().canUndo()) {
    const EditHistory::Change c = mSession->history().undo();
    clampSelection();
    setStatus("undo: " + c.name, false);
  }
}

void FoldEditor::redo() {
  if (mSession && mSession->history().canRedo()) {
    const EditHistory::Change c = mSession->history().redo();
    clampSelection();
    setStatus("redo: " + c.name, false);
  }
}

void FoldEditor::deleteSelectedZone() {
  if (mZone < 0) {
    return;
  }
  const std::string id = mSession->project().zones[static_cast<std::size_t>(mZone)].id;
  if (edit([&] { removeZone(mSession->history(), mZone); })) {
    mZone = -1;
    setStatus("deleted zone '" + id + "' (Ctrl+Z brings it back)", false);
  }
}

void FoldEditor::updateTitleAndSelection() {
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

void FoldEditor::clampSelection() {
  const int zones = static_cast<int>(mSession->project().zones.size());
  if (mZone >= zones) {
    mZone = zones - 1;
  }
  mProfile = std::clamp(mProfile, 0, static_cast<int>(mSession->project().profiles.size()) - 1);
}

void FoldEditor::setStatus(const std::string& text, bool error) {
  mStatus = text;
  mStatusError = error;
  if (error) {
    log::warn("{}", text);
  } else {
    log::info("{}", text);
  }
}

std::string FoldEditor::timing(double ms) const {
  return mShell.clock().fixed() ? "- ms" : fmt::format("{:.1f} ms", ms);
}

void FoldEditor::replaceTexture(gl::Texture& slot, gl::Texture fresh) {
  mRetired.push_back(std::move(slot));
  slot = std::move(fresh);
}

void FoldEditor::retireImageTextures() {
  for (gl::Texture& t : mImageTextures) {
    mRetired.push_back(std::move(t));
  }
  mImageTextures.clear();
}

ui::ShellOptions FoldEditor::shellOptions(const EditorOptions& o) {
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

void FoldEditor::run() {
  ImGui::GetStyle().WindowRounding = 0.0f;
  mShell.run([this](const ui::ShellFrame& f) {
    if (mPlaying) {
      mTime += f.dt * mSpeed;
    }
    mRetired.clear(); // last frame's draw lists are rendered: their old textures can go
    updateTitleAndSelection();
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

void runEditor(const EditorOptions& options) {
  FoldEditor editor(options);
  editor.run();
}

} // namespace sylva::folding_ui

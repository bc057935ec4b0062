// `sylva fold edit`: The window around the canvas: menu bar, workflow bar, toolbox, status bar, start screen
// and help.
#include "internal/Editor.hpp"

namespace sylva::folding_ui {

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
  ImGui::TextWrapped( // wrapped: as one line it ran past the window's right edge and was cut off
      "Ctrl+Z / Ctrl+Y undo/redo, Ctrl+S save, Ctrl+O open, Ctrl+N new, Ctrl+E edit image "
      "externally, Ctrl+Enter synthesise, Space play/pause, Home fit, +/- zoom, 1 actual pixels, "
      "G pixel snapping, Alt no snapping, Del delete zone, Enter finish, Esc cancel; wheel zooms "
      "around the cursor, right/middle drag pans.");
  ImGui::End();
}

} // namespace sylva::folding_ui

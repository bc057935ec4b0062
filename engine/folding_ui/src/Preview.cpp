// `sylva fold edit`: The live GPU preview with its timeline, and the reference-video (optical flow) window.
#include "internal/Editor.hpp"

namespace sylva::folding_ui {

void FoldEditor::drawPreview(ImVec2 pos, ImVec2 size) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::Begin("Preview", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  const Project& p = mSession->project();
  const double period = loopPeriod(p.profiles).seconds;
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

} // namespace sylva::folding_ui

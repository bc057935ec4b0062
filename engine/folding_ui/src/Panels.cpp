// `sylva fold edit`: The right-hand panels: zone properties, the jump tree and the profile editor.
#include "internal/Editor.hpp"

namespace sylva::folding_ui {

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

} // namespace sylva::folding_ui

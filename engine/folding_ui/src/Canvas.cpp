// `sylva fold edit`: The canvas screen: the image on ui::ImageCanvas, its image tabs and the overlays (zones,
// anchors, vectors, heat maps, freeze masks).
#include "internal/Editor.hpp"

namespace sylva::folding_ui {

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

} // namespace sylva::folding_ui

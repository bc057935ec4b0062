// `sylva fold edit`: Input: keyboard shortcuts, tool selection and the canvas gestures of every tool (clicks,
// drags, the freeze brush).
#include "internal/Editor.hpp"

#include <sylva/core/Log.hpp>

namespace sylva::folding_ui {

void FoldEditor::onKey(int key, int mods) {
  // F1 from the key event, not by polling its state once a frame: a tap shorter than a frame (most taps on a
  // slow renderer) was missed.
  if (key == GLFW_KEY_F1) {
    mShowHelp = !mShowHelp;
    return;
  }
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

void FoldEditor::selectTool(ToolKind tool) {
  mTool = tool;
  mClicks.clear();
  mGesture = {};
  if (tool == ToolKind::Mask) {
    prompt(PathPrompt::Action::MaskImport, "Alpha mask image for the selected zone's folding");
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
    if (g.handle) {
      // Where a drag ended, for the log (the GUI tests print it when a saved project differs).
      log::info("select: handle of zone {} dragged from ({:.1f}, {:.1f}) to ({:.1f}, {:.1f})", g.handle->zone,
                g.start.x, g.start.y, g.handleLast.x, g.handleLast.y);
    }
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

} // namespace sylva::folding_ui

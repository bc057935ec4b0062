// Draggable points of a project (the editor's select/move tool, snapping targets).
#include <sylva/folding/Handles.hpp>

#include <glm/geometric.hpp>

#include <stdexcept>

namespace sylva::folding {

namespace {

template <typename T> T& at(std::vector<T>& v, int i) {
  return v.at(static_cast<std::size_t>(i));
}

struct HandleCollector {
  int zone;
  std::vector<Handle>& out;
  void add(Handle::Kind kind, int tool, int index, Vec2 pos) {
    out.push_back({kind, zone, tool, index, pos});
  }
};

} // namespace

std::vector<Handle> zoneHandles(const Project& project, int zone) {
  std::vector<Handle> out;
  const Zone& z = project.zones.at(static_cast<std::size_t>(zone));
  HandleCollector c{zone, out};
  const std::vector<Vec2> outline = z.shape.outline();
  for (std::size_t i = 0; i < outline.size(); ++i) {
    c.add(Handle::Kind::ZoneVertex, -1, static_cast<int>(i), outline[i]);
  }
  for (std::size_t t = 0; t < z.tools.size(); ++t) {
    const int ti = static_cast<int>(t);
    const Tool& tool = z.tools[t];
    if (const auto* points = std::get_if<PointsTool>(&tool)) {
      for (std::size_t i = 0; i < points->pairs.size(); ++i) {
        c.add(Handle::Kind::PointFrom, ti, static_cast<int>(i), points->pairs[i][0]);
        c.add(Handle::Kind::PointTo, ti, static_cast<int>(i), points->pairs[i][1]);
      }
    } else if (const auto* curve = std::get_if<CurveTool>(&tool)) {
      for (int i = 0; i < 4; ++i) {
        c.add(Handle::Kind::CurveSource, ti, i, curve->source[static_cast<std::size_t>(i)]);
      }
      if (curve->dest) {
        for (int i = 0; i < 4; ++i) {
          c.add(Handle::Kind::CurveDest, ti, i, (*curve->dest)[static_cast<std::size_t>(i)]);
        }
      }
    } else if (const auto* lasso = std::get_if<LassoTool>(&tool)) {
      for (std::size_t i = 0; i < lasso->from.size(); ++i) {
        c.add(Handle::Kind::LassoFrom, ti, static_cast<int>(i), lasso->from[i]);
        c.add(Handle::Kind::LassoTo, ti, static_cast<int>(i), lasso->to[i]);
      }
    } else if (const auto* zero = std::get_if<ZeroTool>(&tool)) {
      for (std::size_t i = 0; i < zero->pts.size(); ++i) {
        c.add(Handle::Kind::ZeroPoint, ti, static_cast<int>(i), zero->pts[i]);
      }
    } else if (const auto* scale = std::get_if<ScaleTool>(&tool)) {
      c.add(Handle::Kind::ScaleCentre, ti, 0, scale->centre);
    }
  }
  for (std::size_t f = 0; f < z.folding.polygons.size(); ++f) {
    for (std::size_t i = 0; i < z.folding.polygons[f].size(); ++i) {
      c.add(Handle::Kind::FoldVertex, static_cast<int>(f), static_cast<int>(i), z.folding.polygons[f][i]);
    }
  }
  return out;
}

std::vector<Handle> imageHandles(const Project& project, const std::string& image) {
  std::vector<Handle> out;
  for (std::size_t z = 0; z < project.zones.size(); ++z) {
    if (project.zones[z].image == image) {
      const std::vector<Handle> h = zoneHandles(project, static_cast<int>(z));
      out.insert(out.end(), h.begin(), h.end());
    }
  }
  return out;
}

void setHandle(Project& project, const Handle& h, Vec2 position) {
  Zone& z = at(project.zones, h.zone);
  auto tool = [&]() -> Tool& { return at(z.tools, h.tool); };
  auto wrong = [] { throw std::out_of_range("handle: tool type changed"); };
  switch (h.kind) {
  case Handle::Kind::ZoneVertex:
    if (z.shape.type == Shape::Type::Rect) {
      // Corners as Shape::outline(): moving one keeps the rectangle axis-aligned against the opposite one.
      const std::vector<Vec2> corners = z.shape.outline();
      const Vec2 opposite = corners.at(static_cast<std::size_t>((h.index + 2) % 4));
      z.shape.min = glm::min(opposite, position);
      z.shape.max = glm::max(opposite, position);
    } else {
      at(z.shape.pts, h.index) = position;
    }
    return;
  case Handle::Kind::PointFrom:
  case Handle::Kind::PointTo: {
    auto* points = std::get_if<PointsTool>(&tool());
    if (!points) {
      wrong();
    }
    at(points->pairs, h.index)[h.kind == Handle::Kind::PointFrom ? 0 : 1] = position;
    return;
  }
  case Handle::Kind::CurveSource:
  case Handle::Kind::CurveDest: {
    auto* curve = std::get_if<CurveTool>(&tool());
    if (!curve || (h.kind == Handle::Kind::CurveDest && !curve->dest)) {
      wrong();
    }
    auto& ctrl = h.kind == Handle::Kind::CurveSource ? curve->source : *curve->dest;
    ctrl.at(static_cast<std::size_t>(h.index)) = position;
    return;
  }
  case Handle::Kind::LassoFrom:
  case Handle::Kind::LassoTo: {
    auto* lasso = std::get_if<LassoTool>(&tool());
    if (!lasso) {
      wrong();
    }
    at(h.kind == Handle::Kind::LassoFrom ? lasso->from : lasso->to, h.index) = position;
    return;
  }
  case Handle::Kind::ZeroPoint: {
    auto* zero = std::get_if<ZeroTool>(&tool());
    if (!zero) {
      wrong();
    }
    at(zero->pts, h.index) = position;
    return;
  }
  case Handle::Kind::ScaleCentre: {
    auto* scale = std::get_if<ScaleTool>(&tool());
    if (!scale) {
      wrong();
    }
    scale->centre = position;
    return;
  }
  case Handle::Kind::FoldVertex:
    at(at(z.folding.polygons, h.tool), h.index) = position;
    return;
  }
}

void moveHandle(EditHistory& history, const Handle& handle, Vec2 position, bool coalesce) {
  history.apply(
      "move point", handle.zone, [&](Project& p) { setHandle(p, handle, position); }, coalesce);
}

std::optional<Handle> nearestHandle(const std::vector<Handle>& handles, Vec2 p, double maxDistance) {
  std::optional<Handle> best;
  double bestDistance = maxDistance;
  for (const Handle& h : handles) {
    const double d = glm::distance(h.pos, p);
    if (d <= bestDistance) {
      bestDistance = d;
      best = h;
    }
  }
  return best;
}

} // namespace sylva::folding

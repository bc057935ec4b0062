#include <sylva/terrain/gpu/TerrainPopping.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <tuple>
#include <vector>

namespace sylva::terrain {

double changedPixelFraction(const Image& a, const Image& b, float threshold) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() < 3 || b.channels() < 3) {
    fail("changedPixelFraction: images differ in size ({}x{} vs {}x{}) or have < 3 channels", a.width(),
         a.height(), b.width(), b.height());
  }
  std::size_t changed = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      bool differs = false;
      for (int c = 0; c < 3; ++c) {
        differs = differs || std::abs(a.get(x, y, c) - b.get(x, y, c)) > threshold;
      }
      changed += differs ? 1 : 0;
    }
  }
  return static_cast<double>(changed) / (static_cast<double>(a.width()) * a.height());
}

int changedLeaves(const QuadtreeSelection& a, const QuadtreeSelection& b) {
  const auto keys = [](const QuadtreeSelection& s) {
    std::vector<std::tuple<int, int, int>> out;
    out.reserve(s.nodes.size());
    for (const SelectedNode& n : s.nodes) {
      out.emplace_back(n.level, n.gridX, n.gridZ);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto ka = keys(a);
  const auto kb = keys(b);
  std::vector<std::tuple<int, int, int>> diff;
  std::set_symmetric_difference(ka.begin(), ka.end(), kb.begin(), kb.end(), std::back_inserter(diff));
  return static_cast<int>(diff.size());
}

CameraStepChange measureCameraStep(TerrainRenderer& renderer, Quadtree& quadtree,
                                   render::RenderTarget& target, const render::Camera& from,
                                   const render::Camera& to, const TerrainDrawOptions& options,
                                   const glm::vec4& clear) {
  const auto select = [&](const render::Camera& camera) {
    const Frustum frustum = camera.frustum(target.aspect());
    return quadtree.select(camera.position, &frustum);
  };
  const auto render = [&](const QuadtreeSelection& selection, const render::Camera& camera) {
    target.begin(clear);
    renderer.draw(selection, camera, target.width(), target.height(), 0.0, nullptr, options);
    return target.readColor();
  };
  const QuadtreeSelection a = select(from);
  const QuadtreeSelection b = select(to);
  const Image first = render(a, from);
  CameraStepChange out;
  out.across = changedPixelFraction(first, render(b, to));
  out.inside = changedPixelFraction(first, render(a, to));
  out.leavesChanged =
      changedLeaves(quadtree.select(from.position, nullptr), quadtree.select(to.position, nullptr));
  return out;
}

} // namespace sylva::terrain

// Height queries over a DEM with no GL: loads a height file (GeoTIFF, NumPy .npy/.npz, PNG or EXR with their
// sidecar, …), prints its grid and height range, the ground height and normal at a few points, and where a
// ray cast down from above meets the ground.
//
//   height_query DEM [X Z]...
//
// X and Z are world metres from the DEM's first sample (x east, z south, y up); without them the queries are
// the centre and the four points halfway to the corners.
#include <sylva/core/Error.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/HeightSources.hpp>

#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include <glm/vec2.hpp>

int main(int argc, char** argv) {
  namespace terrain = sylva::terrain;
  if (argc < 2 || argc % 2 != 0) {
    std::fprintf(stderr, "usage: height_query DEM [X Z]...\n");
    return 2;
  }
  try {
    const terrain::HeightField field = terrain::loadHeightField(argv[1]);
    const terrain::HeightFieldInfo info = terrain::heightFieldInfo(field);
    std::printf("%s: %d x %d samples, %.3g x %.3g m apart, %.1f x %.1f m, heights %.2f to %.2f m\n", argv[1],
                field.width(), field.height(), field.spacingX(), field.spacingZ(), field.extentX(),
                field.extentZ(), info.minHeight, info.maxHeight);

    std::vector<glm::vec2> points;
    for (int i = 2; i + 1 < argc; i += 2) {
      points.emplace_back(std::strtof(argv[i], nullptr), std::strtof(argv[i + 1], nullptr));
    }
    if (points.empty()) {
      const glm::vec2 size(field.extentX(), field.extentZ());
      for (const glm::vec2 f : {glm::vec2(0.5f), glm::vec2(0.25f), glm::vec2(0.75f, 0.25f),
                                glm::vec2(0.25f, 0.75f), glm::vec2(0.75f)}) {
        points.push_back(f * size);
      }
    }

    std::printf("%10s %10s %10s %10s %24s %12s\n", "x (m)", "z (m)", "bilinear", "bicubic", "normal",
                "ray hit y");
    for (const glm::vec2 p : points) {
      const float bilinear = terrain::heightAt(field, p.x, p.y);
      const float bicubic = terrain::heightAt(field, p.x, p.y, terrain::Interpolation::Bicubic);
      const glm::vec3 n = terrain::normalAt(field, p.x, p.y);
      // A ray straight down from 100 m above the highest sample: it meets the ground at the bilinear height.
      const glm::vec3 origin(p.x, info.maxHeight + 100.0f, p.y);
      const auto hit = terrain::raycast(field, origin, glm::vec3(0.0f, -1.0f, 0.0f), 1.0e6f);
      std::printf("%10.2f %10.2f %10.3f %10.3f   (%6.3f, %6.3f, %6.3f) %12.3f\n", p.x, p.y, bilinear, bicubic,
                  n.x, n.y, n.z, hit ? hit->position.y : std::numeric_limits<float>::quiet_NaN());
    }
    return 0;
  } catch (const sylva::Error& e) {
    std::fprintf(stderr, "height_query: %s\n", e.what());
    return 1;
  }
}

#include <sylva/terrain/TerrainSetup.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Limits.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::terrain {
ProceduralSpec TerrainSource::defaultProcedural() {
  return defaultLandscapeSpec();
}

HeightField loadTerrainSource(const TerrainSource& source, const LoadOptions* limits, LoadReport* report) {
  if (!source.dem.empty()) {
    return loadHeightField(source.dem, limits != nullptr ? *limits : source.load, report);
  }
  if (report != nullptr) {
    *report = LoadReport{};
    report->units = "metres";
    report->reason = fmt::format("procedural, --spacing {:g} m", source.proceduralSpacing);
    report->orientation = "row 0 is north";
  }
  const int size = source.proceduralSize;
  const int height = source.rows();
  const float spacing = source.proceduralSpacing;
  const std::size_t samples = static_cast<std::size_t>(size) * static_cast<std::size_t>(height);
  if (samples <= kProgressSamples) {
    return generate(source.procedural, 0.0, 0.0, size, height, spacing);
  }
  // Strips whose origin lies on the sample lattice give bit-identical heights to one generate() call (see
  // generate), so a large field can report progress without changing a single sample.
  HeightField field(size, height, spacing, spacing);
  const int strip = std::max(1, static_cast<int>(kProgressSamples / 4 / static_cast<std::size_t>(size)));
  Progress progress("generating heights", static_cast<std::size_t>(height));
  for (int row = 0; row < height; row += strip) {
    if (progress.cancelled()) {
      fail("generating heights: cancelled");
    }
    const int rows = std::min(strip, height - row);
    const HeightField part = generate(
        source.procedural, 0.0, static_cast<double>(row) * static_cast<double>(spacing), size, rows, spacing);
    std::copy(part.samples().begin(), part.samples().end(),
              field.samples().begin() + static_cast<std::ptrdiff_t>(row) * size);
    progress.advance(static_cast<std::size_t>(rows));
  }
  return field;
}

std::optional<float> SeaLevelRule::resolve(float minHeight) const {
  switch (kind) {
  case Kind::Auto:
    return minHeight < 0.0f ? std::optional<float>(0.0f) : std::nullopt;
  case Kind::None:
    return std::nullopt;
  case Kind::Metres:
    return metres;
  }
  return std::nullopt;
}

QuadtreeConfig TerrainSetup::defaultQuadtree() {
  QuadtreeConfig config;
  config.rootSize = 512.0f;
  config.maxDepth = 5;
  config.lodDistanceFactor = 2.0f;
  config.patchTessLevel = 16;
  return config;
}

QuadtreeConfig quadtreeFor(const TerrainSetup& setup, const HeightField& field,
                           const TerrainFieldName& name) {
  QuadtreeConfig config = setup.quadtree;
  if (config.patchTessLevel < 1 || config.patchTessLevel > kMaxPatchTessLevel) {
    fail("{}: {} is not in [1, {}]", fieldName(name, "tess_level"), config.patchTessLevel,
         kMaxPatchTessLevel);
  }
  if (!(config.lodDistanceFactor >= kMinRestrictedLodFactor && config.lodDistanceFactor <= 64.0f)) {
    fail("{}: {} is not in [{}, 64]", fieldName(name, "lod_factor"), config.lodDistanceFactor,
         kMinRestrictedLodFactor);
  }
  if (!(config.lodErrorPixels >= 0.0f && config.lodErrorPixels <= 1000.0f)) {
    fail("{}: {} is not in [0, 1000] pixels", fieldName(name, "lod_error"), config.lodErrorPixels);
  }
  if (setup.roots < 0 || setup.roots > 4096) {
    fail("{}: {} is not in [0, 4096]", fieldName(name, "roots"), setup.roots);
  }
  if (setup.maxDepth && (*setup.maxDepth < 0 || *setup.maxDepth > 16)) {
    fail("{}: {} is not in [0, 16]", fieldName(name, "max_depth"), *setup.maxDepth);
  }
  if (setup.roots > 0) {
    const QuadtreeConfig layout = QuadtreeConfig::forRootCount(setup.roots, field.extentX(), field.extentZ());
    config.rootsX = layout.rootsX;
    config.rootsZ = layout.rootsZ;
    config.rootSize = layout.rootSize;
  } else {
    // Four roots across the longer side, whatever the terrain's size (the demo's 2048 m gives 512 m roots).
    config.rootSize = 0.25f * std::max(field.extentX(), field.extentZ());
  }
  if (setup.maxDepth) {
    config.maxDepth = *setup.maxDepth;
  } else {
    // Deep enough that the finest leaves put two tessellated vertices per height sample, and no deeper: finer
    // leaves would only interpolate (the demo: 512 m roots, 2 m samples, level 16 → depth 5, 16 m leaves).
    const float spacing = std::min(field.spacingX(), field.spacingZ());
    const float leaf = 0.5f * spacing * static_cast<float>(config.patchTessLevel);
    config.maxDepth = std::clamp(static_cast<int>(std::round(std::log2(config.rootSize / leaf))), 0, 12);
  }
  return config;
}

std::size_t affordableSamples() {
  // Unknown available memory (not Linux) = no limit beyond the loader's own.
  const std::optional<std::size_t> bytes = availableMemoryBytes();
  return bytes ? std::max<std::size_t>(4, *bytes / kRenderBytesPerSample) : kMaxHeightFieldSamples;
}

void checkMemoryFor(std::size_t samples, const std::string& what) {
  const std::size_t affordable = affordableSamples();
  if (samples > affordable) {
    fail("{}: {} samples need about {:.1f} GiB to render ({} bytes each: heights, GPU textures), {:.1f} GiB "
         "is available",
         what, samples, static_cast<double>(samples) * kRenderBytesPerSample / (1u << 30),
         kRenderBytesPerSample, static_cast<double>(affordable) * kRenderBytesPerSample / (1u << 30));
  }
}

LoadedTerrain loadTerrainSetup(const TerrainSetup& setup, const TerrainFieldName& name, int maxSide,
                               const std::string& maxSideReason) {
  const auto field = [&name](std::string_view f) { return fieldName(name, f); };
  if (!(setup.exaggeration > 0.0f && setup.exaggeration <= 1000.0f)) {
    fail("{}: {} is not in (0, 1000]", field("exaggeration"), setup.exaggeration);
  }
  if (setup.seaLevel.kind == SeaLevelRule::Kind::Metres &&
      !(std::isfinite(setup.seaLevel.metres) && std::abs(setup.seaLevel.metres) <= 1.0e5f)) {
    fail("{}: {} is not in [-100000, 100000] metres", field("sea_level"), setup.seaLevel.metres);
  }
  LoadedTerrain loaded;
  if (!setup.layersFile.empty()) {
    loaded.layers = loadSplatLayers(setup.layersFile); // before the heights: a bad rules file costs nothing
  }
  // Limits known before any work: the largest side, and memory for a procedural field.
  const TerrainSource& source = setup.source;
  if (source.dem.empty()) {
    if (maxSide > 0 && std::max(source.proceduralSize, source.rows()) > maxSide) {
      fail("{} {}: too large ({}); use {} or less", field("size"),
           std::max(source.proceduralSize, source.rows()), maxSideReason, maxSide);
    }
    validate(source.procedural, field("relief"));
    checkMemoryFor(static_cast<std::size_t>(source.proceduralSize) * static_cast<std::size_t>(source.rows()),
                   field("size"));
  }
  LoadOptions limits = source.load;
  if (maxSide > 0) {
    limits.maxSide = maxSide;
    limits.maxSideReason = maxSideReason;
  }
  limits.maxSamples = std::min(limits.maxSamples, affordableSamples());
  loaded.heights = loadTerrainSource(source, &limits);
  const HeightFieldInfo info = heightFieldInfo(loaded.heights);
  loaded.seaLevel = setup.seaLevel.resolve(info.minHeight);
  const float relief = info.maxHeight - info.minHeight;
  const float extent = std::max(loaded.heights.extentX(), loaded.heights.extentZ());
  if (setup.exaggeration == 1.0f && relief > 0.0f && relief < 0.002f * extent) {
    log::info("relief {:.0f} m is {:.2g} % of the {:.0f} km extent and will look flat; try {} {:.0f}", relief,
              100.0 * relief / extent, extent / 1000.0, field("exaggeration"),
              std::ceil(0.02f * extent / relief));
  }
  loaded.config = quadtreeFor(setup, loaded.heights, name);
  return loaded;
}

} // namespace sylva::terrain

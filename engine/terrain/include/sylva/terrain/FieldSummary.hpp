#pragma once
// What `sylva terrain info` says about a height field: its size, spacing, units, extent, height range, absent
// samples and the default 16-root quadtree over it, as text or JSON.

#include <sylva/terrain/HeightSources.hpp>

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace sylva::terrain {

/**
 * The summary of `field` as loaded (`report`: horizontal units, orientation, warnings) from `source` (how
 * the source is described to the user), one "name  value" line each, ending in '\n'.
 */
std::string describeHeightField(const HeightField& field, const LoadReport& report,
                                const std::string& source);

/**
 * The same as JSON: source, width, height, spacingX/Z, extentX/Z (metres), min/maxHeight,
 * valid/absentSamples, horizontalUnits(+Reason), orientation, warnings, quadtree {roots, rootsX/Z, rootSize,
 * maxDepth, leafSize, minMaxBytes}, and for fields in degrees latitude {centre, south, north, eastWestError}.
 */
nlohmann::json describeHeightFieldJson(const HeightField& field, const LoadReport& report,
                                       const std::string& source);

} // namespace sylva::terrain

#pragma once

// Height-source options shared by every command that needs a terrain (`sylva terrain ...`, render, view,
// bench): one parser, one set of checks, one loader.

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/TerrainSetup.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace sylva::app {

/** Largest side of a procedural field: kMaxHeightFieldSamples (2^30) samples in a square. */
constexpr int kMaxProceduralSize = 32768;
/** Largest accepted sample spacing, metres (100 km per sample is already far beyond any DEM). */
constexpr double kMaxSpacing = 1.0e5;
/** Smallest accepted sample spacing, metres. */
constexpr double kMinSpacing = 1.0e-6;
/** Largest accepted height scale (procedural or PNG), metres. */
constexpr double kMaxHeightScale = 1.0e5;

/** The comma-separated items of "a,b,c" (an empty item where two commas meet or at either end). */
inline std::vector<std::string> commaItems(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    items.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

/** Parses "a,b,c" into exactly `count` finite numbers; throws naming the option. */
inline std::vector<float> parseNumbers(const std::string& option, const std::string& text, std::size_t count,
                                       const char* shape) {
  std::vector<float> values;
  for (const std::string& item : commaItems(text)) {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(value) || std::abs(value) > 3.0e38) {
      fail("{}: expected {} ({} finite numbers), got '{}'", option, shape, count, text);
    }
    values.push_back(static_cast<float>(value));
  }
  if (values.size() != count) {
    fail("{}: expected {} ({} finite numbers), got '{}'", option, shape, count, text);
  }
  return values;
}

/**
 * Parses "a,b,c" into whole numbers in [lo, hi] (`what` names one: "a tessellation level"); throws naming the
 * option, the text and the item at fault.
 */
inline std::vector<int> parseIntegers(const std::string& option, const std::string& text, long lo, long hi,
                                      const char* what) {
  std::vector<int> values;
  for (const std::string& item : commaItems(text)) {
    char* end = nullptr;
    const long value = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || end == nullptr || *end != '\0' || value < lo || value > hi) {
      fail("{} {}: '{}' is not {} in [{}, {}]", option, text, item, what, lo, hi);
    }
    values.push_back(static_cast<int>(value));
  }
  return values;
}

/** A CLI11 check: a finite number in [lo, hi]; CLI11 prefixes the message with the option name. */
inline CLI::Validator finiteRange(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end == nullptr || *end != '\0' || !std::isfinite(value) || value < lo ||
            value > hi) {
          return fmt::format("'{}' is not a finite number in [{:g}, {:g}]", text, lo, hi);
        }
        return {};
      },
      fmt::format("FLOAT in [{:g}, {:g}]", lo, hi));
}

/**
 * A CLI11 check: a whole number in [0, 2^64 - 1] written with digits only (no sign, which would wrap, and no
 * value CLI11 would clamp silently).
 */
inline CLI::Validator unsignedInteger() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty() ||
            !std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) {
          return fmt::format("'{}' is not a whole number >= 0", text);
        }
        errno = 0;
        (void)std::strtoull(text.c_str(), nullptr, 10);
        if (errno == ERANGE) {
          return fmt::format("'{}' is larger than 18446744073709551615 (2^64 - 1)", text);
        }
        return {};
      },
      "UINT");
}

/**
 * --dem FILE or --seed N / --spec FILE, with the procedural parameters (--type, --size, --spacing,
 * --height-scale) and DEM reading options (--png-scale, --npz-array). load() checks the combination and
 * throws sylva::Error naming the option or file.
 */
struct SourceOptions {
  /**
   * The default landscape (terrain::defaultLandscapeSpec on the default grid), as `render` uses: the same
   * --seed gives the same heights in every command. A height source must be given.
   */
  SourceOptions();
  /** Defaults from `spec` and a size × size field at `spacing` metres (render/view/bench use the demo). */
  SourceOptions(const terrain::ProceduralSpec& spec, int size, float spacing);

  std::string dem;
  std::uint64_t seed = 7;
  std::string type = "warped";
  int size = terrain::kDefaultProceduralSize;
  float spacing = terrain::kDefaultProceduralSpacing;
  float heightScale = 400.0f;
  /** When neither --dem nor --seed/--spec is given: true = use the defaults above; false = an error. */
  bool defaultToProcedural = false;
  /** Procedural parameters not exposed as options (octaves, frequency, ...), from the defaults' spec. */
  terrain::ProceduralSpec base;
  std::string spec;
  float pngScale = 100.0f;
  std::string npzArray;
  bool geographic = false;
  bool flipY = false;

  CLI::Option* demOption = nullptr;
  CLI::Option* seedOption = nullptr;
  CLI::Option* typeOption = nullptr;
  CLI::Option* sizeOption = nullptr;
  CLI::Option* spacingOption = nullptr;
  CLI::Option* heightScaleOption = nullptr;
  CLI::Option* specOption = nullptr;
  CLI::Option* pngScaleOption = nullptr;
  CLI::Option* npzArrayOption = nullptr;
  CLI::Option* geographicOption = nullptr;
  CLI::Option* flipYOption = nullptr;

  void add(CLI::App& command) {
    demOption = command.add_option("--dem", dem,
                                   "Height source: a DEM file (.png/.exr with optional .json sidecar, .npy, "
                                   ".npz, or any GDAL raster such as GeoTIFF)");
    seedOption = command.add_option("--seed", seed, "Height source: procedural noise with this seed")
                     ->check(unsignedInteger());
    specOption = command.add_option("--spec", spec,
                                    "Procedural spec JSON (version 1: seed, type, octaves, frequency, "
                                    "lacunarity, gain, warpStrength, heightScale); --seed, --type and "
                                    "--height-scale override its fields");
    typeOption = command.add_option("--type", type, "Procedural noise: fbm, ridged or warped")
                     ->check(CLI::IsMember({"fbm", "ridged", "warped"}))
                     ->capture_default_str();
    sizeOption = command.add_option("--size", size, "Procedural field side, samples")
                     ->check(CLI::Range(2, kMaxProceduralSize))
                     ->capture_default_str();
    spacingOption = command
                        .add_option("--spacing", spacing,
                                    "Metres between samples (procedural; with --dem it overrides the "
                                    "file's spacing)")
                        ->check(finiteRange(kMinSpacing, kMaxSpacing))
                        ->capture_default_str();
    heightScaleOption =
        command
            .add_option("--height-scale", heightScale,
                        "Procedural height of noise value 1, metres (heights lie in [0, scale])")
            ->check(finiteRange(kMinSpacing, kMaxHeightScale))
            ->capture_default_str();
    pngScaleOption =
        command
            .add_option("--png-scale", pngScale, "Metres of the value 1.0 of a PNG DEM without .json sidecar")
            ->check(finiteRange(kMinSpacing, kMaxHeightScale))
            ->capture_default_str();
    npzArrayOption =
        command.add_option("--npz-array", npzArray, "Array inside an .npz DEM (default: the first 2D array)");
    geographicOption = command.add_flag(
        "--geographic", geographic,
        "The DEM's coordinates are longitude/latitude degrees, whatever the file says (converted to metres "
        "at the centre latitude; see docs/terrain-data.md)");
    flipYOption =
        command.add_flag("--flip-y", flipY,
                         "Reverse the DEM's rows after reading (when its coordinates are missing or "
                         "wrong about which edge is north)");
  }

  /** True when the heights come from the generator (--seed/--spec, or no --dem with defaultToProcedural). */
  bool procedural() const {
    return seedOption->count() > 0 || specOption->count() > 0 ||
           (defaultToProcedural && demOption->count() == 0);
  }

  /** Throws sylva::Error naming the option when the combination of source options is wrong. */
  void check() const {
    if (demOption->count() > 0 && procedural()) {
      fail("--dem and {}: give one height source, not both", seedOption->count() > 0 ? "--seed" : "--spec");
    }
    if (demOption->count() == 0 && !procedural()) {
      fail("no height source: give --dem FILE or --seed N (see --help)");
    }
    if (demOption->count() > 0) {
      for (const CLI::Option* option : {typeOption, sizeOption, heightScaleOption}) {
        if (option->count() > 0) {
          fail("{}: applies to procedural sources (--seed/--spec) only, not to --dem", option->get_name());
        }
      }
      if (dem.empty()) {
        fail("--dem: empty file name");
      }
    } else {
      for (const CLI::Option* option : {pngScaleOption, npzArrayOption, geographicOption, flipYOption}) {
        if (option->count() > 0) {
          fail("{}: applies to --dem only", option->get_name());
        }
      }
    }
  }

  /** The procedural spec: --spec file (if any) with --seed/--type/--height-scale overrides. */
  terrain::ProceduralSpec proceduralSpec() const {
    terrain::ProceduralSpec result = base;
    if (specOption->count() > 0) {
      result = terrain::loadProceduralSpec(spec);
    }
    if (seedOption->count() > 0 || specOption->count() == 0) {
      result.seed = seed;
    }
    if (typeOption->count() > 0 || specOption->count() == 0) {
      result.type = type == "ridged"   ? terrain::ProceduralSpec::Type::Ridged
                    : type == "warped" ? terrain::ProceduralSpec::Type::Warped
                                       : terrain::ProceduralSpec::Type::Fbm;
    }
    if (heightScaleOption->count() > 0 || specOption->count() == 0) {
      result.heightScale = heightScale;
    }
    terrain::validate(result, specOption->count() > 0 ? spec : std::string("procedural spec"));
    return result;
  }

  /** One line naming the source, for summaries. */
  std::string describe() const {
    if (!procedural()) {
      return dem;
    }
    const terrain::ProceduralSpec s = proceduralSpec();
    return fmt::format("procedural {} seed {} ({}x{} samples, {:g} m spacing, height scale {:g} m)",
                       terrain::procedureTypeName(s.type), s.seed, size, size, spacing, s.heightScale);
  }

  /** The DEM reading options (--png-scale, --spacing, --npz-array, --geographic, --flip-y). */
  terrain::LoadOptions loadOptions() const {
    terrain::LoadOptions options;
    options.heightScale = pngScale;
    options.spacing = spacingOption->count() > 0 ? spacing : 0.0f;
    options.npzArray = npzArray;
    options.horizontal = geographic ? terrain::HorizontalUnits::Degrees : terrain::HorizontalUnits::Auto;
    options.flipY = flipY;
    return options;
  }

  /**
   * The height source the options describe (checked: throws sylva::Error naming the option); warns about
   * reading options that do not apply to the DEM's format.
   */
  terrain::TerrainSource terrainSource() const {
    check();
    terrain::TerrainSource source;
    if (!procedural()) {
      if (pngScaleOption->count() > 0 && lowerExtension(dem) != ".png") {
        log::warn("--png-scale {:g}: ignored, {} is not a PNG (only PNG heights are normalised)", pngScale,
                  dem);
      }
      if (npzArrayOption->count() > 0 && lowerExtension(dem) != ".npz") {
        log::warn("--npz-array {}: ignored, {} is not an .npz archive", npzArray, dem);
      }
      source.dem = dem;
      source.load = loadOptions();
      return source;
    }
    source.procedural = proceduralSpec();
    source.proceduralSize = size;
    source.proceduralSpacing = spacing;
    return source;
  }

  /**
   * Loads or generates the height field (terrain::loadTerrainSource); throws sylva::Error naming the file or
   * option. `report` (may be null) receives what the DEM loader assumed; a procedural field reports metres.
   */
  terrain::HeightField load(terrain::LoadReport* report = nullptr,
                            const terrain::LoadOptions* limits = nullptr) const {
    return terrain::loadTerrainSource(terrainSource(), limits, report);
  }
};

inline SourceOptions::SourceOptions()
    : SourceOptions(terrain::defaultLandscapeSpec(), terrain::kDefaultProceduralSize,
                    terrain::kDefaultProceduralSpacing) {
  defaultToProcedural = false;
}

inline SourceOptions::SourceOptions(const terrain::ProceduralSpec& spec, int fieldSize, float fieldSpacing)
    : seed(spec.seed), type(terrain::procedureTypeName(spec.type)), size(fieldSize), spacing(fieldSpacing),
      heightScale(spec.heightScale), defaultToProcedural(true), base(spec) {}

} // namespace sylva::app

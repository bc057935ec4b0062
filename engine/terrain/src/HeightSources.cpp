#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/HeightRaster.hpp>

#include "internal/HeightSourcesInternal.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/JsonNode.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace sylva::terrain {

namespace detail {

void checkHeightFieldSize(const std::filesystem::path& path, long long width, long long height,
                          const LoadOptions& limits) {
  const std::size_t maxSamples = limits.maxSamples;
  if (width > kMaxHeightFieldSide || height > kMaxHeightFieldSide) {
    fail("{}: absurd size {}x{} samples (at most {} per side)", path.string(), width, height,
         kMaxHeightFieldSide);
  }
  if (width < 2 || height < 2) {
    fail("{}: {}x{} samples; a height field needs at least 2x2", path.string(), width, height);
  }
  if (width > limits.maxSide || height > limits.maxSide) {
    fail("{}: {}x{} samples is more than {} per side{}", path.string(), width, height, limits.maxSide,
         limits.maxSideReason.empty() ? "" : " (" + limits.maxSideReason + ")");
  }
  if (static_cast<std::size_t>(width) * static_cast<std::size_t>(height) > maxSamples) {
    fail("{}: absurd size {}x{} samples (at most {} in all)", path.string(), width, height, maxSamples);
  }
}

void finishHeightField(const std::filesystem::path& path, HeightField& field, const LoadOptions& options,
                       LoadReport& report) {
  checkHeightFieldSize(path, field.width(), field.height(), options);
  if (options.spacing > 0.0f) {
    field.setSpacing(options.spacing, options.spacing);
    report.units = "metres";
    report.reason = fmt::format("--spacing {:g} m overrides the file ({})", options.spacing, report.reason);
  }
  if (options.flipY) {
    flipRows(field);
    report.orientation += "; then flipped north-south (--flip-y)";
  }
  const auto usable = [](float s) { return std::isfinite(s) && s > 0.0f; };
  if (!usable(field.spacingX()) || !usable(field.spacingZ())) {
    fail("{}: absurd spacing {} x {} m from the file (must be finite and > 0; set LoadOptions::spacing)",
         path.string(), field.spacingX(), field.spacingZ());
  }
  std::size_t valid = 0;
  for (float& h : field.samples()) {
    if (!std::isfinite(h)) {
      h = std::numeric_limits<float>::quiet_NaN();
    } else {
      ++valid;
    }
  }
  if (valid == 0) {
    fail("{}: all {} samples are absent (nodata, NaN or masked)", path.string(), field.samples().size());
  }
}

void warn(const std::filesystem::path& path, LoadReport& report, const std::string& text) {
  log::warn("{}: {}", path.string(), text);
  report.warnings.push_back(text);
}

void flipRows(HeightField& field) {
  const auto w = static_cast<std::ptrdiff_t>(field.width());
  auto& s = field.samples();
  for (int top = 0, bottom = field.height() - 1; top < bottom; ++top, --bottom) {
    std::swap_ranges(s.begin() + top * w, s.begin() + (top + 1) * w, s.begin() + bottom * w);
  }
}

void flipColumns(HeightField& field) {
  const auto w = static_cast<std::ptrdiff_t>(field.width());
  auto& s = field.samples();
  for (int row = 0; row < field.height(); ++row) {
    std::reverse(s.begin() + row * w, s.begin() + (row + 1) * w);
  }
}

void applyCoordinates(const std::filesystem::path& path, HeightField& field,
                      const FileCoordinates& coordinates, const LoadOptions& options, LoadReport& report) {
  using Kind = FileCoordinates::Kind;
  Kind kind = coordinates.kind;
  std::string reason = coordinates.reason;
  if (options.horizontal == HorizontalUnits::Degrees) {
    if (kind == Kind::None) {
      fail("{}: --geographic: the file holds no coordinates to read as degrees (give --spacing in metres)",
           path.string());
    }
    if (kind == Kind::Metres) {
      warn(path, report, fmt::format("--geographic overrides {}", reason));
    }
    kind = Kind::Degrees;
    reason = fmt::format("--geographic ({})", reason);
  } else if (options.horizontal == HorizontalUnits::Metres && kind != Kind::None) {
    kind = Kind::Metres;
    reason = fmt::format("LoadOptions::horizontal = Metres ({})", reason);
  }
  switch (kind) {
  case Kind::None:
    return; // the loader's default spacing (1 m, or a sidecar's) stands; report keeps "none"
  case Kind::Metres:
    report.units = "metres";
    report.reason = reason;
    field.setSpacing(static_cast<float>(coordinates.stepX), static_cast<float>(coordinates.stepZ));
    return;
  case Kind::Unknown:
    report.units = "metres";
    report.reason = fmt::format("{}; units unknown, taken as metres", reason);
    field.setSpacing(static_cast<float>(coordinates.stepX), static_cast<float>(coordinates.stepZ));
    warn(path, report,
         fmt::format(
             "horizontal units unknown ({}): spacing {:g} x {:g} taken as metres{}; pass --geographic "
             "for degrees or --spacing for metres",
             reason, coordinates.stepX, coordinates.stepZ,
             coordinates.looksLikeDegrees ? ", although the coordinates look like longitude/latitude" : ""));
    return;
  case Kind::Degrees:
    break;
  }
  double south = coordinates.south;
  double north = coordinates.north;
  if (std::isnan(south) || std::isnan(north)) {
    warn(path, report, "degrees without a latitude in the file: converted to metres at the equator");
    south = north = 0.0;
  }
  if (south < -90.0 - 1e-6 || north > 90.0 + 1e-6) {
    fail("{}: latitudes {:g} to {:g} lie beyond +-90 degrees; the coordinates are not degrees ({})",
         path.string(), south, north, reason);
  }
  const auto cosDeg = [](double degrees) {
    return std::cos(std::clamp(degrees, -90.0, 90.0) * std::numbers::pi / 180.0);
  };
  const double centre = 0.5 * (south + north);
  const double cosCentre = cosDeg(centre);
  if (cosCentre < 1e-3) {
    fail("{}: the grid is centred on a pole (latitude {:g}); reproject it to a polar projection first",
         path.string(), centre);
  }
  double error =
      std::max(std::abs(cosDeg(south) / cosCentre - 1.0), std::abs(cosDeg(north) / cosCentre - 1.0));
  if (south < 0.0 && north > 0.0) {
    error = std::max(error, 1.0 / cosCentre - 1.0);
  }
  report.units = "degrees";
  report.reason = reason;
  report.centreLatitude = centre;
  report.southLatitude = south;
  report.northLatitude = north;
  report.eastWestError = error;
  field.setSpacing(static_cast<float>(coordinates.stepX * kMetresPerDegree * cosCentre),
                   static_cast<float>(coordinates.stepZ * kMetresPerDegree));
  if (error > 0.05) {
    warn(path, report,
         fmt::format(
             "spans latitudes {:.4g} to {:.4g} degrees: with one east-west spacing (at {:.4g} degrees) "
             "distances are off by up to {:.0f} % on the outer rows; reproject to a projected CRS for "
             "true distances",
             south, north, centre, 100.0 * error));
  }
}

} // namespace detail

namespace {

constexpr int kSidecarVersion = 1;
constexpr const char* kSidecarFormat = "sylva-heightfield";
constexpr float kNoHeight = std::numeric_limits<float>::quiet_NaN();

std::filesystem::path sidecarPath(const std::filesystem::path& path) {
  std::filesystem::path sidecar = path;
  sidecar += ".json";
  return sidecar;
}

void requireFile(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) {
    fail("{}: is a directory, not a height file", path.string());
  }
  if (!std::filesystem::is_regular_file(status)) {
    fail("{}: file not found", path.string());
  }
}

void validateOptions(const std::filesystem::path& path, const LoadOptions& options) {
  if (options.maxSamples < 4 || options.maxSamples > kMaxHeightFieldSamples) {
    fail("{}: absurd maxSamples {} (must be 4..{})", path.string(), options.maxSamples,
         kMaxHeightFieldSamples);
  }
  if (options.maxSide < 2) {
    fail("{}: absurd maxSide {} (must be >= 2)", path.string(), options.maxSide);
  }
  if (!std::isfinite(options.heightScale) || options.heightScale <= 0.0f) {
    fail("{}: absurd heightScale {} (must be finite and > 0 metres)", path.string(), options.heightScale);
  }
  if (!std::isfinite(options.spacing) || options.spacing < 0.0f) {
    fail("{}: absurd spacing {} (must be finite and >= 0 metres; 0 = from the file)", path.string(),
         options.spacing);
  }
}

/** What a `<file>.json` sidecar written by saveHeightField records. */
struct Sidecar {
  float minHeight = 0.0f;
  float maxHeight = 0.0f;
  float spacingX = 1.0f;
  float spacingZ = 1.0f;
};

/** Size and zlib CRC-32 of a file: what binds a sidecar to the image it was written with. */
struct Fingerprint {
  std::uintmax_t bytes = 0;
  std::uint32_t crc = 0;
};

Fingerprint fingerprint(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("{}: cannot open file (missing or unreadable)", path.string());
  }
  Fingerprint f;
  uLong crc = crc32(0L, Z_NULL, 0);
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    crc = crc32(crc, reinterpret_cast<const Bytef*>(buffer.data()), static_cast<uInt>(n));
    f.bytes += n;
  }
  f.crc = static_cast<std::uint32_t>(crc);
  return f;
}

std::optional<Sidecar> readSidecar(const std::filesystem::path& image) {
  const std::filesystem::path path = sidecarPath(image);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    return std::nullopt;
  }
  const nlohmann::json json = loadJsonFile(path);
  const std::string name = path.string();
  requireJsonVersion(json, kSidecarVersion, name);
  const JsonNode root(json, name);
  const auto field = [&](const char* key) -> const nlohmann::json& { return root[key].value(); };
  if (!field("format").is_string() || field("format").get<std::string>() != kSidecarFormat) {
    root["format"].error(fmt::format("must be \"{}\"", kSidecarFormat));
  }
  const auto number = [&](const char* key, bool positive) {
    const double limit = std::numeric_limits<float>::max();
    return positive ? root[key].realAbove(0.0, limit) : root[key].real(-limit, limit);
  };
  Sidecar sidecar{number("minHeight", false), number("maxHeight", false), number("spacingX", true),
                  number("spacingZ", true)};
  // Written since the image and its sidecar became a pair bound by the image's size and CRC: a sidecar left
  // next to another image (an interrupted overwrite, or a file replaced by hand) must not rescale it
  // silently.
  if (json.contains("imageBytes") || json.contains("imageCrc32")) {
    const nlohmann::json& bytes = field("imageBytes");
    const nlohmann::json& crc = field("imageCrc32");
    if (!bytes.is_number_unsigned() || !crc.is_string()) {
      fail("{}: /imageBytes, /imageCrc32: expected a byte count and 8 hex digits", name);
    }
    const Fingerprint actual = fingerprint(image);
    const std::string actualCrc = fmt::format("{:08x}", actual.crc);
    if (bytes.get<std::uintmax_t>() != actual.bytes || crc.get<std::string>() != actualCrc) {
      fail("{}: does not belong to {} (written for {} bytes with CRC-32 {}, the image has {} bytes with "
           "CRC-32 "
           "{}); the pair was left by an interrupted write or one file was replaced",
           name, image.string(), bytes.get<std::uintmax_t>(), crc.get<std::string>(), actual.bytes,
           actualCrc);
    }
  }
  if (sidecar.maxHeight < sidecar.minHeight) {
    fail("{}: /maxHeight: {} is below minHeight {}", name, sidecar.maxHeight, sidecar.minHeight);
  }
  return sidecar;
}

/** PNG or EXR: channel 0 heights, optional alpha (channel 1; 0 = absent). */
HeightField loadImageHeights(const std::filesystem::path& path, const LoadOptions& options, bool png,
                             LoadReport& report) {
  requireFile(path);
  const Image image = loadImage(path);
  if (image.channels() > 2) {
    fail("{}: height images must be grey (or grey+alpha), got {} channels", path.string(), image.channels());
  }
  detail::checkHeightFieldSize(path, image.width(), image.height(), options);
  const std::optional<Sidecar> sidecar = readSidecar(path);
  HeightField field(image.width(), image.height());
  detail::FileCoordinates coordinates;
  if (sidecar) {
    coordinates.kind = detail::FileCoordinates::Kind::Metres;
    coordinates.stepX = sidecar->spacingX;
    coordinates.stepZ = sidecar->spacingZ;
    coordinates.reason = fmt::format("sidecar {}", sidecarPath(path).filename().string());
    if (png && options.heightScale != LoadOptions{}.heightScale) {
      detail::warn(
          path, report,
          fmt::format("height scale {:g} m (--png-scale) ignored: the sidecar {} gives heights in metres",
                      options.heightScale, sidecarPath(path).filename().string()));
    }
  }
  const double base = png && sidecar ? sidecar->minHeight : 0.0;
  const double scale = png ? (sidecar ? static_cast<double>(sidecar->maxHeight) - sidecar->minHeight
                                      : static_cast<double>(options.heightScale))
                           : 1.0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const bool absent = image.channels() == 2 && image.get(x, y, 1) == 0.0f;
      field.at(x, y) = absent ? kNoHeight : static_cast<float>(base + scale * image.get(x, y, 0));
    }
  }
  detail::applyCoordinates(path, field, coordinates, options, report);
  detail::finishHeightField(path, field, options, report);
  return field;
}

// ---- GDAL ----

/** Largest decoded GDAL block we let GDAL allocate: 1 GiB (a single-strip 16k x 16k float DEM). */
constexpr double kMaxBlockBytes = 1024.0 * 1048576.0;

void registerGdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    // We read rasters once, row by row: a row of blocks is all the cache needs. GDAL's default (5 % of RAM)
    // let a reader hold over a gigabyte of blocks on top of the field itself.
    GDALSetCacheMax64(std::int64_t{256} << 20);
  });
}

/** Silences GDAL's stderr printing for the current thread and collects the last message instead. */
class QuietGdal {
public:
  QuietGdal() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;

  static std::string lastMessage(const char* fallback) {
    std::string message = CPLGetLastErrorMsg();
    std::replace(message.begin(), message.end(), '\n', ' ');
    return message.empty() ? fallback : message;
  }
};

struct DatasetCloser {
  void operator()(GDALDatasetH ds) const { GDALClose(ds); }
};
using DatasetPtr = std::unique_ptr<std::remove_pointer_t<GDALDatasetH>, DatasetCloser>;

/** Metres per unit of the band's elevation unit ("" and metres: 1). */
double elevationUnitToMetres(const std::filesystem::path& path, std::string unit) {
  std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return std::tolower(c); });
  if (unit.empty() || unit == "m" || unit == "metre" || unit == "metres" || unit == "meter" ||
      unit == "meters") {
    return 1.0;
  }
  if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") {
    return 0.3048;
  }
  if (unit == "us-ft" || unit == "us survey foot" || unit == "ftus") {
    return 1200.0 / 3937.0;
  }
  log::warn("{}: unknown elevation unit '{}'; heights are taken as metres", path.string(), unit);
  return 1.0;
}

/** Lower-case copy. */
std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

/**
 * netCDF/CF axis attributes in GDAL's dataset metadata (`<variable>#units=degrees_east`, ...): "lon in
 * degrees_east, lat in degrees_north" when both a longitude and a latitude axis are declared and no
 * projected x/y axis is, else "".
 */
std::string cfGeographicAxes(GDALDatasetH dataset) {
  static const std::set<std::string> kEast = {"degrees_east", "degree_east", "degrees_e",
                                              "degree_e",     "degreese",    "degreee"};
  static const std::set<std::string> kNorth = {"degrees_north", "degree_north", "degrees_n",
                                               "degree_n",      "degreesn",     "degreen"};
  std::string lon;
  std::string lat;
  bool projectedAxis = false;
  for (char** item = GDALGetMetadata(dataset, nullptr); item != nullptr && *item != nullptr; ++item) {
    const std::string_view entry(*item);
    const std::size_t hash = entry.find('#');
    const std::size_t equals = entry.find('=');
    if (hash == std::string_view::npos || equals == std::string_view::npos || equals < hash) {
      continue;
    }
    const std::string variable(entry.substr(0, hash));
    const std::string key(entry.substr(hash + 1, equals - hash - 1));
    const std::string value = lower(std::string(entry.substr(equals + 1)));
    if ((key == "units" && kEast.contains(value)) || (key == "standard_name" && value == "longitude")) {
      lon = fmt::format("{} ({} {})", variable, key, value);
    } else if ((key == "units" && kNorth.contains(value)) ||
               (key == "standard_name" && value == "latitude")) {
      lat = fmt::format("{} ({} {})", variable, key, value);
    } else if (key == "standard_name" &&
               (value == "projection_x_coordinate" || value == "projection_y_coordinate")) {
      projectedAxis = true;
    }
  }
  if (lon.empty() || lat.empty() || projectedAxis) {
    return {};
  }
  return fmt::format("netCDF/CF axis attributes: {}, {}", lon, lat);
}

/** What a GDAL dataset says about its horizontal coordinates (geotransform, CRS, CF attributes). */
detail::FileCoordinates gdalCoordinates(GDALDatasetH dataset, bool haveTransform, const double* gt,
                                        int height) {
  detail::FileCoordinates c;
  if (!haveTransform) {
    return c;
  }
  c.stepX = std::hypot(gt[1], gt[4]);
  c.stepZ = std::hypot(gt[2], gt[5]);
  // Latitudes (in CRS units) of the centres of the first and last rows, for an axis-aligned grid.
  const double first = gt[3] + 0.5 * gt[5];
  const double last = gt[3] + (height - 0.5) * gt[5];
  c.south = std::min(first, last);
  c.north = std::max(first, last);
  const double west = gt[0];
  const double east = gt[0] + gt[1] * GDALGetRasterXSize(dataset);
  OGRSpatialReferenceH srs = GDALGetSpatialRef(dataset);
  const char* srsName = srs != nullptr ? OSRGetName(srs) : nullptr;
  const std::string name = srsName != nullptr ? srsName : "unnamed";
  if (srs != nullptr && OSRIsGeographic(srs)) {
    const double degreesPerUnit = OSRGetAngularUnits(srs, nullptr) * 180.0 / std::numbers::pi;
    c.kind = detail::FileCoordinates::Kind::Degrees;
    c.stepX *= degreesPerUnit;
    c.stepZ *= degreesPerUnit;
    c.south *= degreesPerUnit;
    c.north *= degreesPerUnit;
    c.reason = fmt::format("CRS '{}' is geographic", name);
  } else if (srs != nullptr && OSRIsProjected(srs)) {
    const double metresPerUnit = OSRGetLinearUnits(srs, nullptr);
    c.kind = detail::FileCoordinates::Kind::Metres;
    c.stepX *= metresPerUnit;
    c.stepZ *= metresPerUnit;
    c.reason = fmt::format("CRS '{}' is projected ({:g} m per unit)", name, metresPerUnit);
  } else if (const std::string cf = cfGeographicAxes(dataset); !cf.empty()) {
    c.kind = detail::FileCoordinates::Kind::Degrees;
    c.reason = cf;
  } else {
    c.kind = detail::FileCoordinates::Kind::Unknown;
    c.reason = srs != nullptr ? fmt::format("CRS '{}' is neither geographic nor projected", name)
                              : "a geotransform without a CRS or axis units";
    c.looksLikeDegrees = std::min(west, east) >= -180.0 && std::max(west, east) <= 360.0 &&
                         c.south >= -90.0 && c.north <= 90.0 && c.stepX < 1.0 && c.stepZ < 1.0;
  }
  return c;
}

/** A short description of a file's leading bytes, for open errors GDAL leaves without a message. */
std::string guessCorruptFormat(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> head{};
  in.read(head.data(), head.size());
  const std::string_view bytes(head.data(), static_cast<std::size_t>(in.gcount()));
  if (bytes.starts_with("\x89HDF\r\n\x1a\n")) {
    return "corrupt or truncated HDF5/netCDF-4 file";
  }
  if (bytes.starts_with("CDF")) {
    return "corrupt or truncated netCDF file";
  }
  if (bytes.starts_with("II*") || bytes.starts_with(std::string_view("MM\0*", 4))) {
    return "corrupt or truncated TIFF file";
  }
  return "not a raster format GDAL can read";
}

/** A GDAL raster's band 1 as heights: what describeGdal found out before reading a sample. */
struct GdalLayout {
  int width = 0;        ///< samples along x
  int height = 0;       ///< samples along z
  double scale = 1.0;   ///< metres per stored unit (scale × elevation unit)
  double offset = 0.0;  ///< metres added after scaling
  bool hasMask = false; ///< whether the mask band must be read (nodata, alpha, per-dataset mask)
  bool flipX = false;   ///< columns run east to west in the file
  bool flipZ = false;   ///< rows run south to north in the file
  double gt[6] = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0}; ///< the geotransform (identity when absent)
  bool haveTransform = false;                    ///< whether the file has a geotransform
};

DatasetPtr openGdal(const std::filesystem::path& path) {
  requireFile(path);
  detail::checkNetCdfClassicSize(path);
  registerGdal();
  const QuietGdal quiet;
  const std::string name = path.string();
  DatasetPtr dataset(GDALOpenEx(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR,
                                nullptr, nullptr, nullptr));
  if (!dataset) {
    // A known signature that GDAL cannot open is a damaged file of that format, not an unknown format.
    const std::string guess = guessCorruptFormat(path);
    const std::string message = QuietGdal::lastMessage("");
    if (message.empty() || guess.starts_with("corrupt")) {
      fail("{}: {}", name, guess);
    }
    fail("{}: {}", name, message);
  }
  return dataset;
}

/**
 * Everything about `dataset` that can be checked before a sample is read: bands, size (checkSize), data type,
 * units, mask, orientation, block layout and missing blocks. Fills report.orientation.
 */
template <typename CheckSize>
GdalLayout describeGdal(const std::filesystem::path& path, GDALDatasetH dataset, LoadReport& report,
                        const CheckSize& checkSize) {
  const QuietGdal quiet;
  const std::string name = path.string();
  if (GDALGetRasterCount(dataset) < 1) {
    fail("{}: raster has no band", name);
  }
  GdalLayout layout;
  layout.width = GDALGetRasterXSize(dataset);
  layout.height = GDALGetRasterYSize(dataset);
  checkSize(layout.width, layout.height);
  const int width = layout.width;
  const int height = layout.height;
  GDALRasterBandH band = GDALGetRasterBand(dataset, 1);
  if (GDALDataTypeIsComplex(GDALGetRasterDataType(band))) {
    fail("{}: band 1 holds complex numbers, not heights", name);
  }
  int hasScale = 0;
  int hasOffset = 0;
  const double unit = elevationUnitToMetres(path, GDALGetRasterUnitType(band));
  layout.scale = GDALGetRasterScale(band, &hasScale) * unit;
  layout.offset = GDALGetRasterOffset(band, &hasOffset) * unit;
  // The mask band covers nodata values, alpha bands and per-dataset masks alike; 0 = invalid.
  const bool allValid = (GDALGetMaskFlags(band) & GMF_ALL_VALID) != 0;
  layout.hasMask = !allValid;

  double* gt = layout.gt;
  layout.haveTransform = GDALGetGeoTransform(dataset, gt) == CE_None;
  CPLErrorReset();
  const bool axisAligned = gt[2] == 0.0 && gt[4] == 0.0;
  layout.flipX = layout.haveTransform && axisAligned && gt[1] < 0.0;
  layout.flipZ = layout.haveTransform && axisAligned && gt[5] > 0.0;
  if (layout.flipZ || layout.flipX) {
    report.orientation = fmt::format(
        "{}{}{} (the geotransform says so)", layout.flipZ ? "rows flipped: south-up" : "",
        layout.flipZ && layout.flipX ? "; " : "", layout.flipX ? "columns flipped: east-left" : "");
  }

  // GDAL decodes whole blocks (strips or tiles, all bands at once for pixel-interleaved files) into buffers
  // it allocates from the header. A 200-byte TIFF with an absurd strip made GDAL allocate 4.7 GB (found by
  // fuzzing); real DEMs use blocks of a few rows or 256-512 tiles. Refuse blocks larger than twice the raster
  // (tiles may overhang the edge) and than kMaxBlockBytes.
  int blockX = 0;
  int blockY = 0;
  GDALGetBlockSize(band, &blockX, &blockY);
  const double typeBytes = GDALGetDataTypeSizeBytes(GDALGetRasterDataType(band));
  const char* interleave = GDALGetMetadataItem(dataset, "INTERLEAVE", "IMAGE_STRUCTURE");
  const int bands = GDALGetRasterCount(dataset);
  const double blockBands = interleave != nullptr && std::string_view(interleave) == "PIXEL" ? bands : 1;
  const double blockBytes = static_cast<double>(blockX) * blockY * typeBytes * blockBands;
  const double rasterBytes = static_cast<double>(width) * height * typeBytes * blockBands;
  if (blockBytes > std::max(2.0 * rasterBytes, 1048576.0) || blockBytes > kMaxBlockBytes) {
    fail("{}: blocks of {}x{} samples x {} bands ({:.0f} MiB each) are not a plausible layout for a {}x{} "
         "raster "
         "(corrupt header?)",
         name, blockX, blockY, blockBands, blockBytes / 1048576.0, width, height);
  }

  // Blocks a file declares but does not hold (sparse or cut-off GeoTIFF strips and tiles) read back as zeros
  // without any error. Without nodata to mark them absent that is wrong ground, so refuse before reading: a
  // 200-byte TIFF claiming 15k x 16k samples made us allocate a gigabyte of zeros (found by fuzzing).
  double coverage = 100.0;
  const int status = GDALGetDataCoverageStatus(band, 0, 0, width, height, 0, &coverage);
  if ((status & GDAL_DATA_COVERAGE_STATUS_EMPTY) != 0 && (allValid || coverage <= 0.0)) {
    fail("{}: {:.3g} % of the raster's blocks are missing from the file (truncated or corrupt; no nodata "
         "value "
         "to mark them absent)",
         name, 100.0 - coverage);
  }
  CPLErrorReset();
  return layout;
}

/**
 * Reads the file window x ∈ [x0, x0 + w), y ∈ [y0, y0 + h) (file order) of band 1 as metres into `out`
 * (row-major, file order; NaN where masked). `values` and `mask` are scratch of w·h entries.
 */
void readGdalWindow(const std::filesystem::path& path, GDALDatasetH dataset, const GdalLayout& layout, int x0,
                    int y0, int w, int h, std::vector<double>& values, std::vector<unsigned char>& mask,
                    float* out) {
  const std::size_t count = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  values.resize(count);
  GDALRasterBandH band = GDALGetRasterBand(dataset, 1);
  CPLErrorReset();
  // Some drivers report a failed block read without failing the request (the rows come back as zeros).
  if (GDALRasterIO(band, GF_Read, x0, y0, w, h, values.data(), w, h, GDT_Float64, 0, 0) != CE_None ||
      CPLGetLastErrorType() >= CE_Failure) {
    fail("{}: cannot read {}: {}", path.string(),
         h == 1 ? fmt::format("row {}", y0) : fmt::format("rows {}..{}", y0, y0 + h - 1),
         QuietGdal::lastMessage("read failed (truncated or corrupt?)"));
  }
  if (layout.hasMask) {
    mask.resize(count);
    if (GDALRasterIO(GDALGetMaskBand(band), GF_Read, x0, y0, w, h, mask.data(), w, h, GDT_Byte, 0, 0) !=
            CE_None ||
        CPLGetLastErrorType() >= CE_Failure) {
      fail("{}: cannot read the nodata mask of {}: {}", path.string(),
           h == 1 ? fmt::format("row {}", y0) : fmt::format("rows {}..{}", y0, y0 + h - 1),
           QuietGdal::lastMessage("read failed"));
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    out[k] = layout.hasMask && mask[k] == 0 ? kNoHeight
                                            : detail::toHeight(values[k] * layout.scale + layout.offset);
  }
}

HeightField loadGdal(const std::filesystem::path& path, const LoadOptions& options, LoadReport& report) {
  const DatasetPtr dataset = openGdal(path);
  const QuietGdal quiet;
  const GdalLayout layout = describeGdal(path, dataset.get(), report, [&](int width, int height) {
    detail::checkHeightFieldSize(path, width, height, options);
  });
  const int width = layout.width;
  const int height = layout.height;

  HeightField field(width, height);
  std::vector<double> values;
  std::vector<unsigned char> mask;
  std::vector<float> row(static_cast<std::size_t>(width));
  std::optional<Progress> progress;
  if (static_cast<std::size_t>(width) * static_cast<std::size_t>(height) > (std::size_t{1} << 20)) {
    progress.emplace(fmt::format("reading {}", path.filename().string()), static_cast<std::size_t>(height));
  }
  for (int y = 0; y < height; ++y) {
    if (progress) {
      if (progress->cancelled()) {
        fail("{}: reading cancelled", path.string());
      }
      progress->advance();
    }
    readGdalWindow(path, dataset.get(), layout, 0, y, width, 1, values, mask, row.data());
    const int j = layout.flipZ ? height - 1 - y : y;
    for (int x = 0; x < width; ++x) {
      const int i = layout.flipX ? width - 1 - x : x;
      field.at(i, j) = row[static_cast<std::size_t>(x)];
    }
  }

  detail::applyCoordinates(
      path, field, gdalCoordinates(dataset.get(), layout.haveTransform, layout.gt, height), options, report);
  detail::finishHeightField(path, field, options, report);
  return field;
}

/** HeightRaster over a GDAL dataset: windows read on demand through a pool of open datasets. */
class GdalRaster final : public HeightRaster {
public:
  GdalRaster(std::filesystem::path path, GdalLayout layout, bool flipRows, float spacingX, float spacingZ)
      : HeightRaster(layout.width, layout.height, spacingX, spacingZ), mPath(std::move(path)),
        mLayout(layout), mFlipRows(flipRows) {}

  void read(int i0, int j0, int w, int h, float* out) const override {
    checkWindow(i0, j0, w, h);
    DatasetPtr dataset = take();
    const QuietGdal quiet;
    const bool flipZ = mLayout.flipZ != mFlipRows;
    const int x0 = mLayout.flipX ? width() - i0 - w : i0;
    const int y0 = flipZ ? height() - j0 - h : j0;
    std::vector<double> values;
    std::vector<unsigned char> mask;
    std::vector<float> window(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    try {
      readGdalWindow(mPath, dataset.get(), mLayout, x0, y0, w, h, values, mask, window.data());
    } catch (...) {
      give(std::move(dataset));
      throw;
    }
    give(std::move(dataset));
    for (int y = 0; y < h; ++y) {
      const int j = flipZ ? h - 1 - y : y;
      for (int x = 0; x < w; ++x) {
        const int i = mLayout.flipX ? w - 1 - x : x;
        out[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)] =
            window[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
      }
    }
  }

  void prepareSweep(int rows) const override {
    DatasetPtr dataset = take();
    GDALRasterBandH band = GDALGetRasterBand(dataset.get(), 1);
    int blockX = 0;
    int blockY = 0;
    GDALGetBlockSize(band, &blockX, &blockY);
    const double typeBytes = GDALGetDataTypeSizeBytes(GDALGetRasterDataType(band));
    give(std::move(dataset));
    blockX = std::max(blockX, 1);
    blockY = std::max(blockY, 1);
    // A band of `rows` rows touches ceil(rows / blockY) + 1 rows of blocks; keep two bands (the band after
    // the one being read shares its border rows), the mask's blocks as many again.
    const double blockRows = std::ceil(static_cast<double>(rows) / blockY) + 1.0;
    const double blocksPerRow = std::ceil(static_cast<double>(width()) / blockX);
    const double bytes =
        2.0 * blockRows * blocksPerRow * blockX * blockY * typeBytes * (mLayout.hasMask ? 2 : 1);
    GDALSetCacheMax64(static_cast<std::int64_t>(std::clamp(bytes, 16.0 * 1048576.0, 256.0 * 1048576.0)));
  }

private:
  DatasetPtr take() const {
    {
      const std::lock_guard lock(mMutex);
      if (!mPool.empty()) {
        DatasetPtr dataset = std::move(mPool.back());
        mPool.pop_back();
        return dataset;
      }
    }
    return openGdal(mPath);
  }
  void give(DatasetPtr dataset) const {
    const std::lock_guard lock(mMutex);
    mPool.push_back(std::move(dataset));
  }

  std::filesystem::path mPath;
  GdalLayout mLayout;
  bool mFlipRows;
  mutable std::mutex mMutex;
  mutable std::vector<DatasetPtr> mPool;
};

/** HeightRaster over a field held in memory. */
class FieldRaster final : public HeightRaster {
public:
  explicit FieldRaster(HeightField field)
      : HeightRaster(field.width(), field.height(), field.spacingX(), field.spacingZ()),
        mField(std::move(field)) {}

  void read(int i0, int j0, int w, int h, float* out) const override {
    checkWindow(i0, j0, w, h);
    for (int y = 0; y < h; ++y) {
      const float* row = &mField.samples()[static_cast<std::size_t>(j0 + y) * mField.width() + i0];
      std::copy(row, row + w, out + static_cast<std::size_t>(y) * static_cast<std::size_t>(w));
    }
  }

private:
  HeightField mField;
};

void saveGeoTiff(const std::filesystem::path& path, const HeightField& field) {
  registerGdal();
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    const QuietGdal quiet;
    GDALDriverH driver = GDALGetDriverByName("GTiff");
    if (driver == nullptr) {
      fail("{}: GDAL has no GTiff driver", path.string());
    }
    const char* createOptions[] = {"COMPRESS=DEFLATE", nullptr};
    DatasetPtr dataset(GDALCreate(driver, tmp.string().c_str(), field.width(), field.height(), 1, GDT_Float32,
                                  const_cast<char**>(createOptions)));
    if (!dataset) {
      fail("{}: {}", path.string(), QuietGdal::lastMessage("cannot create GeoTIFF"));
    }
    double gt[6] = {0.0, field.spacingX(), 0.0, 0.0, 0.0, -static_cast<double>(field.spacingZ())};
    GDALRasterBandH band = GDALGetRasterBand(dataset.get(), 1);
    auto& samples = const_cast<std::vector<float>&>(field.samples()); // GF_Write only reads the buffer
    if (GDALSetGeoTransform(dataset.get(), gt) != CE_None ||
        GDALSetRasterNoDataValue(band, std::numeric_limits<double>::quiet_NaN()) != CE_None ||
        GDALRasterIO(band, GF_Write, 0, 0, field.width(), field.height(), samples.data(), field.width(),
                     field.height(), GDT_Float32, 0, 0) != CE_None) {
      fail("{}: {}", path.string(), QuietGdal::lastMessage("cannot write GeoTIFF"));
    }
    dataset.reset();
    if (CPLGetLastErrorType() >= CE_Failure) {
      fail("{}: {}", path.string(), QuietGdal::lastMessage("cannot write GeoTIFF"));
    }
  });
}

/**
 * Writes `image` to `path` (.png or .exr) with its sidecar, as a bound pair: the image is completed in its
 * temporary first, the sidecar (holding that image's size and CRC-32) is renamed into place, then the image.
 * A process killed in between leaves a sidecar that does not match the image beside it, which readSidecar
 * rejects, instead of heights silently rescaled by another run's range.
 */
void saveImageWithSidecar(const std::filesystem::path& path, const Image& image, const HeightField& field,
                          const HeightFieldInfo& info, bool png) {
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    if (png) {
      savePng(tmp, image);
    } else {
      saveExr(tmp, image);
    }
    const Fingerprint written = fingerprint(tmp);
    nlohmann::json json;
    json["version"] = kSidecarVersion;
    json["format"] = kSidecarFormat;
    json["minHeight"] = info.minHeight;
    json["maxHeight"] = info.maxHeight;
    json["spacingX"] = field.spacingX();
    json["spacingZ"] = field.spacingZ();
    json["imageBytes"] = written.bytes;
    json["imageCrc32"] = fmt::format("{:08x}", written.crc);
    saveJsonFile(sidecarPath(path), json);
  });
}

} // namespace

HeightFieldInfo heightFieldInfo(const HeightField& field) {
  HeightFieldInfo info;
  info.minHeight = std::numeric_limits<float>::infinity();
  info.maxHeight = -std::numeric_limits<float>::infinity();
  for (const float h : field.samples()) {
    if (std::isnan(h)) {
      ++info.absentCount;
    } else {
      ++info.validCount;
      info.minHeight = std::min(info.minHeight, h);
      info.maxHeight = std::max(info.maxHeight, h);
    }
  }
  if (info.validCount == 0) {
    info.minHeight = kNoHeight;
    info.maxHeight = kNoHeight;
  }
  return info;
}

void HeightRaster::checkWindow(int i0, int j0, int w, int h) const {
  if (w < 1 || h < 1 || i0 < 0 || j0 < 0 || i0 > mWidth - w || j0 > mHeight - h) {
    fail("height raster: window {}x{} at ({}, {}) lies outside the {}x{} samples", w, h, i0, j0, mWidth,
         mHeight);
  }
}

std::shared_ptr<const HeightRaster> HeightRaster::fromField(HeightField field) {
  if (field.width() < 2 || field.height() < 2) {
    fail("height raster: {}x{} samples; a height field needs at least 2x2", field.width(), field.height());
  }
  return std::make_shared<FieldRaster>(std::move(field));
}

std::shared_ptr<const HeightRaster> HeightRaster::open(const std::filesystem::path& path,
                                                       const LoadOptions& options, LoadReport* report) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png" || ext == ".exr" || ext == ".npy" || ext == ".npz") {
    return fromField(loadHeightField(path, options, report));
  }
  validateOptions(path, options);
  LoadReport local;
  LoadReport& r = report != nullptr ? *report : local;
  r = LoadReport{};
  const DatasetPtr dataset = openGdal(path);
  const GdalLayout layout = describeGdal(path, dataset.get(), r, [&](long long width, long long height) {
    if (width > kMaxRasterSide || height > kMaxRasterSide) {
      fail("{}: absurd size {}x{} samples (at most {} per side)", path.string(), width, height,
           kMaxRasterSide);
    }
    if (width < 2 || height < 2) {
      fail("{}: {}x{} samples; a height field needs at least 2x2", path.string(), width, height);
    }
  });
  // The spacing as loadHeightField would set it (coordinates, --spacing), on a stand-in field.
  HeightField spacing(2, 2);
  {
    const QuietGdal quiet;
    detail::applyCoordinates(path, spacing,
                             gdalCoordinates(dataset.get(), layout.haveTransform, layout.gt, layout.height),
                             options, r);
  }
  if (options.spacing > 0.0f) {
    spacing.setSpacing(options.spacing, options.spacing);
    r.units = "metres";
    r.reason = fmt::format("--spacing {:g} m overrides the file ({})", options.spacing, r.reason);
  }
  if (options.flipY) {
    r.orientation += "; then flipped north-south (--flip-y)";
  }
  const auto usable = [](float s) { return std::isfinite(s) && s > 0.0f; };
  if (!usable(spacing.spacingX()) || !usable(spacing.spacingZ())) {
    fail("{}: absurd spacing {} x {} m from the file (must be finite and > 0; set LoadOptions::spacing)",
         path.string(), spacing.spacingX(), spacing.spacingZ());
  }
  return std::make_shared<GdalRaster>(path, layout, options.flipY, spacing.spacingX(), spacing.spacingZ());
}

HeightField loadHeightField(const std::filesystem::path& path, const LoadOptions& options,
                            LoadReport* report) {
  validateOptions(path, options);
  LoadReport local;
  LoadReport& r = report != nullptr ? *report : local;
  r = LoadReport{};
  const std::string ext = lowerExtension(path);
  if (ext == ".png") {
    return loadImageHeights(path, options, true, r);
  }
  if (ext == ".exr") {
    return loadImageHeights(path, options, false, r);
  }
  if (ext == ".npy") {
    requireFile(path);
    return detail::loadNpy(path, options, r);
  }
  if (ext == ".npz") {
    requireFile(path);
    return detail::loadNpz(path, options, r);
  }
  return loadGdal(path, options, r);
}

void saveHeightField(const std::filesystem::path& path, const HeightField& field) {
  if (field.width() < 1 || field.height() < 1 ||
      field.samples().size() !=
          static_cast<std::size_t>(field.width()) * static_cast<std::size_t>(field.height())) {
    fail("{}: cannot save an empty height field", path.string());
  }
  const HeightFieldInfo info = heightFieldInfo(field);
  if (info.validCount == 0) {
    fail("{}: cannot save a height field without valid samples", path.string());
  }
  if (std::isinf(info.minHeight) || std::isinf(info.maxHeight)) {
    fail("{}: cannot save infinite heights", path.string());
  }
  const std::string ext = lowerExtension(path);
  if (ext == ".png") {
    const bool alpha = info.absentCount > 0;
    Image image(field.width(), field.height(), alpha ? 2 : 1, PixelType::U16);
    auto values = image.values<std::uint16_t>();
    const double range = static_cast<double>(info.maxHeight) - info.minHeight;
    const int channels = image.channels();
    for (int j = 0; j < field.height(); ++j) {
      for (int i = 0; i < field.width(); ++i) {
        const float h = field.at(i, j);
        const std::size_t p = (static_cast<std::size_t>(j) * field.width() + i) * channels;
        const double t = std::isnan(h) || range <= 0.0 ? 0.0 : (h - info.minHeight) / range;
        values[p] = static_cast<std::uint16_t>(std::clamp(std::lround(t * 65535.0), 0L, 65535L));
        if (alpha) {
          values[p + 1] = std::isnan(h) ? 0 : 65535;
        }
      }
    }
    saveImageWithSidecar(path, image, field, info, true);
  } else if (ext == ".exr") {
    Image image(field.width(), field.height(), 1, PixelType::F32);
    std::copy(field.samples().begin(), field.samples().end(), image.values<float>().begin());
    saveImageWithSidecar(path, image, field, info, false);
  } else if (ext == ".npy") {
    detail::saveNpy(path, field);
  } else if (ext == ".tif" || ext == ".tiff") {
    saveGeoTiff(path, field);
  } else {
    fail("{}: cannot save heights as '{}' (use .png, .exr, .npy, .tif)", path.string(), ext);
  }
}

} // namespace sylva::terrain

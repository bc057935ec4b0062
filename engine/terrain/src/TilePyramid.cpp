#include <sylva/terrain/TilePyramid.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Parallel.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <zlib.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <system_error>

namespace sylva::terrain {
namespace {

static_assert(std::endian::native == std::endian::little, "tile files are little-endian");

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr char kTileMagic[8] = {'S', 'Y', 'L', 'V', 'T', 'I', 'L', 'E'};
constexpr char kIndexMagic[8] = {'S', 'Y', 'L', 'V', 'I', 'D', 'X', '1'};
constexpr std::size_t kTileHeader = 48;
constexpr std::size_t kIndexHeader = 28;
constexpr const char* kFormat = "sylva-pyramid";
constexpr const char* kCompression = "zlib over the floating-point predictor, per row";

std::size_t samplesOf(int tileSize) {
  return static_cast<std::size_t>(tileSize + 1) * static_cast<std::size_t>(tileSize + 1);
}

template <typename T> void put(std::vector<std::uint8_t>& out, std::size_t offset, T value) {
  std::memcpy(out.data() + offset, &value, sizeof(T));
}
template <typename T> T get(const std::uint8_t* bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes + offset, sizeof(T));
  return value;
}

std::uint32_t crcOf(const std::uint8_t* bytes, std::size_t size) {
  uLong crc = crc32(0L, Z_NULL, 0);
  while (size > 0) {
    const auto chunk = static_cast<uInt>(std::min<std::size_t>(size, 1u << 30));
    crc = crc32(crc, bytes, chunk);
    bytes += chunk;
    size -= chunk;
  }
  return static_cast<std::uint32_t>(crc);
}

/** CRC-32 of a tile's header fields (bytes 8..43: version to payload size) and its payload. */
std::uint32_t tileCrc(const std::uint8_t* bytes, std::size_t packed) {
  uLong crc = crc32(0L, bytes + 8, 36);
  return static_cast<std::uint32_t>(
      crc32_combine(crc, crcOf(bytes + kTileHeader, packed), static_cast<z_off_t>(packed)));
}

/**
 * The floating-point predictor of TIFF (Adobe Photoshop TIFF Technical Note 3), per row of n floats: the
 * bytes are regrouped most significant first (all exponents, then the mantissas' high bytes, …), then each
 * byte is replaced by its difference from the byte before it in the row. Smooth heights become long runs of
 * small numbers that zlib packs well; lossless.
 */
void predict(const float* in, int n, std::uint8_t* out) {
  const auto count = static_cast<std::size_t>(n);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t bits;
    std::memcpy(&bits, &in[i], 4);
    for (std::size_t k = 0; k < 4; ++k) {
      out[k * count + i] = static_cast<std::uint8_t>(bits >> (8 * (3 - k)));
    }
  }
  for (std::size_t m = 4 * count - 1; m > 0; --m) {
    out[m] = static_cast<std::uint8_t>(out[m] - out[m - 1]);
  }
}

void unpredict(std::uint8_t* in, int n, float* out) {
  const auto count = static_cast<std::size_t>(n);
  for (std::size_t m = 1; m < 4 * count; ++m) {
    in[m] = static_cast<std::uint8_t>(in[m] + in[m - 1]);
  }
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t bits = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      bits |= static_cast<std::uint32_t>(in[k * count + i]) << (8 * (3 - k));
    }
    std::memcpy(&out[i], &bits, 4);
  }
}

std::vector<std::uint8_t> readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("{}: cannot open", path.string());
  }
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  if (!std::filesystem::is_directory(path.parent_path())) {
    fail("{}: cannot create the folder: {}", path.parent_path().string(), ec.message());
  }
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) {
      fail("{}: cannot write", path.string());
    }
  });
}

/** Hull of two ranges whose NaN ends mean "empty". */
void widen(TileSummary& into, float lo, float hi) {
  if (std::isnan(lo)) {
    return;
  }
  into.minHeight = std::isnan(into.minHeight) ? lo : std::min(into.minHeight, lo);
  into.maxHeight = std::isnan(into.maxHeight) ? hi : std::max(into.maxHeight, hi);
}

TileSummary rangeOf(const std::vector<float>& heights) {
  TileSummary s{kNaN, kNaN, 0.0f};
  for (const float h : heights) {
    if (!std::isnan(h)) {
      widen(s, h, h);
    }
  }
  return s;
}

std::filesystem::path indexPath(const std::filesystem::path& dir, int level) {
  return dir / std::to_string(level) / "index.bin";
}

void writeIndex(const std::filesystem::path& dir, int level, const PyramidLevel& size,
                const std::vector<TileSummary>& summaries) {
  std::vector<std::uint8_t> bytes(kIndexHeader + summaries.size() * 12);
  std::memcpy(bytes.data(), kIndexMagic, 8);
  put<std::uint32_t>(bytes, 8, kPyramidVersion);
  put<std::int32_t>(bytes, 12, level);
  put<std::int32_t>(bytes, 16, size.tilesX);
  put<std::int32_t>(bytes, 20, size.tilesY);
  for (std::size_t k = 0; k < summaries.size(); ++k) {
    put<float>(bytes, kIndexHeader + 12 * k, summaries[k].minHeight);
    put<float>(bytes, kIndexHeader + 12 * k + 4, summaries[k].maxHeight);
    put<float>(bytes, kIndexHeader + 12 * k + 8, summaries[k].error);
  }
  put<std::uint32_t>(bytes, 24, crcOf(bytes.data() + kIndexHeader, bytes.size() - kIndexHeader));
  writeBytes(indexPath(dir, level), bytes);
}

std::vector<TileSummary> readIndex(const std::filesystem::path& dir, int level, const PyramidLevel& size) {
  const std::filesystem::path path = indexPath(dir, level);
  const std::vector<std::uint8_t> bytes = readBytes(path);
  const std::size_t tiles = static_cast<std::size_t>(size.tilesX) * static_cast<std::size_t>(size.tilesY);
  if (bytes.size() < kIndexHeader || std::memcmp(bytes.data(), kIndexMagic, 8) != 0) {
    fail("{}: not a Sylva tile index", path.string());
  }
  if (get<std::uint32_t>(bytes.data(), 8) != kPyramidVersion ||
      get<std::int32_t>(bytes.data(), 12) != level || get<std::int32_t>(bytes.data(), 16) != size.tilesX ||
      get<std::int32_t>(bytes.data(), 20) != size.tilesY || bytes.size() != kIndexHeader + 12 * tiles) {
    fail("{}: index does not match pyramid.json (level {}, {}x{} tiles)", path.string(), level, size.tilesX,
         size.tilesY);
  }
  if (get<std::uint32_t>(bytes.data(), 24) !=
      crcOf(bytes.data() + kIndexHeader, bytes.size() - kIndexHeader)) {
    fail("{}: checksum mismatch (corrupt index)", path.string());
  }
  std::vector<TileSummary> summaries(tiles);
  for (std::size_t k = 0; k < tiles; ++k) {
    summaries[k] = {get<float>(bytes.data(), kIndexHeader + 12 * k),
                    get<float>(bytes.data(), kIndexHeader + 12 * k + 4),
                    get<float>(bytes.data(), kIndexHeader + 12 * k + 8)};
    const TileSummary& s = summaries[k];
    if (std::isnan(s.minHeight) != std::isnan(s.maxHeight) || s.minHeight > s.maxHeight ||
        !(s.error >= 0.0f) || std::isinf(s.error) || std::isinf(s.minHeight) || std::isinf(s.maxHeight)) {
      fail("{}: tile {} has an impossible summary", path.string(), k);
    }
  }
  return summaries;
}

nlohmann::json infoJson(const PyramidInfo& info) {
  const auto height = [](float h) { return std::isnan(h) ? nlohmann::json(nullptr) : nlohmann::json(h); };
  return {{"version", kPyramidVersion},
          {"format", kFormat},
          {"compression", kCompression},
          {"width", info.width},
          {"height", info.height},
          {"spacingX", info.spacingX},
          {"spacingZ", info.spacingZ},
          {"tileSize", info.tileSize},
          {"levels", info.levels},
          {"minHeight", height(info.minHeight)},
          {"maxHeight", height(info.maxHeight)},
          {"source", info.source},
          {"complete", info.complete},
          {"tiles", info.tiles},
          {"bytes", info.bytes}};
}

PyramidInfo readInfo(const std::filesystem::path& path) {
  const nlohmann::json json = loadJsonFile(path);
  requireJsonVersion(json, kPyramidVersion, path.string());
  const auto field = [&](const char* name) -> const nlohmann::json& {
    if (!json.contains(name)) {
      fail("{}: missing field '{}'", path.string(), name);
    }
    return json.at(name);
  };
  const auto integer = [&](const char* name, long long lo, long long hi) {
    const nlohmann::json& v = field(name);
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi) {
      fail("{}: field '{}' must be a whole number in [{}, {}]", path.string(), name, lo, hi);
    }
    return v.get<long long>();
  };
  const auto number = [&](const char* name, bool nullable) {
    const nlohmann::json& v = field(name);
    if (nullable && v.is_null()) {
      return kNaN;
    }
    if (!v.is_number() || !std::isfinite(v.get<double>()) || std::abs(v.get<double>()) > 3.0e38) {
      fail("{}: field '{}' must be a finite number", path.string(), name);
    }
    return v.get<float>();
  };
  if (!field("format").is_string() || field("format").get<std::string>() != kFormat) {
    fail("{}: field 'format' must be \"{}\"", path.string(), kFormat);
  }
  const auto width = static_cast<int>(integer("width", 2, kMaxRasterSide));
  const auto height = static_cast<int>(integer("height", 2, kMaxRasterSide));
  const float spacingX = number("spacingX", false);
  const float spacingZ = number("spacingZ", false);
  if (!(spacingX > 0.0f) || !(spacingZ > 0.0f)) {
    fail("{}: fields 'spacingX' and 'spacingZ' must be > 0 metres", path.string());
  }
  const auto tileSize = static_cast<int>(integer("tileSize", kMinTileSize, kMaxTileSize));
  PyramidInfo info = PyramidInfo::plan(width, height, spacingX, spacingZ, tileSize);
  if (integer("levels", 1, 64) != info.levels) {
    fail("{}: field 'levels' must be {} for {}x{} samples in tiles of {}", path.string(), info.levels, width,
         height, tileSize);
  }
  info.minHeight = number("minHeight", true);
  info.maxHeight = number("maxHeight", true);
  if (std::isnan(info.minHeight) != std::isnan(info.maxHeight) || info.minHeight > info.maxHeight) {
    fail("{}: fields 'minHeight' and 'maxHeight' must both be null or minHeight <= maxHeight", path.string());
  }
  if (!field("source").is_string() || !field("complete").is_boolean()) {
    fail("{}: field 'source' must be a string and 'complete' true or false", path.string());
  }
  info.source = field("source").get<std::string>();
  info.complete = field("complete").get<bool>();
  info.bytes = static_cast<std::uint64_t>(integer("bytes", 0, std::numeric_limits<long long>::max()));
  return info;
}

/** Reads an existing tile file if it is a valid tile of `key` and size T; nullopt if absent or not. */
std::optional<TileData> existingTile(const std::filesystem::path& path, const TileKey& key, int tileSize) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return std::nullopt;
  }
  try {
    const std::vector<std::uint8_t> bytes = readBytes(path);
    TileData tile = decodeTile(bytes.data(), bytes.size(), path.string());
    if (tile.key == key && tile.size == tileSize) {
      return tile;
    }
  } catch (const Error&) {
  }
  return std::nullopt;
}

/** Level-0 tile `key` from the raster: a window of up to (T + 1)² samples, NaN beyond the raster. */
TileData baseTile(const HeightRaster& raster, const TileKey& key, int tileSize) {
  TileData tile;
  tile.key = key;
  tile.size = tileSize;
  tile.heights.assign(samplesOf(tileSize), kNaN);
  const int i0 = key.x * tileSize;
  const int j0 = key.y * tileSize;
  const int w = std::min(tileSize + 1, raster.width() - i0);
  const int h = std::min(tileSize + 1, raster.height() - j0);
  std::vector<float> window(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  raster.read(i0, j0, w, h, window.data());
  for (int b = 0; b < h; ++b) {
    std::copy_n(window.begin() + static_cast<std::ptrdiff_t>(b) * w, w,
                tile.heights.begin() + static_cast<std::ptrdiff_t>(b) * (tileSize + 1));
  }
  for (float& v : tile.heights) {
    if (!std::isfinite(v)) {
      v = kNaN;
    }
  }
  tile.summary = rangeOf(tile.heights);
  return tile;
}

/** Level-L tile `key` (L ≥ 1) from the tiles of level L − 1 in `dir`: decimation, range and error. */
TileData coarseTile(const std::filesystem::path& dir, const PyramidInfo& info, const TileKey& key) {
  const int T = info.tileSize;
  const PyramidLevel fine = info.level(key.level - 1);
  const PyramidLevel coarse = info.level(key.level);
  std::map<std::pair<int, int>, TileData> children;
  const auto child = [&](int cx, int cy) -> const TileData& {
    auto it = children.find({cx, cy});
    if (it == children.end()) {
      const TileKey childKey{key.level - 1, cx, cy};
      const std::filesystem::path path = tilePath(dir, childKey);
      const std::vector<std::uint8_t> bytes = readBytes(path);
      TileData data = decodeTile(bytes.data(), bytes.size(), path.string());
      if (data.key != childKey || data.size != T) {
        fail("{}: holds tile {}/{}/{} of size {}, not the one its path names", path.string(), data.key.level,
             data.key.y, data.key.x, data.size);
      }
      it = children.emplace(std::make_pair(cx, cy), std::move(data)).first;
    }
    return it->second;
  };
  // Level L − 1 sample (gi, gj) ∈ [2xT, 2xT + 2T]², read from one of the (up to) four children below this
  // tile: on a shared border, the child that both neighbours of the border sample lie in.
  const auto fineSample = [&](int gi, int gj) {
    const int cx = std::clamp(gi / T, 2 * key.x, std::min(2 * key.x + 1, fine.tilesX - 1));
    const int cy = std::clamp(gj / T, 2 * key.y, std::min(2 * key.y + 1, fine.tilesY - 1));
    return child(cx, cy).at(gi - cx * T, gj - cy * T);
  };

  TileData tile;
  tile.key = key;
  tile.size = T;
  tile.heights.assign(samplesOf(T), kNaN);
  for (int b = 0; b <= T; ++b) {
    const int j = key.y * T + b;
    if (j >= coarse.height) {
      break;
    }
    for (int a = 0; a <= T; ++a) {
      const int i = key.x * T + a;
      if (i >= coarse.width) {
        break;
      }
      tile.heights[static_cast<std::size_t>(b) * (T + 1) + a] =
          fineSample(std::min(2 * i, fine.width - 1), std::min(2 * j, fine.height - 1));
    }
  }
  tile.summary = rangeOf(tile.heights);

  // Error: the largest vertical distance from this tile's bilinear surface to the finer samples it covers,
  // plus the largest error of the finer tiles (each bounds its own distance to level 0).
  double error = 0.0;
  const int gi0 = 2 * key.x * T;
  const int gj0 = 2 * key.y * T;
  const int gi1 = std::min(gi0 + 2 * T, fine.width - 1);
  const int gj1 = std::min(gj0 + 2 * T, fine.height - 1);
  for (int gj = gj0; gj <= gj1; ++gj) {
    const int b = (gj - gj0) / 2;
    const bool midZ = ((gj - gj0) & 1) != 0;
    for (int gi = gi0; gi <= gi1; ++gi) {
      const float h = fineSample(gi, gj);
      if (std::isnan(h)) {
        continue;
      }
      const int a = (gi - gi0) / 2;
      const bool midX = ((gi - gi0) & 1) != 0;
      const auto at = [&](int da, int db) { return static_cast<double>(tile.at(a + da, b + db)); };
      double surface = at(0, 0);
      if (midX && midZ) {
        surface = 0.25 * (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1));
      } else if (midX) {
        surface = 0.5 * (at(0, 0) + at(1, 0));
      } else if (midZ) {
        surface = 0.5 * (at(0, 0) + at(0, 1));
      }
      if (!std::isnan(surface)) {
        error = std::max(error, std::abs(surface - h));
      }
    }
  }
  float below = 0.0f;
  for (int cy = 2 * key.y; cy <= std::min(2 * key.y + 1, fine.tilesY - 1); ++cy) {
    for (int cx = 2 * key.x; cx <= std::min(2 * key.x + 1, fine.tilesX - 1); ++cx) {
      const TileData& c = child(cx, cy);
      below = std::max(below, c.summary.error);
      widen(tile.summary, c.summary.minHeight, c.summary.maxHeight);
    }
  }
  // Rounded up so the float bound never falls below the exact distance.
  tile.summary.error =
      std::nextafter(static_cast<float>(error + below), std::numeric_limits<float>::infinity());
  if (error == 0.0 && below == 0.0f) {
    tile.summary.error = 0.0f;
  }
  return tile;
}

void checkMatches(const std::filesystem::path& path, const PyramidInfo& existing, const PyramidInfo& wanted) {
  if (existing.width != wanted.width || existing.height != wanted.height ||
      existing.tileSize != wanted.tileSize || existing.spacingX != wanted.spacingX ||
      existing.spacingZ != wanted.spacingZ) {
    fail(
        "{}: holds a pyramid of {}x{} samples at {:g} x {:g} m in tiles of {}, not {}x{} at {:g} x {:g} m in "
        "tiles of {}; remove the folder or choose another",
        path.string(), existing.width, existing.height, existing.spacingX, existing.spacingZ,
        existing.tileSize, wanted.width, wanted.height, wanted.spacingX, wanted.spacingZ, wanted.tileSize);
  }
}

} // namespace

PyramidLevel PyramidInfo::level(int level) const {
  if (level < 0 || level >= levels) {
    fail("tile pyramid: level {} outside 0..{}", level, levels - 1);
  }
  PyramidLevel l{width, height, 0, 0};
  for (int k = 0; k < level; ++k) {
    l.width = (l.width - 1 + 1) / 2 + 1;
    l.height = (l.height - 1 + 1) / 2 + 1;
  }
  l.tilesX = (l.width - 1 + tileSize - 1) / tileSize;
  l.tilesY = (l.height - 1 + tileSize - 1) / tileSize;
  return l;
}

PyramidInfo PyramidInfo::plan(int width, int height, float spacingX, float spacingZ, int tileSize) {
  if (tileSize < kMinTileSize || tileSize > kMaxTileSize) {
    fail("tile pyramid: tile size {} outside [{}, {}]", tileSize, kMinTileSize, kMaxTileSize);
  }
  if (width < 2 || height < 2 || width > kMaxRasterSide || height > kMaxRasterSide) {
    fail("tile pyramid: {}x{} samples outside [2, {}] per side", width, height, kMaxRasterSide);
  }
  PyramidInfo info;
  info.width = width;
  info.height = height;
  info.spacingX = spacingX;
  info.spacingZ = spacingZ;
  info.tileSize = tileSize;
  info.minHeight = kNaN;
  info.maxHeight = kNaN;
  info.levels = 1;
  int w = width;
  int h = height;
  info.tiles = 0;
  while (true) {
    const std::uint64_t tx = static_cast<std::uint64_t>((w - 1 + tileSize - 1) / tileSize);
    const std::uint64_t ty = static_cast<std::uint64_t>((h - 1 + tileSize - 1) / tileSize);
    info.tiles += tx * ty;
    if (tx == 1 && ty == 1) {
      break;
    }
    w = (w - 1 + 1) / 2 + 1;
    h = (h - 1 + 1) / 2 + 1;
    ++info.levels;
  }
  return info;
}

std::filesystem::path tilePath(const std::filesystem::path& dir, const TileKey& key) {
  return dir / std::to_string(key.level) / std::to_string(key.y) / (std::to_string(key.x) + ".tile");
}

std::vector<std::uint8_t> encodeTile(const TileData& tile) {
  const int n = tile.size + 1;
  if (tile.size < kMinTileSize || tile.size > kMaxTileSize || tile.heights.size() != samplesOf(tile.size)) {
    fail("tile {}/{}/{}: {} heights for size {}", tile.key.level, tile.key.y, tile.key.x, tile.heights.size(),
         tile.size);
  }
  std::vector<std::uint8_t> predicted(tile.heights.size() * 4);
  for (int row = 0; row < n; ++row) {
    predict(tile.heights.data() + static_cast<std::size_t>(row) * n, n,
            predicted.data() + static_cast<std::size_t>(row) * n * 4);
  }
  uLongf packed = compressBound(static_cast<uLong>(predicted.size()));
  std::vector<std::uint8_t> bytes(kTileHeader + packed);
  if (compress2(bytes.data() + kTileHeader, &packed, predicted.data(), static_cast<uLong>(predicted.size()),
                6) != Z_OK) {
    fail("tile {}/{}/{}: zlib cannot compress", tile.key.level, tile.key.y, tile.key.x);
  }
  bytes.resize(kTileHeader + packed);
  std::memcpy(bytes.data(), kTileMagic, 8);
  put<std::uint32_t>(bytes, 8, kPyramidVersion);
  put<std::int32_t>(bytes, 12, tile.key.level);
  put<std::int32_t>(bytes, 16, tile.key.x);
  put<std::int32_t>(bytes, 20, tile.key.y);
  put<std::int32_t>(bytes, 24, tile.size);
  put<float>(bytes, 28, tile.summary.minHeight);
  put<float>(bytes, 32, tile.summary.maxHeight);
  put<float>(bytes, 36, tile.summary.error);
  put<std::uint32_t>(bytes, 40, static_cast<std::uint32_t>(packed));
  put<std::uint32_t>(bytes, 44, tileCrc(bytes.data(), packed));
  return bytes;
}

TileData decodeTile(const std::uint8_t* bytes, std::size_t size, const std::string& name) {
  if (size < kTileHeader || std::memcmp(bytes, kTileMagic, 8) != 0) {
    fail("{}: not a Sylva tile (bad magic)", name);
  }
  if (get<std::uint32_t>(bytes, 8) != kPyramidVersion) {
    fail("{}: tile version {} (this Sylva reads {})", name, get<std::uint32_t>(bytes, 8), kPyramidVersion);
  }
  TileData tile;
  tile.key = {get<std::int32_t>(bytes, 12), get<std::int32_t>(bytes, 16), get<std::int32_t>(bytes, 20)};
  tile.size = get<std::int32_t>(bytes, 24);
  tile.summary = {get<float>(bytes, 28), get<float>(bytes, 32), get<float>(bytes, 36)};
  if (tile.size < kMinTileSize || tile.size > kMaxTileSize || tile.key.level < 0 || tile.key.level > 63 ||
      tile.key.x < 0 || tile.key.y < 0) {
    fail("{}: impossible tile header (level {}, tile {},{}, size {})", name, tile.key.level, tile.key.x,
         tile.key.y, tile.size);
  }
  const std::uint32_t packed = get<std::uint32_t>(bytes, 40);
  if (packed != size - kTileHeader) {
    fail("{}: {} bytes of data, the header says {} (truncated?)", name, size - kTileHeader, packed);
  }
  if (get<std::uint32_t>(bytes, 44) != tileCrc(bytes, packed)) {
    fail("{}: checksum mismatch (corrupt tile)", name);
  }
  const int n = tile.size + 1;
  std::vector<std::uint8_t> predicted(samplesOf(tile.size) * 4);
  uLongf unpacked = static_cast<uLongf>(predicted.size());
  if (uncompress(predicted.data(), &unpacked, bytes + kTileHeader, packed) != Z_OK ||
      unpacked != predicted.size()) {
    fail("{}: data does not inflate to {}x{} heights (corrupt tile)", name, n, n);
  }
  tile.heights.resize(samplesOf(tile.size));
  for (int row = 0; row < n; ++row) {
    unpredict(predicted.data() + static_cast<std::size_t>(row) * n * 4, n,
              tile.heights.data() + static_cast<std::size_t>(row) * n);
  }
  const TileSummary range = rangeOf(tile.heights);
  const TileSummary& s = tile.summary;
  const bool rangeOk = std::isnan(range.minHeight)
                           ? true
                           : !(range.minHeight < s.minHeight) && !(range.maxHeight > s.maxHeight);
  if (std::isnan(s.minHeight) != std::isnan(s.maxHeight) || s.minHeight > s.maxHeight || !rangeOk ||
      (std::isnan(s.minHeight) && !std::isnan(range.minHeight)) || !(s.error >= 0.0f) ||
      std::isinf(s.error) || std::isinf(s.minHeight) || std::isinf(s.maxHeight)) {
    fail("{}: the header's height range or error does not hold for its heights (corrupt tile)", name);
  }
  for (const float h : tile.heights) {
    if (std::isinf(h)) {
      fail("{}: holds an infinite height (corrupt tile)", name);
    }
  }
  return tile;
}

PyramidBuild buildPyramid(const HeightRaster& raster, const std::filesystem::path& dir,
                          const PyramidOptions& options) {
  if (options.shardCount < 1 || options.shardIndex < 0 || options.shardIndex >= options.shardCount) {
    fail("--shard {}/{}: shards count from 0, so i must lie in [0, {})", options.shardIndex,
         options.shardCount, options.shardCount);
  }
  PyramidBuild build;
  build.info = PyramidInfo::plan(raster.width(), raster.height(), raster.spacingX(), raster.spacingZ(),
                                 options.tileSize);
  PyramidInfo& info = build.info;
  info.source = options.source;
  if (info.tiles > kMaxPyramidTiles) {
    fail("tile pyramid: {}x{} samples in tiles of {} make {} tiles, more than {}; use a larger --tile-size",
         raster.width(), raster.height(), info.tileSize, info.tiles, kMaxPyramidTiles);
  }
  const std::filesystem::path json = dir / "pyramid.json";
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    fail("{}: exists and is not a folder", dir.string());
  }
  if (std::filesystem::exists(json, ec)) {
    checkMatches(json, readInfo(json), info);
  } else {
    std::filesystem::create_directories(dir, ec);
    if (!std::filesystem::is_directory(dir)) {
      fail("{}: cannot create the folder: {}", dir.string(), ec.message());
    }
    saveJsonFile(json, infoJson(info));
  }

  std::atomic<std::size_t> done{0};
  std::atomic<std::size_t> written{0};
  std::atomic<std::size_t> kept{0};
  std::atomic<std::uint64_t> writtenBytes{0};
  std::size_t total = 0;
  for (int level = 0; level < (options.shardCount > 1 ? 1 : info.levels); ++level) {
    const PyramidLevel l = info.level(level);
    const std::size_t tiles = static_cast<std::size_t>(l.tilesX) * static_cast<std::size_t>(l.tilesY);
    total += level == 0 ? (tiles + options.shardCount - 1 - options.shardIndex) / options.shardCount : tiles;
  }

  raster.prepareSweep(info.tileSize + 1);
  std::uint64_t bytes = 0;
  for (int level = 0; level < info.levels; ++level) {
    const PyramidLevel l = info.level(level);
    const std::size_t tiles = static_cast<std::size_t>(l.tilesX) * static_cast<std::size_t>(l.tilesY);
    const std::size_t step = level == 0 ? static_cast<std::size_t>(options.shardCount) : 1;
    const std::size_t first = level == 0 ? static_cast<std::size_t>(options.shardIndex) : 0;
    const std::size_t count = tiles > first ? (tiles - first + step - 1) / step : 0;
    std::vector<TileSummary> summaries(tiles);
    std::vector<std::uint64_t> sizes(tiles, 0);
    parallelFor(
        count,
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t n = begin; n < end; ++n) {
            const std::size_t k = first + n * step;
            const TileKey key{level, static_cast<int>(k % static_cast<std::size_t>(l.tilesX)),
                              static_cast<int>(k / static_cast<std::size_t>(l.tilesX))};
            const std::filesystem::path path = tilePath(dir, key);
            std::optional<TileData> tile = existingTile(path, key, info.tileSize);
            if (tile) {
              ++kept;
              sizes[k] = std::filesystem::file_size(path);
            } else {
              tile = level == 0 ? baseTile(raster, key, info.tileSize) : coarseTile(dir, info, key);
              const std::vector<std::uint8_t> encoded = encodeTile(*tile);
              writeBytes(path, encoded);
              ++written;
              writtenBytes += encoded.size();
              sizes[k] = encoded.size();
            }
            summaries[k] = tile->summary;
            const std::size_t now = ++done;
            if (options.onTile) {
              options.onTile(now, total);
            }
          }
        },
        1);
    if (options.shardCount > 1) {
      break; // a shard builds its share of level 0 only; the build without --shard completes the rest
    }
    TileSummary whole{kNaN, kNaN, 0.0f};
    for (const TileSummary& s : summaries) {
      widen(whole, s.minHeight, s.maxHeight);
    }
    if (level == 0 && std::isnan(whole.minHeight)) {
      fail("{}: all {}x{} samples are absent (nodata, NaN or masked)",
           options.source.empty() ? dir.string() : options.source, raster.width(), raster.height());
    }
    if (level == 0) {
      info.minHeight = whole.minHeight;
      info.maxHeight = whole.maxHeight;
    }
    for (const std::uint64_t s : sizes) {
      bytes += s;
    }
    writeIndex(dir, level, l, summaries);
  }
  build.written = written;
  build.kept = kept;
  build.writtenBytes = writtenBytes;
  if (options.shardCount == 1) {
    info.complete = true;
    info.bytes = bytes;
    saveJsonFile(json, infoJson(info));
  }
  return build;
}

std::shared_ptr<TilePyramid> TilePyramid::open(const std::filesystem::path& dir, std::size_t cacheBytes) {
  const std::filesystem::path json = dir / "pyramid.json";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    fail("{}: not a folder (a tile pyramid is a folder with pyramid.json)", dir.string());
  }
  if (!std::filesystem::is_regular_file(json, ec)) {
    fail("{}: no pyramid.json (not a tile pyramid; build one with `sylva terrain pyramid`)", dir.string());
  }
  std::shared_ptr<TilePyramid> pyramid(new TilePyramid());
  pyramid->mDir = dir;
  pyramid->mInfo = readInfo(json);
  pyramid->mBudget = cacheBytes;
  if (!pyramid->mInfo.complete) {
    fail("{}: field 'complete' is false: the build was interrupted or built shards only; run `sylva terrain "
         "pyramid` without --shard to finish it",
         json.string());
  }
  if (std::isnan(pyramid->mInfo.minHeight)) {
    fail("{}: fields 'minHeight' and 'maxHeight' are null in a complete pyramid", json.string());
  }
  for (int level = 0; level < pyramid->mInfo.levels; ++level) {
    pyramid->mIndex.push_back(readIndex(dir, level, pyramid->mInfo.level(level)));
  }
  return pyramid;
}

const TileSummary& TilePyramid::summary(const TileKey& key) const {
  const PyramidLevel l = mInfo.level(key.level);
  if (key.x < 0 || key.y < 0 || key.x >= l.tilesX || key.y >= l.tilesY) {
    fail("{}: no tile {},{} at level {} ({}x{} tiles)", mDir.string(), key.x, key.y, key.level, l.tilesX,
         l.tilesY);
  }
  return mIndex[static_cast<std::size_t>(key.level)]
               [static_cast<std::size_t>(key.y) * static_cast<std::size_t>(l.tilesX) + key.x];
}

void TilePyramid::touch(std::list<TileKey>::iterator it) const {
  mOrder.splice(mOrder.begin(), mOrder, it);
}

std::shared_ptr<const TileData> TilePyramid::tile(const TileKey& key) const {
  (void)summary(key); // range check
  {
    const std::lock_guard lock(mMutex);
    const auto it = mCache.find(key);
    if (it != mCache.end()) {
      touch(it->second.order);
      return it->second.tile;
    }
  }
  const std::filesystem::path path = tilePath(mDir, key);
  const std::vector<std::uint8_t> bytes = readBytes(path);
  auto data = std::make_shared<TileData>(decodeTile(bytes.data(), bytes.size(), path.string()));
  if (data->key != key || data->size != mInfo.tileSize) {
    fail("{}: holds tile {}/{}/{} of size {}, not the one its path names", path.string(), data->key.level,
         data->key.y, data->key.x, data->size);
  }
  const std::size_t tileBytes = data->heights.size() * sizeof(float);
  const std::lock_guard lock(mMutex);
  ++mRead;
  const auto it = mCache.find(key);
  if (it != mCache.end()) {
    touch(it->second.order);
    return it->second.tile;
  }
  while (!mOrder.empty() && mCachedBytes + tileBytes > mBudget) {
    const TileKey last = mOrder.back();
    mOrder.pop_back();
    mCache.erase(last);
    mCachedBytes -= tileBytes;
  }
  mOrder.push_front(key);
  mCache.emplace(key, Entry{data, mOrder.begin()});
  mCachedBytes += tileBytes;
  return data;
}

namespace {

/** Grid coordinates of world (x, z) on level `level`'s samples, clamped to them, as heightAt(field) finds
 * them. */
glm::dvec2 levelGrid(const PyramidInfo& info, const PyramidLevel& l, int level, double x, double z) {
  const double scale = std::ldexp(1.0, level);
  double gx = x / (static_cast<double>(info.spacingX) * scale);
  double gz = z / (static_cast<double>(info.spacingZ) * scale);
  gx = std::clamp(gx, 0.0, static_cast<double>(l.width - 1));
  gz = std::clamp(gz, 0.0, static_cast<double>(l.height - 1));
  return {gx, gz};
}

} // namespace

float heightInTile(const PyramidInfo& layout, const TileData& tile, double x, double z) {
  if (std::isnan(x) || std::isnan(z)) {
    return kNaN;
  }
  const PyramidLevel l = layout.level(tile.key.level);
  const glm::dvec2 g = levelGrid(layout, l, tile.key.level, x, z);
  const int T = tile.size;
  // The cell and fractions exactly as heightAt(HeightField, …) finds them (HeightQuery.cpp), kept in the
  // tile.
  const int i = std::clamp(std::min(static_cast<int>(std::floor(g.x)), l.width - 2), tile.key.x * T,
                           tile.key.x * T + T - 1);
  const int j = std::clamp(std::min(static_cast<int>(std::floor(g.y)), l.height - 2), tile.key.y * T,
                           tile.key.y * T + T - 1);
  const double tx = std::clamp(g.x - i, 0.0, 1.0);
  const double tz = std::clamp(g.y - j, 0.0, 1.0);
  const int a = i - tile.key.x * T;
  const int b = j - tile.key.y * T;
  const auto lerp = [](double p, double q, double s) {
    return s == 0.0 ? p : s == 1.0 ? q : p + s * (q - p);
  };
  const auto row = [&](int db) { return lerp(tile.at(a, b + db), tile.at(a + 1, b + db), tx); };
  if (tz == 0.0) {
    return static_cast<float>(row(0));
  }
  if (tz == 1.0) {
    return static_cast<float>(row(1));
  }
  return static_cast<float>(lerp(row(0), row(1), tz));
}

float TilePyramid::heightAt(float x, float z, int level) const {
  if (std::isnan(x) || std::isnan(z)) {
    return kNaN;
  }
  const PyramidLevel l = mInfo.level(level);
  const glm::dvec2 g = levelGrid(mInfo, l, level, x, z);
  const int i = std::min(static_cast<int>(std::floor(g.x)), l.width - 2);
  const int j = std::min(static_cast<int>(std::floor(g.y)), l.height - 2);
  const int T = mInfo.tileSize;
  const std::shared_ptr<const TileData> t =
      tile({level, std::min(i / T, l.tilesX - 1), std::min(j / T, l.tilesY - 1)});
  return heightInTile(mInfo, *t, x, z);
}

std::size_t TilePyramid::cachedBytes() const {
  const std::lock_guard lock(mMutex);
  return mCachedBytes;
}

std::size_t TilePyramid::tilesRead() const {
  const std::lock_guard lock(mMutex);
  return mRead;
}

} // namespace sylva::terrain

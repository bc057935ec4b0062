#include <sylva/terrain/HeightSources.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include "ExternalData.hpp"
#include "TempDir.hpp"
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <nlohmann/json.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace sylva::terrain {
namespace {

using test::kNaN;

// ---- helpers ----

using test::externalData;

void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string readBytes(const std::filesystem::path& path) {
  return readTextFile(path);
}

/** Expects loadHeightField to throw a one-line sylva::Error naming the file and containing `reason`. */
void expectLoadError(const std::filesystem::path& path, const std::string& reason,
                     const LoadOptions& options = {}) {
  try {
    loadHeightField(path, options);
    ADD_FAILURE() << "expected an error for " << path;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << "wanted '" << reason << "' in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

/** A `.npy` file with header dict `dict` (padded as numpy does), then `data` verbatim. */
std::string npyWithHeader(std::string header, const std::string& data, int major = 1) {
  const std::size_t prefix = major == 1 ? 10 : 12;
  while ((prefix + header.size() + 1) % 64 != 0) {
    header += ' ';
  }
  header += '\n';
  std::string bytes = "\x93NUMPY";
  bytes += static_cast<char>(major);
  bytes += '\0';
  bytes += static_cast<char>(header.size() & 0xff);
  bytes += static_cast<char>((header.size() >> 8) & 0xff);
  if (major != 1) {
    bytes += '\0';
    bytes += '\0';
  }
  return bytes + header + data;
}

/** A `.npy` file for `descr`, `shape` and order, then `data` verbatim. */
std::string npyBytes(const std::string& descr, const std::string& shape, bool fortran,
                     const std::string& data, int major = 1) {
  return npyWithHeader("{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
                           ", 'shape': " + shape + ", }",
                       data, major);
}

/** Raw bytes of `values` as type T in the given byte order. */
template <typename T> std::string raw(const std::vector<double>& values, bool bigEndian = false) {
  std::string bytes;
  for (const double v : values) {
    const T t = static_cast<T>(v);
    std::array<char, sizeof(T)> b{};
    std::memcpy(b.data(), &t, sizeof(T));
    if (bigEndian == (std::endian::native == std::endian::little)) {
      std::reverse(b.begin(), b.end());
    }
    bytes.append(b.data(), b.size());
  }
  return bytes;
}

std::uint32_t crc32(const std::string& data) {
  std::uint32_t crc = 0xffffffffu;
  for (const char c : data) {
    crc ^= static_cast<unsigned char>(c);
    for (int k = 0; k < 8; ++k) {
      crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
  }
  return ~crc;
}

void put16(std::string& out, unsigned v) {
  out += static_cast<char>(v & 0xff);
  out += static_cast<char>((v >> 8) & 0xff);
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xffff);
  put16(out, v >> 16);
}

/** A minimal zip archive with stored (uncompressed) members, as numpy.savez writes. */
std::string makeZip(const std::vector<std::pair<std::string, std::string>>& members) {
  std::string local;
  std::string central;
  for (const auto& [name, data] : members) {
    const auto offset = static_cast<std::uint32_t>(local.size());
    const std::uint32_t crc = crc32(data);
    std::string common;
    put16(common, 20);   // version needed
    put16(common, 0);    // flags
    put16(common, 0);    // stored
    put16(common, 0);    // time
    put16(common, 0x21); // date: 1980-01-01
    put32(common, crc);
    put32(common, static_cast<std::uint32_t>(data.size()));
    put32(common, static_cast<std::uint32_t>(data.size()));
    put16(common, static_cast<unsigned>(name.size()));
    put16(common, 0); // extra length
    put32(local, 0x04034b50);
    local += common + name + data;
    put32(central, 0x02014b50);
    put16(central, 20); // version made by
    central += common;
    put16(central, 0); // comment length
    put16(central, 0); // disk
    put16(central, 0); // internal attributes
    put32(central, 0); // external attributes
    put32(central, offset);
    central += name;
  }
  std::string zip = local + central;
  put32(zip, 0x06054b50);
  put16(zip, 0);
  put16(zip, 0);
  put16(zip, static_cast<unsigned>(members.size()));
  put16(zip, static_cast<unsigned>(members.size()));
  put32(zip, static_cast<std::uint32_t>(central.size()));
  put32(zip, static_cast<std::uint32_t>(local.size()));
  put16(zip, 0);
  return zip;
}

HeightField ramp(int w, int h, float spacingX = 1.0f, float spacingZ = 1.0f) {
  HeightField field(w, h, spacingX, spacingZ);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      field.at(i, j) = -20.5f + static_cast<float>(i) * 3.25f + static_cast<float>(j) * 17.0f;
    }
  }
  return field;
}

void expectSameHeights(const HeightField& a, const HeightField& b, float tolerance = 0.0f) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  for (int j = 0; j < a.height(); ++j) {
    for (int i = 0; i < a.width(); ++i) {
      if (std::isnan(a.at(i, j))) {
        EXPECT_TRUE(std::isnan(b.at(i, j))) << i << "," << j;
      } else if (tolerance == 0.0f) {
        EXPECT_EQ(a.at(i, j), b.at(i, j)) << i << "," << j;
      } else {
        EXPECT_NEAR(a.at(i, j), b.at(i, j), tolerance) << i << "," << j;
      }
    }
  }
}

// ---- PNG ----

TEST(HeightSources, Png8BitScalesByHeightScale) {
  test::TempDir dir;
  Image image(3, 2, 1, PixelType::U8);
  auto v = image.values<std::uint8_t>();
  const std::array<std::uint8_t, 6> levels = {0, 51, 102, 153, 204, 255};
  std::copy(levels.begin(), levels.end(), v.begin());
  saveImage(dir / "h8.png", image);
  LoadOptions options;
  options.heightScale = 250.0f;
  const HeightField field = loadHeightField(dir / "h8.png", options);
  ASSERT_EQ(field.width(), 3);
  ASSERT_EQ(field.height(), 2);
  EXPECT_EQ(field.spacingX(), 1.0f);
  EXPECT_EQ(field.spacingZ(), 1.0f);
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(field.at(k % 3, k / 3), levels[static_cast<std::size_t>(k)] / 255.0f * 250.0f, 1e-4f) << k;
  }
  options.spacing = 2.5f;
  const HeightField spaced = loadHeightField(dir / "h8.png", options);
  EXPECT_EQ(spaced.spacingX(), 2.5f);
  EXPECT_EQ(spaced.spacingZ(), 2.5f);
}

TEST(HeightSources, Png16BitKeepsFullPrecisionAndDefaultScaleIs100m) {
  test::TempDir dir;
  Image image(2, 2, 1, PixelType::U16);
  auto v = image.values<std::uint16_t>();
  v[0] = 0;
  v[1] = 1;
  v[2] = 32768;
  v[3] = 65535;
  saveImage(dir / "h16.png", image);
  const HeightField field = loadHeightField(dir / "h16.png");
  EXPECT_EQ(field.at(0, 0), 0.0f);
  EXPECT_NEAR(field.at(1, 0), 100.0f / 65535.0f, 1e-7f);
  EXPECT_NEAR(field.at(0, 1), 100.0f * 32768.0f / 65535.0f, 1e-4f);
  EXPECT_NEAR(field.at(1, 1), 100.0f, 1e-5f);
}

TEST(HeightSources, PngGreyAlphaMarksAbsentSamples) {
  test::TempDir dir;
  Image image(2, 2, 2, PixelType::U8);
  for (int k = 0; k < 4; ++k) {
    image.set(k % 2, k / 2, 0, 0.5f);
    image.set(k % 2, k / 2, 1, k == 2 ? 0.0f : 1.0f);
  }
  saveImage(dir / "ga.png", image);
  const HeightField field = loadHeightField(dir / "ga.png");
  EXPECT_TRUE(std::isnan(field.at(0, 1)));
  EXPECT_NEAR(field.at(1, 1), 100.0f * 128.0f / 255.0f, 1e-4f);
}

TEST(HeightSources, PngColourIsRejected) {
  test::TempDir dir;
  saveImage(dir / "rgb.png", Image(4, 4, 3, PixelType::U8));
  expectLoadError(dir / "rgb.png", "3 channels");
}

TEST(HeightSources, PngRoundTripThroughSidecarKeepsMetres) {
  test::TempDir dir;
  HeightField field = ramp(17, 9, 2.0f, 0.75f);
  field.at(3, 4) = kNaN;
  field.at(16, 8) = kNaN;
  saveHeightField(dir / "h.png", field);
  const Image image = loadImage(dir / "h.png");
  EXPECT_EQ(image.type(), PixelType::U16);
  EXPECT_EQ(image.channels(), 2); // absent samples need alpha
  const nlohmann::json sidecar = loadJsonFile(dir / "h.png.json");
  EXPECT_EQ(sidecar.at("version"), 1);
  EXPECT_EQ(sidecar.at("minHeight").get<float>(), -20.5f);
  LoadOptions options;
  options.heightScale = 1.0f; // ignored: the sidecar wins
  const HeightField loaded = loadHeightField(dir / "h.png", options);
  EXPECT_EQ(loaded.spacingX(), 2.0f);
  EXPECT_EQ(loaded.spacingZ(), 0.75f);
  const HeightFieldInfo info = heightFieldInfo(field);
  expectSameHeights(field, loaded, (info.maxHeight - info.minHeight) / 65535.0f * 0.51f);
  EXPECT_EQ(loaded.at(0, 0), -20.5f); // the minimum maps to 0 exactly
}

TEST(HeightSources, BrokenSidecarNamesTheField) {
  test::TempDir dir;
  saveHeightField(dir / "h.png", ramp(4, 4));
  nlohmann::json sidecar = loadJsonFile(dir / "h.png.json");
  sidecar["spacingX"] = -1.0;
  saveJsonFile(dir / "h.png.json", sidecar);
  expectLoadError(dir / "h.png", "/spacingX: -1 is less than 0");
  sidecar["spacingX"] = 1.0;
  sidecar["version"] = 7;
  saveJsonFile(dir / "h.png.json", sidecar);
  expectLoadError(dir / "h.png", "/version: must be 1");
}

// What a run killed between renaming the sidecar and renaming the image leaves: the new sidecar beside the
// old image. Loading must refuse the pair instead of rescaling the old image by the new range.
TEST(HeightSources, SidecarOfAnotherImageIsRejected) {
  test::TempDir dir;
  saveHeightField(dir / "old.png", ramp(8, 8, 1.0f, 1.0f));
  HeightField higher = ramp(8, 8);
  for (float& h : higher.samples()) {
    h = 2.0f * h + 500.0f;
  }
  higher.at(3, 3) += 40.0f; // not a linear image of the old ramp, whose normalised PNG would be identical
  saveHeightField(dir / "new.png", higher);
  std::filesystem::copy_file(dir / "new.png.json", dir / "old.png.json",
                             std::filesystem::copy_options::overwrite_existing);
  expectLoadError(dir / "old.png", "does not belong to");
  // The same for EXR, and a sidecar whose binding fields are malformed names them.
  saveHeightField(dir / "a.exr", ramp(5, 5));
  saveHeightField(dir / "b.exr", ramp(6, 5));
  std::filesystem::copy_file(dir / "b.exr.json", dir / "a.exr.json",
                             std::filesystem::copy_options::overwrite_existing);
  expectLoadError(dir / "a.exr", "does not belong to");
  nlohmann::json sidecar = loadJsonFile(dir / "new.png.json");
  EXPECT_TRUE(sidecar.contains("imageBytes"));
  EXPECT_EQ(sidecar.at("imageCrc32").get<std::string>().size(), 8u);
  sidecar["imageCrc32"] = 12;
  saveJsonFile(dir / "new.png.json", sidecar);
  expectLoadError(dir / "new.png", "/imageCrc32");
  // Sidecars without the binding (older files, or written by hand) still load.
  sidecar.erase("imageCrc32");
  sidecar.erase("imageBytes");
  saveJsonFile(dir / "new.png.json", sidecar);
  EXPECT_NO_THROW((void)loadHeightField(dir / "new.png"));
}

TEST(HeightSources, MaxSamplesIsCheckedBeforeLoadingEveryFormat) {
  test::TempDir dir;
  LoadOptions options;
  options.maxSamples = 24; // a 5x5 field has 25
  for (const char* name : {"h.png", "h.exr", "h.npy", "h.tif"}) {
    saveHeightField(dir / name, ramp(5, 5));
    expectLoadError(dir / name, "at most 24 in all", options);
    options.maxSamples = 25;
    EXPECT_NO_THROW((void)loadHeightField(dir / name, options)) << name;
    options.maxSamples = 24;
  }
  options.maxSamples = 3;
  expectLoadError(dir / "h.npy", "absurd maxSamples", options);
}

// ---- EXR / NPY / GeoTIFF round trips ----

TEST(HeightSources, ExrRoundTripIsExactWithNegativeHeightsAndHoles) {
  test::TempDir dir;
  HeightField field = ramp(11, 7, 0.5f, 4.0f);
  field.at(5, 5) = kNaN;
  saveHeightField(dir / "h.exr", field);
  const HeightField loaded = loadHeightField(dir / "h.exr");
  expectSameHeights(field, loaded);
  EXPECT_EQ(loaded.spacingX(), 0.5f);
  EXPECT_EQ(loaded.spacingZ(), 4.0f);
}

TEST(HeightSources, NpyRoundTripIsExact) {
  test::TempDir dir;
  HeightField field = ramp(13, 5);
  field.at(0, 0) = kNaN;
  saveHeightField(dir / "h.npy", field);
  const std::string bytes = readBytes(dir / "h.npy");
  EXPECT_EQ(bytes.find("{'descr': '<f4'"), 10u) << "format 1.0 header right after magic and length";
  expectSameHeights(field, loadHeightField(dir / "h.npy"));
}

TEST(HeightSources, GeoTiffRoundTripKeepsSpacingAndNodata) {
  test::TempDir dir;
  HeightField field = ramp(20, 12, 2.0f, 3.0f);
  field.at(7, 3) = kNaN;
  saveHeightField(dir / "h.tif", field);
  std::filesystem::copy_file(dir / "h.tif", dir / "UPPER.TIF"); // extensions are case-insensitive
  const HeightField loaded = loadHeightField(dir / "UPPER.TIF");
  expectSameHeights(field, loaded);
  EXPECT_EQ(loaded.spacingX(), 2.0f);
  EXPECT_EQ(loaded.spacingZ(), 3.0f);
  EXPECT_EQ(heightFieldInfo(loaded).absentCount, 1u);
}

// ---- NumPy details ----

struct DtypeCase {
  std::string descr;
  std::string (*encode)(const std::vector<double>&);
};

TEST(HeightSources, NpyDecodesEveryDtypeInBothByteOrders) {
  test::TempDir dir;
  const std::vector<double> values = {0, 1, 2, 100, 200, 250}; // fits every dtype
  const std::vector<DtypeCase> cases = {
      {"|u1", [](const std::vector<double>& v) { return raw<std::uint8_t>(v); }},
      {"|i1",
       [](const std::vector<double>& v) {
         return raw<std::int8_t>(std::vector<double>(v.begin(), v.end() - 2));
       }},
      {"<i2", [](const std::vector<double>& v) { return raw<std::int16_t>(v); }},
      {">i2", [](const std::vector<double>& v) { return raw<std::int16_t>(v, true); }},
      {"<u2", [](const std::vector<double>& v) { return raw<std::uint16_t>(v); }},
      {"<i4", [](const std::vector<double>& v) { return raw<std::int32_t>(v); }},
      {">i4", [](const std::vector<double>& v) { return raw<std::int32_t>(v, true); }},
      {"<f4", [](const std::vector<double>& v) { return raw<float>(v); }},
      {">f4", [](const std::vector<double>& v) { return raw<float>(v, true); }},
      {"<f8", [](const std::vector<double>& v) { return raw<double>(v); }},
      {">f8", [](const std::vector<double>& v) { return raw<double>(v, true); }},
  };
  for (const DtypeCase& c : cases) {
    const bool small = c.descr == "|i1";
    const std::string shape = small ? "(2, 2)" : "(2, 3)";
    writeBytes(dir / "a.npy", npyBytes(c.descr, shape, false, c.encode(values)));
    const HeightField field = loadHeightField(dir / "a.npy");
    const int w = small ? 2 : 3;
    ASSERT_EQ(field.width(), w) << c.descr;
    ASSERT_EQ(field.height(), 2) << c.descr;
    for (int k = 0; k < w * 2; ++k) {
      EXPECT_EQ(field.at(k % w, k / w), static_cast<float>(values[static_cast<std::size_t>(k)])) << c.descr;
    }
  }
}

TEST(HeightSources, NpyFortranOrderIsTransposedInMemory) {
  test::TempDir dir;
  // Logical array [[1, 2, 3], [4, 5, 6]] stored column-major: 1 4 2 5 3 6.
  writeBytes(dir / "f.npy", npyBytes("<i2", "(2, 3)", true, raw<std::int16_t>({1, 4, 2, 5, 3, 6})));
  const HeightField field = loadHeightField(dir / "f.npy");
  ASSERT_EQ(field.width(), 3);
  ASSERT_EQ(field.height(), 2);
  EXPECT_EQ(field.at(2, 0), 3.0f);
  EXPECT_EQ(field.at(0, 1), 4.0f);
  EXPECT_EQ(field.at(2, 1), 6.0f);
}

TEST(HeightSources, NpyVersion2HeaderAndNonFiniteSamples) {
  test::TempDir dir;
  const float inf = std::numeric_limits<float>::infinity();
  std::string data = raw<float>({1, 2, 3, 4});
  std::memcpy(data.data() + 4, &inf, 4);
  writeBytes(dir / "v2.npy", npyBytes("<f4", "(2, 2)", false, data, 2));
  const HeightField field = loadHeightField(dir / "v2.npy");
  EXPECT_EQ(field.at(0, 0), 1.0f);
  EXPECT_TRUE(std::isnan(field.at(1, 0))) << "non-finite samples become absent";
  EXPECT_EQ(heightFieldInfo(field).validCount, 3u);
}

TEST(HeightSources, NpyErrorsNameTheFileAndReason) {
  test::TempDir dir;
  const std::string six = raw<std::int16_t>({1, 2, 3, 4, 5, 6});
  writeBytes(dir / "trunc.npy", npyBytes("<i2", "(2, 3)", false, six.substr(0, 7)));
  expectLoadError(dir / "trunc.npy", "truncated");
  writeBytes(dir / "magic.npy", "PK\x03\x04 not numpy at all, just some bytes");
  expectLoadError(dir / "magic.npy", "bad magic");
  writeBytes(dir / "short.npy", "\x93NUM");
  expectLoadError(dir / "short.npy", "truncated");
  writeBytes(dir / "3d.npy", npyBytes("<i2", "(1, 2, 3)", false, six));
  expectLoadError(dir / "3d.npy", "expected a 2D array, got shape (1, 2, 3)");
  writeBytes(dir / "1d.npy", npyBytes("<i2", "(6,)", false, six));
  expectLoadError(dir / "1d.npy", "shape (6,)");
  writeBytes(dir / "one.npy", npyBytes("<i2", "(1, 1)", false, six.substr(0, 2)));
  expectLoadError(dir / "one.npy", "at least 2x2");
  writeBytes(dir / "row.npy", npyBytes("<i2", "(1, 6)", false, six));
  expectLoadError(dir / "row.npy", "at least 2x2");
  writeBytes(dir / "c8.npy", npyBytes("<c8", "(2, 3)", false, six + six + six + six));
  expectLoadError(dir / "c8.npy", "unsupported dtype '<c8'");
  writeBytes(dir / "f2.npy", npyBytes("<f2", "(2, 3)", false, six));
  expectLoadError(dir / "f2.npy", "unsupported dtype '<f2'");
  writeBytes(dir / "big.npy", npyBytes("<i2", "(70000, 2)", false, six));
  expectLoadError(dir / "big.npy", "absurd size");
  writeBytes(dir / "nan.npy",
             npyBytes("<f4", "(2, 3)", false, raw<float>({kNaN, kNaN, kNaN, kNaN, kNaN, kNaN})));
  expectLoadError(dir / "nan.npy", "all 6 samples are absent");
  std::string corrupt = npyBytes("<i2", "(2, 3)", false, six);
  corrupt.replace(corrupt.find("'shape'"), 7, "'shape'   :: ");
  writeBytes(dir / "dict.npy", corrupt);
  expectLoadError(dir / "dict.npy", "corrupt .npy header");
  std::string noShape = npyBytes("<i2", "(2, 3)", false, six);
  noShape.replace(noShape.find("'shape'"), 7, "'shope'");
  writeBytes(dir / "noshape.npy", noShape);
  expectLoadError(dir / "noshape.npy", "missing 'shape'");
  writeBytes(dir / "struct.npy",
             npyWithHeader("{'descr': [('a', '<i2')], 'fortran_order': False, 'shape': (2, 3), }", six));
  expectLoadError(dir / "struct.npy", "structured dtypes");
}

// ---- NPZ ----

TEST(HeightSources, NpzPicksTheFirst2DArrayOrTheNamedOne) {
  test::TempDir dir;
  const std::string scalar = npyBytes("<f8", "()", false, raw<double>({5.0}));
  const std::string first = npyBytes("<i2", "(2, 2)", false, raw<std::int16_t>({1, 2, 3, 4}));
  const std::string second = npyBytes("<f4", "(3, 2)", false, raw<float>({-1, -2, -3, -4, -5, -6}));
  writeBytes(dir / "a.npz", makeZip({{"meta.npy", scalar}, {"heights.npy", first}, {"other.npy", second}}));
  const HeightField picked = loadHeightField(dir / "a.npz");
  ASSERT_EQ(picked.width(), 2);
  EXPECT_EQ(picked.at(1, 1), 4.0f);
  EXPECT_EQ(picked.spacingX(), 1.0f);
  LoadOptions options;
  options.npzArray = "other";
  const HeightField named = loadHeightField(dir / "a.npz", options);
  ASSERT_EQ(named.height(), 3);
  EXPECT_EQ(named.at(1, 2), -6.0f);
  options.npzArray = "nope";
  expectLoadError(dir / "a.npz", "no array 'nope' in the archive (arrays: meta, heights, other)", options);
  options.npzArray = "meta";
  expectLoadError(dir / "a.npz", "array 'meta': expected a 2D array", options);
}

TEST(HeightSources, NpzSpacingMembersInMetresAndDegrees) {
  test::TempDir dir;
  const auto scalar = [](double v) { return npyBytes("<f8", "()", false, raw<double>({v})); };
  const std::string heights = npyBytes("<i2", "(2, 4)", false, raw<std::int16_t>({1, 2, 3, 4, 5, 6, 7, 8}));
  writeBytes(dir / "m.npz", makeZip({{"z.npy", heights}, {"dx.npy", scalar(2.5)}, {"dy.npy", scalar(4.0)}}));
  const HeightField metres = loadHeightField(dir / "m.npz");
  EXPECT_EQ(metres.spacingX(), 2.5f);
  EXPECT_EQ(metres.spacingZ(), 4.0f);
  // Degrees, detected from a lon/lat box spanning width·dx × height·dy at latitude 60°.
  writeBytes(dir / "d.npz", makeZip({{"z.npy", heights},
                                     {"dx.npy", scalar(0.01)},
                                     {"dy.npy", scalar(0.01)},
                                     {"xmin.npy", scalar(10.0)},
                                     {"xmax.npy", scalar(10.04)},
                                     {"ymin.npy", scalar(60.01)},
                                     {"ymax.npy", scalar(59.99)}}));
  const HeightField degrees = loadHeightField(dir / "d.npz");
  EXPECT_NEAR(degrees.spacingX(), 0.01 * 111320.0 * 0.5, 0.01);
  EXPECT_NEAR(degrees.spacingZ(), 0.01 * 111320.0, 0.01);
  LoadOptions options;
  options.horizontal = HorizontalUnits::Metres;
  EXPECT_FLOAT_EQ(loadHeightField(dir / "d.npz", options).spacingX(), 0.01f);
  options.spacing = 7.0f;
  EXPECT_EQ(loadHeightField(dir / "d.npz", options).spacingZ(), 7.0f);
}

TEST(HeightSources, NpzCorruptionIsReported) {
  test::TempDir dir;
  const std::string heights = npyBytes("<i2", "(2, 2)", false, raw<std::int16_t>({1, 2, 3, 4}));
  const std::string zip = makeZip({{"h.npy", heights}});
  writeBytes(dir / "cut.npz", zip.substr(0, zip.size() / 2));
  expectLoadError(dir / "cut.npz", "not a readable .npz");
  writeBytes(dir / "junk.npz", std::string(300, 'x'));
  expectLoadError(dir / "junk.npz", "not a readable .npz");
  std::string flipped = zip;
  flipped[zip.find(heights) + heights.size() - 1] ^= 0x55; // damage the data, not the CRC
  writeBytes(dir / "crc.npz", flipped);
  expectLoadError(dir / "crc.npz", "corrupt archive data");
  writeBytes(dir / "empty.npz", makeZip({{"readme.txt", "hello"}}));
  expectLoadError(dir / "empty.npz", "no .npy arrays");
}

// ---- errors common to all formats ----

TEST(HeightSources, MissingFilesAreNamedForEveryFormat) {
  for (const char* name : {"nope.png", "nope.exr", "nope.npy", "nope.npz", "nope.tif", "nope.nc"}) {
    expectLoadError(std::filesystem::path("/nonexistent/dir") / name, "not found");
  }
}

TEST(HeightSources, GarbageAndTruncatedRastersAreReportedByGdal) {
  test::TempDir dir;
  writeBytes(dir / "junk.tif", "this is not a GeoTIFF, just text");
  expectLoadError(dir / "junk.tif", "junk.tif");
  saveHeightField(dir / "whole.tif", ramp(64, 64));
  const std::string bytes = readBytes(dir / "whole.tif");
  writeBytes(dir / "cut.tif", bytes.substr(0, bytes.size() / 2));
  try {
    loadHeightField(dir / "cut.tif");
    ADD_FAILURE() << "expected an error for a truncated GeoTIFF";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cut.tif: "), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(HeightSources, AbsurdOptionsAreRejected) {
  test::TempDir dir;
  saveHeightField(dir / "h.npy", ramp(4, 4));
  for (const float scale : {0.0f, -1.0f, kNaN, std::numeric_limits<float>::infinity()}) {
    LoadOptions options;
    options.heightScale = scale;
    expectLoadError(dir / "h.npy", "heightScale", options);
  }
  for (const float spacing : {-1.0f, kNaN, std::numeric_limits<float>::infinity()}) {
    LoadOptions options;
    options.spacing = spacing;
    expectLoadError(dir / "h.npy", "spacing", options);
  }
}

TEST(HeightSources, SaveRejectsEmptyFieldsAndUnknownFormats) {
  test::TempDir dir;
  EXPECT_THROW(saveHeightField(dir / "h.png", HeightField()), Error);
  EXPECT_THROW(saveHeightField(dir / "h.png", HeightField(3, 3, 1.0f, 1.0f, kNaN)), Error);
  EXPECT_THROW(saveHeightField(dir / "h.bmp", ramp(3, 3)), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "h.bmp"));
  EXPECT_FALSE(std::filesystem::exists(dir / "h.png"));
}

TEST(HeightSources, InfoCountsValidSamples) {
  HeightField field = ramp(5, 4);
  field.at(4, 3) = kNaN; // would be the maximum
  field.at(0, 0) = kNaN; // would be the minimum
  const HeightFieldInfo info = heightFieldInfo(field);
  EXPECT_EQ(info.validCount, 18u);
  EXPECT_EQ(info.absentCount, 2u);
  EXPECT_EQ(info.minHeight, -20.5f + 3.25f);
  EXPECT_EQ(info.maxHeight, -20.5f + 3.0f * 3.25f + 3.0f * 17.0f);
  const HeightFieldInfo none = heightFieldInfo(HeightField(2, 2, 1.0f, 1.0f, kNaN));
  EXPECT_EQ(none.validCount, 0u);
  EXPECT_TRUE(std::isnan(none.minHeight));
}

// ---- real data (scripts/fetch-sample-data.sh) ----

TEST(HeightSourcesRealData, LuxembourgElevationGeoTiff) {
  const std::filesystem::path path = externalData("elev.tif");
  SYLVA_REQUIRE_EXTERNAL_DATA(path);
  const HeightField field = loadHeightField(path);
  EXPECT_EQ(field.width(), 95);
  EXPECT_EQ(field.height(), 90);
  const HeightFieldInfo info = heightFieldInfo(field);
  EXPECT_GT(info.absentCount, 0u) << "elev.tif has nodata outside Luxembourg";
  EXPECT_GT(info.validCount, 4000u);
  EXPECT_GE(info.minHeight, 100.0f);
  EXPECT_LE(info.maxHeight, 600.0f);
  EXPECT_GT(info.maxHeight - info.minHeight, 300.0f);
  // 1/120° pixels at ~49.8° N: 927.7 m north-south, 599 m east-west.
  EXPECT_NEAR(field.spacingZ(), 111320.0 / 120.0, 1.0);
  EXPECT_NEAR(field.spacingX(), 111320.0 / 120.0 * std::cos(49.8 * std::numbers::pi / 180.0), 5.0);
  // North-up: the Moselle valley (south-east, low) is lower than the Ardennes (north, high) on average.
  double north = 0.0;
  double south = 0.0;
  int northCount = 0;
  int southCount = 0;
  for (int i = 0; i < field.width(); ++i) {
    for (int j = 0; j < 30; ++j) {
      if (field.valid(i, j)) {
        north += field.at(i, j);
        ++northCount;
      }
      if (field.valid(i, field.height() - 1 - j)) {
        south += field.at(i, field.height() - 1 - j);
        ++southCount;
      }
    }
  }
  EXPECT_GT(north / northCount, south / southCount);
}

TEST(HeightSourcesRealData, JacksboroFaultNpz) {
  const std::filesystem::path path = externalData("jacksboro_fault_dem.npz");
  SYLVA_REQUIRE_EXTERNAL_DATA(path);
  const HeightField field = loadHeightField(path);
  EXPECT_EQ(field.width(), 403);
  EXPECT_EQ(field.height(), 344);
  const HeightFieldInfo info = heightFieldInfo(field);
  EXPECT_EQ(info.absentCount, 0u);
  EXPECT_EQ(info.minHeight, 236.0f);
  EXPECT_EQ(info.maxHeight, 1076.0f);
  // dx = dy = 3″ = 1/1200°, at latitude (36.733 + 36.446) / 2 ≈ 36.59°.
  EXPECT_NEAR(field.spacingZ(), 111320.0 / 1200.0, 0.01);
  EXPECT_NEAR(field.spacingX(), 111320.0 / 1200.0 * std::cos(36.5896 * std::numbers::pi / 180.0), 0.05);
  LoadOptions options;
  options.npzArray = "elevation";
  expectSameHeights(field, loadHeightField(path, options));
  options.npzArray = "dx";
  expectLoadError(path, "expected a 2D array", options);
}

// ---- real-world coordinates: geographic grids, coordinate arrays, truncated netCDF ----

namespace geo {

/** Height of the synthetic test DEM at column i, row j (row 0 = the file's first latitude). */
float testHeight(int i, int j) {
  return static_cast<float>(10 * j + i);
}

/**
 * Writes a CF netCDF grid through GDAL's multidimensional API, as climate and ocean tools do: 1D coordinate
 * variables `lonName`/`latName` with CF units and no CRS, latitude rising with the row (the common
 * south-to-north order), heights in metres.
 */
void writeCfNetCdf(const std::filesystem::path& path, bool netcdf4, const char* lonName = "lon",
                   const char* latName = "lat", const char* lonUnits = "degrees_east",
                   const char* latUnits = "degrees_north", double lat0 = 40.0, double step = 0.5, int w = 9,
                   int h = 7) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("netCDF");
  ASSERT_NE(driver, nullptr);
  const char* options[] = {netcdf4 ? "FORMAT=NC4" : "FORMAT=NC", nullptr};
  std::unique_ptr<GDALDataset> ds(
      driver->CreateMultiDimensional(path.string().c_str(), nullptr, const_cast<char**>(options)));
  ASSERT_NE(ds, nullptr);
  auto root = ds->GetRootGroup();
  auto dimLat = root->CreateDimension(latName, "", "", static_cast<GUInt64>(h));
  auto dimLon = root->CreateDimension(lonName, "", "", static_cast<GUInt64>(w));
  const auto f64 = GDALExtendedDataType::Create(GDT_Float64);
  const auto text = GDALExtendedDataType::CreateString();
  auto lat = root->CreateMDArray(latName, {dimLat}, f64);
  auto lon = root->CreateMDArray(lonName, {dimLon}, f64);
  lat->CreateAttribute("units", {}, text)->Write(latUnits);
  lon->CreateAttribute("units", {}, text)->Write(lonUnits);
  std::vector<double> lats(static_cast<std::size_t>(h));
  std::vector<double> lons(static_cast<std::size_t>(w));
  for (int j = 0; j < h; ++j) {
    lats[static_cast<std::size_t>(j)] = lat0 + step * j;
  }
  for (int i = 0; i < w; ++i) {
    lons[static_cast<std::size_t>(i)] = 5.0 + step * i;
  }
  const GUInt64 start[2] = {0, 0};
  std::size_t count[2] = {static_cast<std::size_t>(h), static_cast<std::size_t>(w)};
  ASSERT_TRUE(lat->Write(start, count, nullptr, nullptr, f64, lats.data()));
  ASSERT_TRUE(lon->Write(start, count + 1, nullptr, nullptr, f64, lons.data()));
  auto z = root->CreateMDArray("elevation", {dimLat, dimLon}, GDALExtendedDataType::Create(GDT_Float32));
  z->CreateAttribute("units", {}, text)->Write("m");
  std::vector<float> values(static_cast<std::size_t>(w * h));
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      values[static_cast<std::size_t>(j * w + i)] = testHeight(i, j);
    }
  }
  ASSERT_TRUE(
      z->Write(start, count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32), values.data()));
}

/** A 6x5 GeoTIFF with geotransform (x0, step, 0, y0, 0, -step) and, if `epsg` > 0, that CRS. */
void writeGeoTiff(const std::filesystem::path& path, double x0, double y0, double step, int epsg) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  std::unique_ptr<GDALDataset> ds(driver->Create(path.string().c_str(), 6, 5, 1, GDT_Float32, nullptr));
  ASSERT_NE(ds, nullptr);
  double gt[6] = {x0, step, 0.0, y0, 0.0, -step};
  ds->SetGeoTransform(gt);
  if (epsg > 0) {
    OGRSpatialReference srs;
    srs.importFromEPSG(epsg);
    ds->SetSpatialRef(&srs);
  }
  std::vector<float> values(30);
  for (int k = 0; k < 30; ++k) {
    values[static_cast<std::size_t>(k)] = static_cast<float>(k);
  }
  ASSERT_EQ(
      ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 6, 5, values.data(), 6, 5, GDT_Float32, 0, 0, nullptr),
      CE_None);
}

} // namespace geo

TEST(HeightSourcesGeo, CfNetCdfWithoutCrsIsGeographicAndNorthUp) {
  test::TempDir dir;
  for (const bool nc4 : {false, true}) {
    const std::filesystem::path path = dir / (nc4 ? "grid4.nc" : "grid.nc");
    geo::writeCfNetCdf(path, nc4);
    LoadReport report;
    const HeightField field = loadHeightField(path, {}, &report);
    ASSERT_EQ(field.width(), 9);
    ASSERT_EQ(field.height(), 7);
    // Latitudes 40..43 degrees: converted at 41.5 degrees.
    const double cosCentre = std::cos(41.5 * std::numbers::pi / 180.0);
    EXPECT_NEAR(field.spacingX(), 0.5 * 111320.0 * cosCentre, 0.05) << path;
    EXPECT_NEAR(field.spacingZ(), 0.5 * 111320.0, 0.05) << path;
    EXPECT_EQ(report.units, "degrees");
    EXPECT_NE(report.reason.find("degrees_east"), std::string::npos) << report.reason;
    EXPECT_NEAR(report.centreLatitude, 41.5, 1e-9);
    // Worst on the northern row (43 degrees): cos 43 / cos 41.5 - 1 = -2.35 %.
    EXPECT_NEAR(report.eastWestError, 1.0 - std::cos(43.0 * std::numbers::pi / 180.0) / cosCentre, 1e-9);
    EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
    // Row 0 is north: the file's last latitude row (43 degrees).
    EXPECT_EQ(field.at(0, 0), geo::testHeight(0, 6)) << path;
    EXPECT_EQ(field.at(8, 6), geo::testHeight(8, 0)) << path;
  }
}

TEST(HeightSourcesGeo, CfStandardNamesAndWideLatitudeRangesWarn) {
  test::TempDir dir;
  // Axes named x/y but declared as longitude/latitude degrees by their units, spanning 60 degrees.
  geo::writeCfNetCdf(dir / "wide.nc", false, "x", "y", "degree_east", "degree_north", 0.0, 10.0, 5, 7);
  LoadReport report;
  const HeightField field = loadHeightField(dir / "wide.nc", {}, &report);
  EXPECT_EQ(report.units, "degrees");
  EXPECT_NEAR(report.centreLatitude, 30.0, 1e-9);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("off by up to"), std::string::npos) << report.warnings[0];
  EXPECT_NEAR(field.spacingX(), 10.0 * 111320.0 * std::cos(30.0 * std::numbers::pi / 180.0), 0.5);
}

TEST(HeightSourcesGeo, TruncatedNetCdfIsAnErrorNeverZeros) {
  test::TempDir dir;
  for (const bool nc4 : {false, true}) {
    const std::filesystem::path whole = dir / (nc4 ? "whole4.nc" : "whole.nc");
    geo::writeCfNetCdf(whole, nc4, "lon", "lat", "degrees_east", "degrees_north", 40.0, 0.5, 64, 48);
    const std::string bytes = readBytes(whole);
    for (const std::size_t keep : {std::size_t{1000}, bytes.size() / 2, bytes.size() - 1}) {
      const std::filesystem::path cut = dir / fmt::format("cut{}_{}.nc", nc4 ? 4 : 3, keep);
      writeBytes(cut, bytes.substr(0, keep));
      expectLoadError(cut, nc4 ? "netCDF" : "truncated netCDF file");
    }
  }
  // A header that lies about a dimension's size is caught the same way.
  std::string bytes = readBytes(dir / "whole.nc");
  writeBytes(dir / "header.nc", bytes.substr(0, 200));
  expectLoadError(dir / "header.nc", "netCDF");
}

TEST(HeightSourcesGeo, GeoTiffUnitsFromTheCrsOrAWarning) {
  test::TempDir dir;
  geo::writeGeoTiff(dir / "wgs84.tif", 6.0, 50.0, 0.001, 4326);
  LoadReport report;
  const HeightField geographic = loadHeightField(dir / "wgs84.tif", {}, &report);
  EXPECT_EQ(report.units, "degrees");
  EXPECT_NE(report.reason.find("geographic"), std::string::npos) << report.reason;
  EXPECT_NEAR(report.centreLatitude, 50.0 - 0.0025, 1e-9);
  EXPECT_NEAR(geographic.spacingZ(), 111.32, 1e-3);
  geo::writeGeoTiff(dir / "utm.tif", 500000.0, 5500000.0, 25.0, 32632);
  const HeightField utm = loadHeightField(dir / "utm.tif", {}, &report);
  EXPECT_EQ(report.units, "metres");
  EXPECT_NE(report.reason.find("projected"), std::string::npos) << report.reason;
  EXPECT_FLOAT_EQ(utm.spacingX(), 25.0f);
  EXPECT_TRUE(report.warnings.empty());
  // No CRS, numbers that look like lon/lat: metres, with a warning that says so; --geographic fixes it.
  geo::writeGeoTiff(dir / "bare.tif", 6.0, 50.0, 0.001, 0);
  const HeightField bare = loadHeightField(dir / "bare.tif", {}, &report);
  EXPECT_FLOAT_EQ(bare.spacingX(), 0.001f);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("look like longitude/latitude"), std::string::npos) << report.warnings[0];
  LoadOptions options;
  options.horizontal = HorizontalUnits::Degrees;
  const HeightField forced = loadHeightField(dir / "bare.tif", options, &report);
  EXPECT_EQ(report.units, "degrees");
  EXPECT_NEAR(forced.spacingZ(), 111.32, 1e-3);
}

TEST(HeightSourcesGeo, GeographicNeedsCoordinates) {
  test::TempDir dir;
  saveHeightField(dir / "h.npy", ramp(4, 3));
  LoadOptions options;
  options.horizontal = HorizontalUnits::Degrees;
  expectLoadError(dir / "h.npy", "--geographic: the file holds no coordinates", options);
  LoadReport report;
  (void)loadHeightField(dir / "h.npy", {}, &report);
  EXPECT_EQ(report.units, "none");
  EXPECT_TRUE(report.warnings.empty());
}

TEST(HeightSourcesGeo, NpzCoordinateArraysGiveSpacingAndOrientation) {
  test::TempDir dir;
  // 3 rows x 4 columns; latitude rises with the row index (south first), as xarray writes ascending axes.
  const std::string heights =
      npyBytes("<f4", "(3, 4)", false, raw<float>({0, 1, 2, 3, 10, 11, 12, 13, 20, 21, 22, 23}));
  const auto axis = [](std::vector<double> v) {
    return npyBytes("<f8", fmt::format("({},)", v.size()), false, raw<double>(v));
  };
  for (const auto& [lonName, latName] : {std::pair{"lon", "lat"}, std::pair{"longitude", "latitude"}}) {
    const std::string file = fmt::format("{}.npz", lonName);
    writeBytes(dir / file, makeZip({{"elevation.npy", heights},
                                    {std::string(lonName) + ".npy", axis({10.0, 10.01, 10.02, 10.03})},
                                    {std::string(latName) + ".npy", axis({59.99, 60.0, 60.01})}}));
    LoadReport report;
    const HeightField field = loadHeightField(dir / file, {}, &report);
    EXPECT_EQ(report.units, "degrees") << file;
    EXPECT_NEAR(field.spacingX(), 0.01 * 111320.0 * 0.5, 0.05) << file;
    EXPECT_NEAR(field.spacingZ(), 0.01 * 111320.0, 0.05) << file;
    EXPECT_EQ(field.at(0, 0), 20.0f) << "row 0 must be the northern (last) row of " << file;
    EXPECT_EQ(field.at(3, 2), 3.0f) << file;
    EXPECT_NE(report.orientation.find("rows flipped"), std::string::npos) << report.orientation;
    // --flip-y undoes it for a user who knows the file is the other way round.
    LoadOptions options;
    options.flipY = true;
    EXPECT_EQ(loadHeightField(dir / file, options).at(0, 0), 0.0f) << file;
  }
  // x/y in metres, x falling: columns flipped; y falling (north first): rows kept. Units are unknown: warned.
  writeBytes(dir / "xy.npz", makeZip({{"z.npy", heights},
                                      {"x.npy", axis({300.0, 270.0, 240.0, 210.0})},
                                      {"y.npy", axis({5000.0, 4950.0, 4900.0})}}));
  LoadReport report;
  const HeightField xy = loadHeightField(dir / "xy.npz", {}, &report);
  EXPECT_FLOAT_EQ(xy.spacingX(), 30.0f);
  EXPECT_FLOAT_EQ(xy.spacingZ(), 50.0f);
  EXPECT_EQ(xy.at(0, 0), 3.0f);
  EXPECT_EQ(report.units, "metres");
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("units unknown"), std::string::npos);
  // Unusable coordinate arrays are named: wrong length (ignored with a warning), not monotonic (an error).
  writeBytes(
      dir / "short.npz",
      makeZip({{"z.npy", heights}, {"lon.npy", axis({1.0, 2.0})}, {"lat.npy", axis({1.0, 2.0, 3.0})}}));
  (void)loadHeightField(dir / "short.npz", {}, &report);
  EXPECT_EQ(report.units, "none");
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings[0].find("array 'lon' has shape (2,)"), std::string::npos) << report.warnings[0];
  writeBytes(dir / "zigzag.npz", makeZip({{"z.npy", heights},
                                          {"lon.npy", axis({1.0, 2.0, 1.5, 3.0})},
                                          {"lat.npy", axis({1.0, 2.0, 3.0})}}));
  expectLoadError(dir / "zigzag.npz", "coordinate array 'lon' is not strictly monotonic");
}

TEST(HeightSourcesGeo, DirectoryAsDemIsNamedAsSuch) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "dem.tif");
  expectLoadError(dir / "dem.tif", "is a directory");
  std::filesystem::create_directories(dir / "dem.npy");
  expectLoadError(dir / "dem.npy", "is a directory");
}

} // namespace
} // namespace sylva::terrain

// NumPy `.npy` / `.npz` height sources. Format:
// https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html A `.npy` file is the magic
// "\x93NUMPY", a version (1.0: 2-byte header length; 2.0/3.0: 4-byte), a Python dict literal {'descr': '<i2',
// 'fortran_order': False, 'shape': (344, 403), } padded with spaces and '\n', then the raw array. A `.npz` is
// a zip archive of `<name>.npy` members (stored or deflated).
#include "internal/HeightSourcesInternal.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Limits.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <zip.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::terrain::detail {
namespace {

constexpr std::string_view kMagic = "\x93NUMPY";
constexpr std::size_t kMaxHeaderBytes = 1u << 20;

/** One value of the header's Python literal: a string, bool, integer, None or tuple. */
struct PyValue {
  enum class Kind { Str, Bool, Int, None, Tuple, List };
  Kind kind = Kind::None;
  std::string str;
  bool boolean = false;
  long long integer = 0;
  std::vector<PyValue> items;
};

/** Recursive-descent parser for the subset of Python literals numpy writes in `.npy` headers. */
class PyLiteralParser {
public:
  PyLiteralParser(std::string_view text, const std::string& where) : mText(text), mWhere(where) {}

  std::vector<std::pair<std::string, PyValue>> parseDict() {
    skipSpace();
    expect('{');
    std::vector<std::pair<std::string, PyValue>> entries;
    for (;;) {
      skipSpace();
      if (peek() == '}') {
        ++mPos;
        break;
      }
      PyValue key = parseValue();
      if (key.kind != PyValue::Kind::Str) {
        error("header dict key is not a string");
      }
      skipSpace();
      expect(':');
      entries.emplace_back(key.str, parseValue());
      skipSpace();
      if (peek() == ',') {
        ++mPos;
      } else if (peek() != '}') {
        error("expected ',' or '}' in header dict");
      }
    }
    skipSpace();
    if (mPos != mText.size()) {
      error("unexpected text after the header dict");
    }
    return entries;
  }

private:
  [[noreturn]] void error(std::string_view what) const {
    fail("{}: corrupt .npy header: {} (at character {})", mWhere, what, mPos);
  }
  char peek() const { return mPos < mText.size() ? mText[mPos] : '\0'; }
  void skipSpace() {
    while (mPos < mText.size() &&
           (mText[mPos] == ' ' || mText[mPos] == '\t' || mText[mPos] == '\n' || mText[mPos] == '\r')) {
      ++mPos;
    }
  }
  void expect(char c) {
    if (peek() != c) {
      error(fmt::format("expected '{}'", c));
    }
    ++mPos;
  }
  bool consumeWord(std::string_view word) {
    if (mText.substr(mPos, word.size()) == word) {
      mPos += word.size();
      return true;
    }
    return false;
  }

  PyValue parseValue() {
    skipSpace();
    PyValue value;
    const char c = peek();
    if (c == '\'' || c == '"') {
      ++mPos;
      value.kind = PyValue::Kind::Str;
      while (peek() != c) {
        if (mPos >= mText.size()) {
          error("unterminated string");
        }
        if (peek() == '\\') {
          ++mPos; // the escaped character must exist too: a backslash may not end the header
          if (mPos >= mText.size()) {
            error("unterminated string");
          }
        }
        value.str += mText[mPos++];
      }
      ++mPos;
    } else if (c == '(' || c == '[') {
      const char close = c == '(' ? ')' : ']';
      value.kind = c == '(' ? PyValue::Kind::Tuple : PyValue::Kind::List;
      ++mPos;
      for (;;) {
        skipSpace();
        if (peek() == close) {
          ++mPos;
          break;
        }
        value.items.push_back(parseValue());
        skipSpace();
        if (peek() == ',') {
          ++mPos;
        } else if (peek() != close) {
          error("expected ',' or a closing bracket");
        }
      }
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      value.kind = PyValue::Kind::Int;
      bool negative = false;
      if (c == '-') {
        negative = true;
        ++mPos;
      }
      int digits = 0;
      while (peek() >= '0' && peek() <= '9') {
        if (++digits > 18) {
          error("integer too large");
        }
        value.integer = value.integer * 10 + (peek() - '0');
        ++mPos;
      }
      if (digits == 0) {
        error("expected digits");
      }
      if (peek() == 'L') { // Python 2 long suffix, written by old numpy versions
        ++mPos;
      }
      value.integer = negative ? -value.integer : value.integer;
    } else if (consumeWord("True")) {
      value.kind = PyValue::Kind::Bool;
      value.boolean = true;
    } else if (consumeWord("False")) {
      value.kind = PyValue::Kind::Bool;
    } else if (consumeWord("None")) {
      value.kind = PyValue::Kind::None;
    } else {
      error("unexpected character in header");
    }
    return value;
  }

  std::string_view mText;
  const std::string& mWhere;
  std::size_t mPos = 0;
};

/** Parsed `.npy` header. */
struct NpyHeader {
  char byteOrder = '<'; ///< '<' little, '>' big, '|' not applicable
  char kind = 'f';      ///< 'i' signed, 'u' unsigned, 'f' float
  int itemSize = 4;     ///< bytes per element
  bool fortranOrder = false;
  std::vector<long long> shape;
  std::size_t dataOffset = 0; ///< bytes from the start of the file to the data

  std::string descr() const { return fmt::format("{}{}{}", byteOrder, kind, itemSize); }
  std::size_t elementCount() const {
    std::size_t n = 1;
    for (const long long d : shape) {
      n *= static_cast<std::size_t>(d);
    }
    return n;
  }
  std::string shapeText() const {
    std::string text = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) {
      text += fmt::format("{}{}", i ? ", " : "", shape[i]);
    }
    return text + (shape.size() == 1 ? ",)" : ")");
  }
};

/** Bytes needed before the header dict can be parsed: 0 if `prefix` is too short to know yet. */
std::size_t headerEnd(std::span<const std::byte> prefix, const std::string& where) {
  if (prefix.size() < 10) {
    return 0;
  }
  if (std::memcmp(prefix.data(), kMagic.data(), kMagic.size()) != 0) {
    fail("{}: not a .npy array (bad magic)", where);
  }
  const auto major = static_cast<unsigned>(prefix[6]);
  const auto byteAt = [&](std::size_t i) { return static_cast<std::size_t>(prefix[i]); };
  if (major == 1) {
    return 10 + (byteAt(8) | (byteAt(9) << 8));
  }
  if (major == 2 || major == 3) {
    if (prefix.size() < 12) {
      return 0;
    }
    const std::size_t length = byteAt(8) | (byteAt(9) << 8) | (byteAt(10) << 16) | (byteAt(11) << 24);
    if (length > kMaxHeaderBytes) {
      fail("{}: corrupt .npy header (header length {} bytes)", where, length);
    }
    return 12 + length;
  }
  fail("{}: unsupported .npy format version {}", where, major);
}

NpyHeader parseHeader(std::span<const std::byte> bytes, const std::string& where) {
  const std::size_t end = headerEnd(bytes, where);
  if (end == 0 || end > bytes.size()) {
    fail("{}: truncated .npy header", where);
  }
  const std::size_t start = static_cast<unsigned>(bytes[6]) == 1 ? 10 : 12;
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()) + start, end - start);
  NpyHeader header;
  header.dataOffset = end;
  bool haveDescr = false;
  bool haveOrder = false;
  bool haveShape = false;
  for (const auto& [key, value] : PyLiteralParser(text, where).parseDict()) {
    if (key == "descr") {
      if (value.kind != PyValue::Kind::Str) {
        fail("{}: structured dtypes are not supported (need a plain numeric array)", where);
      }
      const std::string& d = value.str;
      if (d.size() < 3 || std::string_view("<>|=").find(d[0]) == std::string_view::npos) {
        fail("{}: unsupported dtype '{}'", where, d);
      }
      header.byteOrder = d[0] == '=' ? (std::endian::native == std::endian::little ? '<' : '>') : d[0];
      header.kind = d[1];
      const std::string size = d.substr(2);
      const bool ok = (header.kind == 'i' || header.kind == 'u')
                          ? (size == "1" || size == "2" || size == "4" || size == "8")
                          : header.kind == 'f' && (size == "4" || size == "8");
      if (!ok) {
        fail("{}: unsupported dtype '{}' (supported: int8/16/32/64, uint8/16/32/64, float32/64)", where, d);
      }
      header.itemSize = std::stoi(size);
      haveDescr = true;
    } else if (key == "fortran_order") {
      if (value.kind != PyValue::Kind::Bool) {
        fail("{}: corrupt .npy header: 'fortran_order' is not True/False", where);
      }
      header.fortranOrder = value.boolean;
      haveOrder = true;
    } else if (key == "shape") {
      if (value.kind != PyValue::Kind::Tuple) {
        fail("{}: corrupt .npy header: 'shape' is not a tuple", where);
      }
      for (const PyValue& item : value.items) {
        if (item.kind != PyValue::Kind::Int || item.integer < 0) {
          fail("{}: corrupt .npy header: 'shape' holds a non-integer or negative size", where);
        }
        header.shape.push_back(item.integer);
      }
      haveShape = true;
    }
  }
  if (!haveDescr || !haveOrder || !haveShape) {
    fail("{}: corrupt .npy header: missing '{}'", where,
         !haveDescr   ? "descr"
         : !haveOrder ? "fortran_order"
                      : "shape");
  }
  // Bound the element count before anyone multiplies the sizes (no overflow below).
  double elements = 1.0;
  for (const long long d : header.shape) {
    elements *= static_cast<double>(d);
  }
  if (elements > static_cast<double>(kMaxHeightFieldSamples) * 16.0) {
    fail("{}: absurd array shape {}", where, header.shapeText());
  }
  return header;
}

/** Element `index` of the raw data as a double, honouring byte order and type. */
double element(const std::byte* data, std::size_t index, const NpyHeader& header) {
  std::array<std::byte, 8> raw{};
  std::memcpy(raw.data(), data + index * static_cast<std::size_t>(header.itemSize),
              static_cast<std::size_t>(header.itemSize));
  const bool fileLittle = header.byteOrder != '>';
  if (header.itemSize > 1 && fileLittle != (std::endian::native == std::endian::little)) {
    std::reverse(raw.begin(), raw.begin() + header.itemSize);
  }
  const auto as = [&]<typename T>(T) {
    T v;
    std::memcpy(&v, raw.data(), sizeof(T));
    return static_cast<double>(v);
  };
  switch (header.kind) {
  case 'i':
    return header.itemSize == 1   ? as(std::int8_t{})
           : header.itemSize == 2 ? as(std::int16_t{})
           : header.itemSize == 4 ? as(std::int32_t{})
                                  : as(std::int64_t{});
  case 'u':
    return header.itemSize == 1   ? as(std::uint8_t{})
           : header.itemSize == 2 ? as(std::uint16_t{})
           : header.itemSize == 4 ? as(std::uint32_t{})
                                  : as(std::uint64_t{});
  default:
    return header.itemSize == 4 ? as(float{}) : as(double{});
  }
}

/** Checks that `bytes` hold all the data the header promises; returns a pointer to it. */
const std::byte* dataOf(std::span<const std::byte> bytes, const NpyHeader& header, const std::string& where) {
  const std::size_t expected = header.elementCount() * static_cast<std::size_t>(header.itemSize);
  const std::size_t available = bytes.size() - header.dataOffset;
  if (available < expected) {
    fail("{}: truncated: shape {} of {} needs {} bytes of data, found {}", where, header.shapeText(),
         header.descr(), expected, available);
  }
  return bytes.data() + header.dataOffset;
}

/** A 2D array as a HeightField with 1 m spacing (rows = shape[0] north to south, columns = shape[1]). */
HeightField toHeightField(std::span<const std::byte> bytes, const std::string& where,
                          const std::filesystem::path& path, const LoadOptions& limits) {
  const NpyHeader header = parseHeader(bytes, where);
  if (header.shape.size() != 2) {
    fail("{}: expected a 2D array, got shape {}", where, header.shapeText());
  }
  const long long rows = header.shape[0];
  const long long cols = header.shape[1];
  try {
    checkHeightFieldSize(path, cols, rows, limits);
  } catch (const Error& e) {
    // Re-label with the array name for .npz members; checkHeightFieldSize names only the file.
    const std::string message = e.what();
    const std::string prefix = path.string() + ": ";
    fail("{}: {}", where, message.starts_with(prefix) ? message.substr(prefix.size()) : message);
  }
  const std::byte* data = dataOf(bytes, header, where);
  HeightField field(static_cast<int>(cols), static_cast<int>(rows));
  std::vector<float>& out = field.samples();
  for (long long r = 0; r < rows; ++r) {
    for (long long c = 0; c < cols; ++c) {
      const long long index = header.fortranOrder ? c * rows + r : r * cols + c;
      out[static_cast<std::size_t>(r * cols + c)] =
          toHeight(element(data, static_cast<std::size_t>(index), header));
    }
  }
  return field;
}

std::vector<std::byte> readWholeFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    fail("{}: file not found", path.string());
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("{}: cannot open file", path.string());
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) {
    fail("{}: cannot read file size: {}", path.string(), ec.message());
  }
  if (size > kMaxHeaderBytes + kMaxHeightFieldSamples * 8) {
    fail("{}: file too large ({} bytes) for a height field", path.string(), size);
  }
  std::vector<std::byte> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) {
    fail("{}: read failed", path.string());
  }
  return bytes;
}

// ---- .npz through libzip ----

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};
struct ZipFileCloser {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};
using ZipPtr = std::unique_ptr<zip_t, ZipCloser>;
using ZipFilePtr = std::unique_ptr<zip_file_t, ZipFileCloser>;

class NpzArchive {
public:
  explicit NpzArchive(const std::filesystem::path& path) : mPath(path.string()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      fail("{}: file not found", mPath);
    }
    mFileSize = std::filesystem::file_size(path, ec);
    int code = 0;
    mZip.reset(zip_open(mPath.c_str(), ZIP_RDONLY, &code));
    if (!mZip) {
      zip_error_t error;
      zip_error_init_with_code(&error, code);
      const std::string reason = zip_error_strerror(&error);
      zip_error_fini(&error);
      fail("{}: not a readable .npz (zip) archive: {}", mPath, reason);
    }
    const zip_int64_t count = zip_get_num_entries(mZip.get(), 0);
    for (zip_int64_t i = 0; i < count; ++i) {
      const char* name = zip_get_name(mZip.get(), static_cast<zip_uint64_t>(i), 0);
      if (name == nullptr) {
        fail("{}: corrupt archive: entry {} has no name", mPath, i);
      }
      const std::string_view entry(name);
      if (entry.ends_with(".npy")) {
        mNames.emplace_back(entry.substr(0, entry.size() - 4));
        mIndices.push_back(static_cast<zip_uint64_t>(i));
      }
    }
    if (mNames.empty()) {
      fail("{}: archive holds no .npy arrays", mPath);
    }
  }

  const std::vector<std::string>& names() const { return mNames; }
  std::string label(const std::string& name) const { return fmt::format("{}: array '{}'", mPath, name); }

  std::optional<std::size_t> find(const std::string& name) const {
    const auto it = std::find(mNames.begin(), mNames.end(), name);
    return it == mNames.end() ? std::nullopt : std::optional<std::size_t>(it - mNames.begin());
  }

  /** The member's bytes; `limit` > 0 reads at most that many (enough for a header). */
  std::vector<std::byte> read(std::size_t member, std::size_t limit = 0) const {
    const std::string where = label(mNames[member]);
    zip_stat_t stat;
    zip_stat_init(&stat);
    if (zip_stat_index(mZip.get(), mIndices[member], 0, &stat) != 0 || (stat.valid & ZIP_STAT_SIZE) == 0) {
      fail("{}: corrupt archive: {}", where, zip_strerror(mZip.get()));
    }
    if (stat.size > kMaxHeaderBytes + kMaxHeightFieldSamples * 8) {
      fail("{}: member too large ({} bytes) for a height field", where, stat.size);
    }
    if (limit == 0) {
      // Never allocate what the zip directory claims before two independent checks agree with it: the
      // member's own .npy header (read with a bounded prefix) and the compressed bytes that really exist.
      checkClaimedSize(member, stat, where);
    }
    ZipFilePtr file(zip_fopen_index(mZip.get(), mIndices[member], 0));
    if (!file) {
      fail("{}: cannot open member: {}", where, zip_strerror(mZip.get()));
    }
    std::size_t wanted = static_cast<std::size_t>(stat.size);
    if (limit > 0) {
      wanted = std::min(wanted, limit);
    }
    std::vector<std::byte> bytes(wanted);
    std::size_t done = 0;
    while (done < wanted) {
      const zip_int64_t n = zip_fread(file.get(), bytes.data() + done, wanted - done);
      if (n < 0) {
        fail("{}: corrupt archive data: {}", where, zip_file_strerror(file.get()));
      }
      if (n == 0) {
        fail("{}: truncated archive member ({} of {} bytes)", where, done, wanted);
      }
      done += static_cast<std::size_t>(n);
    }
    if (limit == 0) {
      // Reading to the end makes libzip verify the CRC; a mismatch shows up here.
      std::byte extra{};
      if (zip_fread(file.get(), &extra, 1) < 0) {
        fail("{}: corrupt archive data: {}", where, zip_file_strerror(file.get()));
      }
    }
    return bytes;
  }

  /**
   * Rejects a member whose uncompressed size (from the zip directory) disagrees with its `.npy` header, or
   * exceeds what its compressed bytes can expand to (stored: equal; deflate: at most kMaxDeflateRatio times),
   * or whose compressed bytes exceed the archive itself. So a small file can never make us allocate much.
   */
  void checkClaimedSize(std::size_t member, const zip_stat_t& stat, const std::string& where) const {
    const NpyHeader head = header(member);
    const std::size_t implied =
        head.dataOffset + head.elementCount() * static_cast<std::size_t>(head.itemSize);
    if (stat.size != implied) {
      fail("{}: corrupt archive: the member claims {} bytes but its .npy header (shape {} of {}) implies {}",
           where, stat.size, head.shapeText(), head.descr(), implied);
    }
    if ((stat.valid & ZIP_STAT_COMP_SIZE) != 0) {
      const bool stored = (stat.valid & ZIP_STAT_COMP_METHOD) != 0 && stat.comp_method == ZIP_CM_STORE;
      const std::uint64_t most = stored ? stat.comp_size : stat.comp_size * kMaxDeflateRatio + 1024;
      if (stat.comp_size > mFileSize || stat.size > most) {
        fail("{}: corrupt archive: {} compressed bytes (archive: {}) cannot hold the {} bytes the member "
             "claims",
             where, stat.comp_size, mFileSize, stat.size);
      }
    }
  }

  /** Header of a member, reading only its first bytes. */
  NpyHeader header(std::size_t member) const {
    const std::string where = label(mNames[member]);
    std::vector<std::byte> prefix = read(member, 12);
    const std::size_t end = headerEnd(prefix, where);
    if (end == 0) {
      fail("{}: truncated .npy header", where);
    }
    return parseHeader(read(member, end), where);
  }

  /** A scalar member (shape () or all dimensions 1) as a double; nullopt if absent or not a scalar. */
  std::optional<double> scalar(const std::string& name) const {
    const auto member = find(name);
    if (!member) {
      return std::nullopt;
    }
    const std::vector<std::byte> bytes = read(*member);
    const std::string where = label(name);
    const NpyHeader header = parseHeader(bytes, where);
    if (header.elementCount() != 1) {
      return std::nullopt;
    }
    return element(dataOf(bytes, header, where), 0, header);
  }

private:
  std::string mPath;
  std::uintmax_t mFileSize = 0;
  ZipPtr mZip;
  std::vector<std::string> mNames;
  std::vector<zip_uint64_t> mIndices;
};

/** A 1D coordinate array of `length` finite values; nullopt when absent, or (with a warning) unusable. */
std::optional<std::vector<double>> coordinateArray(const NpzArchive& archive, const std::string& name,
                                                   int length, const std::filesystem::path& path,
                                                   LoadReport& report) {
  const auto member = archive.find(name);
  if (!member) {
    return std::nullopt;
  }
  const NpyHeader head = archive.header(*member);
  if (head.shape.size() != 1 || head.shape[0] != length) {
    warn(path, report,
         fmt::format("array '{}' has shape {}; a coordinate array needs ({},): ignored", name,
                     head.shapeText(), length));
    return std::nullopt;
  }
  const std::vector<std::byte> bytes = archive.read(*member);
  const std::string where = archive.label(name);
  const NpyHeader header = parseHeader(bytes, where);
  const std::byte* data = dataOf(bytes, header, where);
  std::vector<double> values(static_cast<std::size_t>(length));
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = element(data, i, header);
    if (!std::isfinite(values[i])) {
      warn(path, report, fmt::format("array '{}' holds {} at index {}: ignored", name, values[i], i));
      return std::nullopt;
    }
  }
  return values;
}

/**
 * Step of an evenly spaced coordinate array (last − first) / (n − 1); warns when the steps vary by more than
 * 1 % (the mean is used) and fails when it does not move monotonically.
 */
double coordinateStep(const std::vector<double>& values, const std::string& name,
                      const std::filesystem::path& path, LoadReport& report) {
  const double step = (values.back() - values.front()) / static_cast<double>(values.size() - 1);
  double worst = 0.0;
  for (std::size_t i = 1; i < values.size(); ++i) {
    const double d = values[i] - values[i - 1];
    if (d == 0.0 || (d > 0.0) != (step > 0.0)) {
      fail("{}: coordinate array '{}' is not strictly monotonic (index {}: {} after {})", path.string(), name,
           i, values[i], values[i - 1]);
    }
    worst = std::max(worst, std::abs(d - step) / std::abs(step));
  }
  if (worst > 0.01) {
    warn(path, report,
         fmt::format("coordinate array '{}' is unevenly spaced (steps differ by up to {:.1f} %); its mean "
                     "step {:g} is used",
                     name, 100.0 * worst, step));
  }
  return step;
}

/**
 * Coordinates from 1D arrays named as NumPy/xarray users write them (`lon`/`lat`, `longitude`/`latitude`,
 * `x`/`y`), flipping `field` so that row 0 is north and column 0 west. nullopt when there are none.
 */
std::optional<FileCoordinates> coordinatesFromArrays(const NpzArchive& archive, HeightField& field,
                                                     const std::filesystem::path& path, LoadReport& report) {
  static constexpr std::array<std::pair<const char*, const char*>, 3> kPairs = {
      {{"lon", "lat"}, {"longitude", "latitude"}, {"x", "y"}}};
  for (const auto& [xName, yName] : kPairs) {
    const bool hasX = archive.find(xName).has_value();
    const bool hasY = archive.find(yName).has_value();
    if (!hasX && !hasY) {
      continue;
    }
    if (hasX != hasY) {
      warn(path, report,
           fmt::format("coordinate array '{}' without '{}': both are needed, so both are ignored",
                       hasX ? xName : yName, hasX ? yName : xName));
      continue;
    }
    const auto xs = coordinateArray(archive, xName, field.width(), path, report);
    const auto ys = coordinateArray(archive, yName, field.height(), path, report);
    if (!xs || !ys) {
      continue;
    }
    const double stepX = coordinateStep(*xs, xName, path, report);
    const double stepY = coordinateStep(*ys, yName, path, report);
    const bool degrees = std::string_view(xName) != "x";
    FileCoordinates c;
    c.kind = degrees ? FileCoordinates::Kind::Degrees : FileCoordinates::Kind::Unknown;
    c.stepX = std::abs(stepX);
    c.stepZ = std::abs(stepY);
    c.south = std::min(ys->front(), ys->back());
    c.north = std::max(ys->front(), ys->back());
    const double west = std::min(xs->front(), xs->back());
    const double east = std::max(xs->front(), xs->back());
    c.looksLikeDegrees = west >= -180.0 && east <= 360.0 && c.south >= -90.0 && c.north <= 90.0 &&
                         c.stepX < 1.0 && c.stepZ < 1.0;
    c.reason = degrees ? fmt::format("coordinate arrays '{}' and '{}' (longitude/latitude)", xName, yName)
                       : fmt::format("coordinate arrays '{}' and '{}' (no units in the file)", xName, yName);
    std::vector<std::string> flips;
    if (stepY > 0.0) {
      flipRows(field);
      flips.push_back(
          fmt::format("rows flipped: '{}' rises with the row index, so the last row is north", yName));
    }
    if (stepX < 0.0) {
      flipColumns(field);
      flips.push_back(fmt::format("columns flipped: '{}' falls with the column index", xName));
    }
    report.orientation = flips.empty() ? fmt::format("row 0 is north ('{}' falls with the row index)", yName)
                                       : fmt::format("{}", fmt::join(flips, "; "));
    return c;
  }
  return std::nullopt;
}

/**
 * Coordinates from the scalar members `dx`, `dy` (e.g. matplotlib's Jacksboro DEM): degrees when `xmin`,
 * `xmax`, `ymin`, `ymax` describe a lon/lat box spanning width·dx × height·dy (±1 sample), else unknown.
 */
FileCoordinates coordinatesFromSteps(const NpzArchive& archive, const HeightField& field,
                                     const std::string& path) {
  std::optional<double> dx = archive.scalar("dx");
  std::optional<double> dy = archive.scalar("dy");
  FileCoordinates c;
  if (!dx && !dy) {
    return c;
  }
  dx = dx ? dx : dy;
  dy = dy ? dy : dx;
  if (!std::isfinite(*dx) || !std::isfinite(*dy) || *dx == 0.0 || *dy == 0.0) {
    fail("{}: spacing members dx={} dy={} must be finite and non-zero", path, *dx, *dy);
  }
  c.stepX = std::abs(*dx);
  c.stepZ = std::abs(*dy);
  c.kind = FileCoordinates::Kind::Unknown;
  c.reason = "scalar members 'dx'/'dy' (no units in the file)";
  const auto xmin = archive.scalar("xmin");
  const auto xmax = archive.scalar("xmax");
  const auto ymin = archive.scalar("ymin");
  const auto ymax = archive.scalar("ymax");
  if (ymin && ymax) {
    c.south = std::min(*ymin, *ymax);
    c.north = std::max(*ymin, *ymax);
  }
  if (xmin && xmax && ymin && ymax) {
    const auto spans = [](double lo, double hi, int count, double step) {
      return std::abs(std::abs(hi - lo) - count * step) <= 1.01 * step;
    };
    const bool lonLat = std::abs(*xmin) <= 180.0 && std::abs(*xmax) <= 180.0 && std::abs(*ymin) <= 90.0 &&
                        std::abs(*ymax) <= 90.0;
    c.looksLikeDegrees = lonLat;
    if (lonLat && spans(*xmin, *xmax, field.width(), c.stepX) &&
        spans(*ymin, *ymax, field.height(), c.stepZ)) {
      c.kind = FileCoordinates::Kind::Degrees;
      c.reason = "scalar members 'dx'/'dy' with a longitude/latitude box 'xmin'..'ymax' of that size";
    }
  }
  return c;
}

} // namespace

HeightField loadNpy(const std::filesystem::path& path, const LoadOptions& options, LoadReport& report) {
  const std::vector<std::byte> bytes = readWholeFile(path);
  HeightField field = toHeightField(bytes, path.string(), path, options);
  applyCoordinates(path, field, FileCoordinates{}, options, report);
  finishHeightField(path, field, options, report);
  return field;
}

HeightField loadNpz(const std::filesystem::path& path, const LoadOptions& options, LoadReport& report) {
  const NpzArchive archive(path);
  std::size_t member = 0;
  if (!options.npzArray.empty()) {
    const auto found = archive.find(options.npzArray);
    if (!found) {
      std::string names;
      for (const std::string& name : archive.names()) {
        names += (names.empty() ? "" : ", ") + name;
      }
      fail("{}: no array '{}' in the archive (arrays: {})", path.string(), options.npzArray, names);
    }
    member = *found;
  } else {
    bool found = false;
    for (std::size_t i = 0; i < archive.names().size() && !found; ++i) {
      if (archive.header(i).shape.size() == 2) {
        member = i;
        found = true;
      }
    }
    if (!found) {
      fail("{}: archive holds no 2D array", path.string());
    }
  }
  const std::vector<std::byte> bytes = archive.read(member);
  HeightField field = toHeightField(bytes, archive.label(archive.names()[member]), path, options);
  std::optional<FileCoordinates> coordinates = coordinatesFromArrays(archive, field, path, report);
  if (!coordinates) {
    coordinates = coordinatesFromSteps(archive, field, path.string());
  }
  applyCoordinates(path, field, *coordinates, options, report);
  finishHeightField(path, field, options, report);
  return field;
}

void saveNpy(const std::filesystem::path& path, const HeightField& field) {
  std::string header = fmt::format("{{'descr': '<f4', 'fortran_order': False, 'shape': ({}, {}), }}",
                                   field.height(), field.width());
  // Pad so that magic + version + length + header is a multiple of 64 bytes, ending in '\n' (format 1.0).
  const std::size_t total = (10 + header.size() + 1 + 63) / 64 * 64;
  header.append(total - 10 - header.size() - 1, ' ');
  header += '\n';
  std::string bytes(kMagic);
  bytes += '\x01';
  bytes += '\x00';
  bytes += static_cast<char>(header.size() & 0xff);
  bytes += static_cast<char>((header.size() >> 8) & 0xff);
  bytes += header;
  const std::size_t dataStart = bytes.size();
  bytes.resize(dataStart + field.samples().size() * 4);
  for (std::size_t i = 0; i < field.samples().size(); ++i) {
    auto bits = std::bit_cast<std::uint32_t>(field.samples()[i]);
    for (int b = 0; b < 4; ++b) {
      bytes[dataStart + i * 4 + static_cast<std::size_t>(b)] = static_cast<char>((bits >> (8 * b)) & 0xffu);
    }
  }
  writeTextFile(path, bytes);
}

} // namespace sylva::terrain::detail

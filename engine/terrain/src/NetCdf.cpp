// Truncation check for classic netCDF files (CDF-1, CDF-2 "64-bit offset", CDF-5 "64-bit data"). Format:
// https://docs.unidata.ucar.edu/netcdf-c/current/file_format_specifications.html. The netCDF library reads
// past the end of a classic file as zeros without an error, so GDAL hands back a DEM of 0 m for a file cut
// after its header. We walk the header (big-endian: magic, numrecs, dimensions, global attributes, variables
// with their sizes and offsets) and compare the bytes the variables need with the file's size.
#include "internal/HeightSourcesInternal.hpp"

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace sylva::terrain::detail {
namespace {

constexpr std::uint32_t kDimensionTag = 0x0A;
constexpr std::uint32_t kVariableTag = 0x0B;
constexpr std::uint32_t kAttributeTag = 0x0C;
constexpr std::uint64_t kStreaming = 0xFFFFFFFFu;
/** Headers are small; a declared count beyond this is corrupt (and would make the walk slow). */
constexpr std::uint64_t kMaxListEntries = 1u << 20;

/** Bytes of one value of netCDF type `type` (1 byte .. 11 uint64), 0 if unknown. */
std::uint64_t typeSize(std::uint32_t type) {
  static constexpr std::array<std::uint64_t, 12> kSizes = {0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
  return type < kSizes.size() ? kSizes[type] : 0;
}

/** Sequential big-endian reader over the header bytes; throws `<file>: ...` when they run out. */
class HeaderReader {
public:
  HeaderReader(std::ifstream& in, std::string name, int version)
      : mIn(in), mName(std::move(name)), mVersion(version) {}

  std::uint64_t u32() { return read(4); }
  /** NON_NEG and counts: 8 bytes in CDF-5, else 4. */
  std::uint64_t count() { return read(mVersion == 5 ? 8 : 4); }
  /** OFFSET (variable `begin`): 4 bytes in CDF-1, else 8. */
  std::uint64_t offset() { return read(mVersion == 1 ? 4 : 8); }

  void skip(std::uint64_t bytes) {
    const std::uint64_t padded = (bytes + 3) / 4 * 4;
    if (padded > static_cast<std::uint64_t>(std::numeric_limits<std::streamoff>::max())) {
      corrupt("a header entry claims an absurd size");
    }
    mIn.seekg(static_cast<std::streamoff>(padded), std::ios::cur);
    if (!mIn) {
      corrupt("the header runs past the end of the file");
    }
  }

  void name() {
    const std::uint64_t length = count();
    if (length > kMaxListEntries) {
      corrupt("a header name claims an absurd length");
    }
    skip(length);
  }

  /** A list header: ABSENT (0, 0) or `tag` followed by the element count. */
  std::uint64_t list(std::uint32_t tag) {
    const std::uint64_t found = u32();
    const std::uint64_t n = count();
    if (found == 0 && n == 0) {
      return 0;
    }
    if (found != tag || n > kMaxListEntries) {
      corrupt("the header's lists are malformed");
    }
    return n;
  }

  void attributes() {
    const std::uint64_t n = list(kAttributeTag);
    for (std::uint64_t i = 0; i < n; ++i) {
      name();
      const std::uint64_t size = typeSize(static_cast<std::uint32_t>(u32()));
      const std::uint64_t values = count();
      if (size == 0 || values > (std::uint64_t{1} << 40)) {
        corrupt("an attribute has an unknown type or absurd length");
      }
      skip(size * values);
    }
  }

  [[noreturn]] void corrupt(const char* why) const {
    fail("{}: corrupt or truncated netCDF header ({})", mName, why);
  }

private:
  std::uint64_t read(int bytes) {
    std::array<unsigned char, 8> b{};
    mIn.read(reinterpret_cast<char*>(b.data()), bytes);
    if (!mIn) {
      corrupt("the header runs past the end of the file");
    }
    std::uint64_t value = 0;
    for (int i = 0; i < bytes; ++i) {
      value = value << 8 | b[static_cast<std::size_t>(i)];
    }
    return value;
  }

  std::ifstream& mIn;
  std::string mName;
  int mVersion;
};

/** a · b, or UINT64_MAX on overflow. */
std::uint64_t mulSat(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) {
    return std::numeric_limits<std::uint64_t>::max();
  }
  return a * b;
}

std::uint64_t addSat(std::uint64_t a, std::uint64_t b) {
  return b > std::numeric_limits<std::uint64_t>::max() - a ? std::numeric_limits<std::uint64_t>::max()
                                                           : a + b;
}

} // namespace

void checkNetCdfClassicSize(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 4> magic{};
  if (!in.read(magic.data(), 4) || magic[0] != 'C' || magic[1] != 'D' || magic[2] != 'F') {
    return; // not a classic netCDF file (netCDF-4 is HDF5: its library reports truncation itself)
  }
  const int version = magic[3];
  if (version != 1 && version != 2 && version != 5) {
    fail("{}: unknown netCDF classic version {} (expected 1, 2 or 5)", path.string(), version);
  }
  const std::string name = path.string();
  std::error_code ec;
  const std::uintmax_t fileSize = std::filesystem::file_size(path, ec);
  if (ec) {
    fail("{}: cannot read the file size: {}", name, ec.message());
  }
  HeaderReader header(in, name, version);
  const std::uint64_t numrecs = header.count();

  std::vector<std::uint64_t> dimensions(static_cast<std::size_t>(header.list(kDimensionTag)));
  for (std::uint64_t& length : dimensions) {
    header.name();
    length = header.count(); // 0 = the record (unlimited) dimension
  }
  header.attributes();

  struct Variable {
    std::uint64_t bytesPerRecord = 0; // all of it for a fixed-size variable
    std::uint64_t begin = 0;
    bool record = false;
  };
  std::vector<Variable> variables(static_cast<std::size_t>(header.list(kVariableTag)));
  std::uint64_t recordSize = 0;
  for (Variable& v : variables) {
    header.name();
    const std::uint64_t rank = header.count();
    if (rank > 1024) {
      header.corrupt("a variable claims an absurd rank");
    }
    std::uint64_t elements = 1;
    for (std::uint64_t d = 0; d < rank; ++d) {
      const std::uint64_t id = header.count();
      if (id >= dimensions.size()) {
        header.corrupt("a variable names a dimension that does not exist");
      }
      const std::uint64_t length = dimensions[static_cast<std::size_t>(id)];
      if (d == 0 && length == 0) {
        v.record = true;
      } else {
        elements = mulSat(elements, length);
      }
    }
    header.attributes();
    const std::uint64_t size = typeSize(static_cast<std::uint32_t>(header.u32()));
    if (size == 0) {
      header.corrupt("a variable has an unknown type");
    }
    const std::uint64_t vsize = header.count();
    v.begin = header.offset();
    v.bytesPerRecord = mulSat(elements, size);
    if (v.record) {
      recordSize = addSat(recordSize, vsize);
    }
  }

  const auto records =
      std::count_if(variables.begin(), variables.end(), [](const Variable& v) { return v.record; });
  if (records == 1) {
    // The one exception in the layout: a single record variable's records are not padded to 4 bytes.
    recordSize = std::find_if(variables.begin(), variables.end(), [](const Variable& v) {
                   return v.record;
                 })->bytesPerRecord;
  }
  // The smallest file that holds every variable's values (ignoring the padding after the last one).
  std::uint64_t needed = 0;
  for (const Variable& v : variables) {
    std::uint64_t end = addSat(v.begin, v.bytesPerRecord);
    if (v.record) {
      if (numrecs == kStreaming || numrecs == 0) {
        continue;
      }
      end = addSat(addSat(v.begin, mulSat(numrecs - 1, recordSize)), v.bytesPerRecord);
    }
    needed = std::max(needed, end);
  }
  if (fileSize < needed) {
    fail(
        "{}: truncated netCDF file: its header declares {} bytes of data, the file has {} ({:.1f} % missing)",
        name, needed, fileSize, 100.0 * static_cast<double>(needed - fileSize) / static_cast<double>(needed));
  }
}

} // namespace sylva::terrain::detail

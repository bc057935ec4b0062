// Replays every committed fuzz input (fuzz/corpus/<target>: seeds and what fuzzing kept;
// fuzz/regressions/<target>: inputs that once crashed, hung or over-allocated) through the same harness
// libFuzzer runs. In the ASan build a reintroduced defect fails here; in every build an input that escapes
// with anything but sylva::Error does.
#include "Harness.hpp"
#include "TempDir.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/terrain/HeightSources.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzReplay : public testing::TestWithParam<std::string> {};

TEST_P(FuzzReplay, CorpusAndRegressionsAreRejectedCleanly) {
  std::size_t inputs = 0;
  for (const char* folder : {"fuzz/corpus/", "fuzz/regressions/"}) {
    const fs::path dir = sylva::test::sourcePath(folder + GetParam());
    if (!fs::is_directory(dir)) {
      continue;
    }
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
      if (!entry.is_regular_file() || entry.path().filename().string().starts_with(".")) {
        continue;
      }
      SCOPED_TRACE(entry.path().string());
      const std::vector<std::uint8_t> bytes = readBytes(entry.path());
      EXPECT_NO_THROW(sylva::fuzz::runTarget(GetParam(), bytes));
      ++inputs;
    }
  }
  // Every target has a seed corpus; an empty one would make this test vacuous.
  EXPECT_GE(inputs, 3u) << "fuzz/corpus/" << GetParam() << " has too few inputs";
}

std::vector<std::string> targetNames() {
  std::vector<std::string> names;
  for (const sylva::fuzz::Target& target : sylva::fuzz::targets()) {
    names.emplace_back(target.name);
  }
  return names;
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, testing::ValuesIn(targetNames()),
                         [](const auto& info) { return info.param; });

TEST(FuzzHarness, UnknownTargetIsRejected) {
  EXPECT_THROW(sylva::fuzz::runTarget("no-such-target", {}), std::invalid_argument);
}

// The two defects a first fuzzing probe found (shared/fuzz-findings), checked for their exact messages: the
// harness run above only proves they no longer crash.
TEST(FuzzRegressions, NpyBackslashAtHeaderEndIsAnUnterminatedString) {
  const sylva::test::TempDir dir;
  const std::vector<std::uint8_t> bytes =
      readBytes(sylva::test::sourcePath("fuzz/regressions/npy/npy-header-backslash-overflow.npy"));
  std::ofstream(dir / "x.npy", std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  try {
    (void)sylva::terrain::loadHeightField(dir / "x.npy");
    FAIL() << "loaded a corrupt header";
  } catch (const sylva::Error& e) {
    EXPECT_NE(std::string(e.what()).find("corrupt .npy header"), std::string::npos) << e.what();
  }
}

TEST(FuzzRegressions, NpzMemberClaimingGigabytesIsRejectedBeforeAllocating) {
  const fs::path path = sylva::test::sourcePath("fuzz/regressions/npz/npz-claims-4gb-member.npz");
  try {
    (void)sylva::terrain::loadHeightField(path);
    FAIL() << "loaded a corrupt archive";
  } catch (const sylva::Error& e) {
    EXPECT_NE(std::string(e.what()).find("corrupt archive"), std::string::npos) << e.what();
  }
}

/** The one-line message loading `relative` (a committed regression input) fails with. */
std::string loadError(const std::string& relative) {
  try {
    (void)sylva::terrain::loadHeightField(sylva::test::sourcePath(relative));
  } catch (const sylva::Error& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST(FuzzRegressions, TiffWithoutItsBlocksIsRejectedBeforeReadingZeros) {
  EXPECT_NE(loadError("fuzz/regressions/gdal/tiff-claims-15k-by-16k-without-blocks.tif")
                .find("blocks are missing from the file"),
            std::string::npos);
}

TEST(FuzzRegressions, JsonNumberOverflowIsInvalidJson) {
  try {
    (void)sylva::loadJsonFile(sylva::test::sourcePath("fuzz/regressions/json/number-overflows-double.json"));
    FAIL() << "parsed";
  } catch (const sylva::Error& e) {
    EXPECT_NE(std::string(e.what()).find("invalid JSON: number overflow"), std::string::npos) << e.what();
  }
}

TEST(FuzzRegressions, IncludeNameTooLongIsAMissingInclude) {
  const std::vector<std::uint8_t> bytes =
      readBytes(sylva::test::sourcePath("fuzz/regressions/shader/include-name-too-long.glsl"));
  EXPECT_NO_THROW(sylva::fuzz::runTarget("shader", bytes));
}

} // namespace

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/core/Random.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace sylva {
namespace {

TEST(Rng, SameSeedSameSequence) {
  Rng a(42);
  Rng b(42);
  Rng c(43);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const std::uint32_t va = a.nextU32();
    EXPECT_EQ(va, b.nextU32());
    differs |= va != c.nextU32();
  }
  EXPECT_TRUE(differs);
}

TEST(Rng, UniformAndBelowStayInRange) {
  Rng rng(7);
  double sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const float u = rng.uniform();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
    ASSERT_LT(rng.below(10), 10u);
  }
  EXPECT_NEAR(sum / 100000.0, 0.5, 0.01);
}

TEST(Parallel, CoversEveryIndexOnce) {
  std::vector<std::atomic<int>> hits(10007);
  parallelFor(hits.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      hits[i]++;
    }
  });
  for (const auto& h : hits) {
    ASSERT_EQ(h.load(), 1);
  }
}

TEST(Parallel, PropagatesExceptions) {
  EXPECT_THROW(parallelFor(
                   1000,
                   [](std::size_t b, std::size_t) {
                     if (b > 0) {
                       fail("chunk {}", b);
                     }
                   },
                   1),
               Error);
}

TEST(Files, JsonErrorsNameFileLineAndColumn) {
  test::TempDir dir;
  std::ofstream(dir / "scene.json") << "{\n  \"version\": 1,\n  \"oops\" 3\n}\n";
  try {
    loadJsonFile(dir / "scene.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scene.json:3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadJsonFile(dir / "missing.json"), Error);
}

TEST(Files, AtomicWriteCleansUpOnFailure) {
  test::TempDir dir;
  EXPECT_THROW(writeFileAtomically(dir / "out.bin",
                                   [](const std::filesystem::path& tmp) {
                                     std::ofstream(tmp) << "partial";
                                     fail("writer failed");
                                   }),
               Error);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  saveJsonFile(dir / "sub/ok.json", nlohmann::json{{"version", 1}});
  EXPECT_EQ(loadJsonFile(dir / "sub/ok.json")["version"], 1);
}

std::vector<std::string> entries(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// A SIGKILLed writer leaves its temporary; the next write of the same file removes it (its process is gone),
// and leaves alone temporaries of other files and of live processes.
TEST(Files, NextWriteRemovesTemporariesOfDeadWriters) {
  test::TempDir dir;
  const pid_t child = ::fork();
  if (child == 0) {
    ::_exit(0);
  }
  ::waitpid(child, nullptr, 0); // a pid that no longer runs
  const std::string dead = ".out.txt.tmp." + std::to_string(child);
  const std::string alive = ".out.txt.tmp.1"; // init: always alive
  const std::string other = ".other.txt.tmp." + std::to_string(child);
  for (const std::string& name : {dead, alive, other}) {
    std::ofstream(dir / name) << "partial";
  }
  writeTextFile(dir / "out.txt", "complete");
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{other, alive, "out.txt"}));
}

// An atomic save called on one of this process's own temporaries (an image written inside the writer of its
// sidecar pair) writes straight into it: no temporary of a temporary.
TEST(Files, AtomicWriteIntoOwnTemporaryNeedsNoSecondTemporary) {
  test::TempDir dir;
  writeFileAtomically(dir / "pair.png", [&](const std::filesystem::path& tmp) {
    writeTextFile(tmp, "image");
    EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{tmp.filename().string()}));
  });
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"pair.png"}));
}

} // namespace
} // namespace sylva

namespace sylva {
namespace {

TEST(Files, TheDataFolderDoesNotDependOnTheWorkingDirectory) {
  const std::filesystem::path before = dataDirectory();
  EXPECT_TRUE(before.is_absolute());
  EXPECT_TRUE(std::filesystem::is_regular_file(dataPath("scenes/meadow.json"))) << before;
  const test::TempDir dir;
  const std::filesystem::path cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir.path());
  const std::filesystem::path elsewhere = dataDirectory();
  std::filesystem::current_path(cwd);
  EXPECT_EQ(elsewhere, before);
  ::setenv("SYLVA_DATA_DIR", dir.path().c_str(), 1);
  EXPECT_EQ(dataPath("x/y.json"), dir.path().lexically_normal() / "x" / "y.json");
  ::unsetenv("SYLVA_DATA_DIR");
  EXPECT_EQ(dataDirectory(), before);
}

TEST(Files, ADirectoryGivenAsAFileIsNamedInOneLine) {
  const test::TempDir dir;
  const std::filesystem::path project = dir / "project.json";
  std::filesystem::create_directories(project);
  try {
    (void)loadJsonFile(project);
    ADD_FAILURE() << "a directory was read";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), project.string() + ": is a directory, not a file");
  }
}

TEST(Files, OutputsAreCheckedBeforeTheWork) {
  const test::TempDir dir;
  EXPECT_NO_THROW(checkOutputFile(dir / "a" / "b.png", "--out")); // directories are made when writing
  try {
    checkOutputFile(dir.path(), "--gif", "anim.gif");
    ADD_FAILURE() << "a directory was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "--gif " + dir.path().string() +
                                         ": is a directory; give a file name (e.g. " +
                                         (dir / "anim.gif").string() + ")");
  }
  writeTextFile(dir / "file", "x");
  EXPECT_THROW(checkOutputFile(dir / "file" / "b.png", "--out"), Error);
}

TEST(Files, JsonVersionEnvelope) {
  EXPECT_NO_THROW(requireJsonVersion(nlohmann::json{{"version", 2}}, 2, "x.json"));
  const auto message = [](const nlohmann::json& json) {
    try {
      requireJsonVersion(json, 1, "rules.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(nlohmann::json::array()), "rules.json: /: expected an object, got array");
  EXPECT_EQ(message(nlohmann::json{{"layers", 1}}), "rules.json: /version: missing field");
  EXPECT_EQ(message(nlohmann::json{{"version", "1"}}), "rules.json: /version: must be 1");
  EXPECT_EQ(message(nlohmann::json{{"version", 3}}), "rules.json: /version: must be 1");
}

} // namespace
} // namespace sylva

namespace sylva {
namespace {

TEST(Progress, CancelAllReachesEveryLiveProgressAndIsForgottenAfterwards) {
  {
    Progress a("a", 10);
    Progress b("b", 10);
    EXPECT_TRUE(Progress::anyActive());
    EXPECT_FALSE(a.cancelled());
    Progress::cancelAll();
    EXPECT_TRUE(a.cancelled());
    EXPECT_TRUE(b.cancelled());
  }
  EXPECT_FALSE(Progress::anyActive());
  Progress c("c", 1);
  EXPECT_FALSE(c.cancelled()) << "a finished job's Ctrl-C must not cancel the next one";
  c.cancel();
  EXPECT_TRUE(c.cancelled());
}

} // namespace
} // namespace sylva

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/scene/Sequence.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>
#include <set>

namespace sylva::scene {
namespace {

namespace fs = std::filesystem;

std::string errorOf(auto&& body) {
  try {
    body();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

/** A w × h gradient with `channels` channels (rendered frames are RGBA). */
Image testImage(int w, int h, int channels = 3) {
  Image image(w, h, channels, PixelType::U8);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.set(x, y, 0, static_cast<float>(x) / static_cast<float>(w));
      image.set(x, y, 1, static_cast<float>(y) / static_cast<float>(h));
    }
  }
  return image;
}

TEST(Sequence, ParsesFrames) {
  FrameRange r = parseFrames("7");
  ASSERT_EQ(r.spans.size(), 1u);
  EXPECT_EQ(r.spans[0], std::make_pair(7, 7));
  EXPECT_EQ(r.count(), 1);
  r = parseFrames("0-119");
  EXPECT_EQ(r.count(), 120);
  r = parseFrames("20-29, 0-9 ,15");
  ASSERT_EQ(r.spans.size(), 3u);
  EXPECT_EQ(r.spans[0], std::make_pair(0, 9)); // sorted
  EXPECT_EQ(r.spans[1], std::make_pair(15, 15));
  EXPECT_EQ(r.spans[2], std::make_pair(20, 29));
  EXPECT_EQ(r.count(), 21);
  EXPECT_EQ(r.frames().front(), 0);
  EXPECT_EQ(r.frames().back(), 29);
  EXPECT_EQ(parseFrames("0-9,10-19").count(), 20); // touching is not overlapping
  EXPECT_EQ(parseFrames("0-999999").count(), 1000000);
}

TEST(Sequence, RefusesBadFrames) {
  EXPECT_EQ(errorOf([] { parseFrames("0-15,10-20"); }), "--frames: 10-20 overlaps 0-15");
  EXPECT_EQ(errorOf([] { parseFrames("10-20,0-15"); }), "--frames: 0-15 overlaps 10-20");
  EXPECT_EQ(errorOf([] { parseFrames("0-100,40,200-300"); }), "--frames: 40 overlaps 0-100");
  EXPECT_EQ(errorOf([] { parseFrames("0-100,200-300,50-60"); }), "--frames: 50-60 overlaps 0-100");
  EXPECT_EQ(errorOf([] { parseFrames("5,5"); }), "--frames: 5 overlaps 5");
  EXPECT_EQ(errorOf([] { parseFrames("20-10"); }), "--frames: 20-10 ends before it starts");
  EXPECT_EQ(errorOf([] { parseFrames("1000000"); }), "--frames: 1000000 is more than 999999");
  EXPECT_EQ(errorOf([] { parseFrames("-5"); }), "--frames: '-5' is not N or A-B (frame numbers 0 to 999999)");
  EXPECT_EQ(errorOf([] { parseFrames("a-b"); }),
            "--frames: 'a-b' is not N or A-B (frame numbers 0 to 999999)");
  EXPECT_EQ(errorOf([] { parseFrames("0-5,"); }), "--frames: '' is not N or A-B (frame numbers 0 to 999999)");
  EXPECT_EQ(errorOf([] { parseFrames("99999999999999999999"); }),
            "--frames: '99999999999999999999' is not N or A-B (frame numbers 0 to 999999)");
  EXPECT_THROW(parseFrames(""), Error);
}

TEST(Sequence, ParsesShards) {
  const Shard s = parseShard("2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  EXPECT_EQ(parseShard("0/1").count, 1);
  EXPECT_EQ(parseShard("4095/4096").index, 4095);
  EXPECT_EQ(errorOf([] { parseShard("5/5"); }),
            "--shard: index 5 is not below the shard count 5 (shards are numbered from 0)");
  EXPECT_EQ(errorOf([] { parseShard("0/0"); }), "--shard: 0 shards is outside [1, 4096]");
  EXPECT_EQ(errorOf([] { parseShard("0/4097"); }), "--shard: 4097 shards is outside [1, 4096]");
  EXPECT_EQ(errorOf([] { parseShard("1"); }), "--shard: '1' is not i/n (e.g. 0/4: the first of four shards)");
  EXPECT_THROW(parseShard("-1/4"), Error);
}

TEST(Sequence, ShardsPartitionTheRange) {
  const FrameRange range = parseFrames("3-17,40-44,100");
  const std::vector<int> all = range.frames();
  for (int n : {1, 2, 3, 7, 21, 50}) {
    std::multiset<int> seen;
    for (int i = 0; i < n; ++i) {
      const std::vector<int> part = framesOf(range, Shard{i, n});
      EXPECT_TRUE(std::is_sorted(part.begin(), part.end()));
      seen.insert(part.begin(), part.end());
    }
    EXPECT_EQ(std::vector<int>(seen.begin(), seen.end()), all) << n << " shards";
  }
  // Frame f belongs to shard (index of f in the range) % n: interleaved, so shards finish together.
  EXPECT_EQ(framesOf(range, Shard{1, 4}), (std::vector<int>{4, 8, 12, 16, 42}));
}

TEST(Sequence, FrameNames) {
  EXPECT_EQ(frameName(0), "frame_00000.png");
  EXPECT_EQ(frameName(42), "frame_00042.png");
  EXPECT_EQ(frameName(999999), "frame_999999.png");
  EXPECT_THROW(frameName(-1), Error);
}

TEST(Sequence, FrameCompleteOnlyForWholePngsOfTheRightSize) {
  test::TempDir dir;
  const fs::path path = dir / frameName(3);
  EXPECT_FALSE(frameComplete(path, 16, 8)); // missing
  writeFrameAtomically(path, testImage(16, 8));
  EXPECT_TRUE(frameComplete(path, 16, 8));
  EXPECT_FALSE(frameComplete(path, 8, 16)); // another size
  // Truncated at every length, from the header to the last byte of IEND: never complete.
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 60u);
  const fs::path cut = dir / frameName(4);
  for (std::size_t n : {std::size_t{0}, std::size_t{7}, std::size_t{33}, bytes.size() / 2, bytes.size() - 13,
                        bytes.size() - 1}) {
    std::ofstream(cut, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(n));
    EXPECT_FALSE(frameComplete(cut, 16, 8)) << n << " of " << bytes.size() << " bytes";
  }
  std::ofstream(cut, std::ios::binary | std::ios::trunc) << "not a png at all";
  EXPECT_FALSE(frameComplete(cut, 16, 8));
  fs::create_directories(dir / frameName(5));
  EXPECT_FALSE(frameComplete(dir / frameName(5), 16, 8)); // a directory
}

TEST(Sequence, AtomicWriteLeavesNoTemporaryAndRoundTrips) {
  test::TempDir dir;
  const fs::path path = dir / "out" / "deep" / frameName(1);
  const Image image = testImage(9, 7);
  writeFrameAtomically(path, image);
  EXPECT_EQ(loadPng(path), image);
  writeFrameAtomically(path, testImage(9, 7)); // overwrite
  int files = 0;
  for (const auto& entry : fs::directory_iterator(path.parent_path())) {
    EXPECT_EQ(entry.path().filename(), frameName(1));
    ++files;
  }
  EXPECT_EQ(files, 1);
  // A failing write (empty image) leaves neither the frame nor a temporary.
  const fs::path bad = dir / frameName(2);
  EXPECT_THROW(writeFrameAtomically(bad, Image()), Error);
  EXPECT_FALSE(fs::exists(bad));
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(Sequence, TemporaryFromAKilledRunIsIgnoredAndRemoved) {
  test::TempDir dir;
  // A killed run left a half-written temporary (pid that cannot be running) and no frame.
  const fs::path stale = dir / (frameName(7) + ".tmp-999999999");
  std::ofstream(stale, std::ios::binary) << "\x89PNG\r\n\x1a\n partial";
  // A run in progress (this process) is writing another one.
  const fs::path live = dir / (frameName(8) + ".tmp-" + std::to_string(::getpid()));
  std::ofstream(live, std::ios::binary) << "in progress";
  std::ofstream(dir / "notes.tmp-1") << "not ours";
  EXPECT_FALSE(frameComplete(dir / frameName(7), 4, 4)); // the frame is still to do
  EXPECT_EQ(removeStaleTemporaries(dir.path()), 1);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(dir / "notes.tmp-1"));
  EXPECT_EQ(removeStaleTemporaries(dir.path(), true), 1);
  EXPECT_FALSE(fs::exists(live));
  EXPECT_EQ(removeStaleTemporaries(dir / "missing"), 0);
  // The resumed run writes the frame normally.
  writeFrameAtomically(dir / frameName(7), testImage(4, 4));
  EXPECT_TRUE(frameComplete(dir / frameName(7), 4, 4));
}

TEST(Sequence, APlanDrawsOnlyTheFramesStillMissingAndEncodesOnceTheRangeIsComplete) {
  test::TempDir dir;
  SequenceJob job;
  job.file = test::sourcePath("data/scenes/meadow.json").string();
  job.frames = "0-5";
  job.shard = "1/2";
  job.out = (dir / "seq").string();
  job.width = 8;
  job.height = 6;
  // Shard 1 of 2 draws every other frame of the range; the one already complete is skipped.
  writeFrameAtomically(dir / "seq" / frameName(3), testImage(8, 6));
  SequencePlan plan = planSequence(job);
  EXPECT_TRUE(plan.sequence);
  EXPECT_EQ(plan.frames, (std::vector<int>{1, 3, 5}));
  EXPECT_EQ(plan.todo, (std::vector<int>{1, 5}));
  EXPECT_EQ(plan.camera, plan.desc.output.camera);
  EXPECT_EQ(plan.framePath(5), dir / "seq" / frameName(5));
  job.overwrite = true;
  EXPECT_EQ(planSequence(job).todo, (std::vector<int>{1, 3, 5}));

  // The GIF waits for every shard's frames, then holds the whole range.
  job.gif = (dir / "anim.gif").string();
  plan = planSequence(job);
  EXPECT_TRUE(finishSequence(plan).empty());
  EXPECT_FALSE(fs::exists(job.gif));
  for (int f = 0; f <= 5; ++f) {
    writeFrameAtomically(plan.framePath(f), testImage(8, 6, 4));
  }
  EXPECT_EQ(finishSequence(plan), (std::vector<std::string>{job.gif}));
  EXPECT_TRUE(fs::exists(job.gif));

  // The job is checked before anything is drawn.
  SequenceJob still;
  still.file = job.file;
  still.shard = "1/2";
  EXPECT_EQ(errorOf([&] { planSequence(still); }), "--shard 1/2: needs a sequence (--frames A-B)");
  still.shard = "0/1";
  still.camera = "nowhere";
  EXPECT_EQ(errorOf([&] { planSequence(still); }), "--camera nowhere: " + job.file + " has no such camera");
  SequenceJob onFile = job;
  onFile.out = (dir / "anim.gif").string();
  EXPECT_EQ(errorOf([&] { planSequence(onFile); }),
            "--out " + onFile.out + ": a sequence needs a directory, and this is a file");
}

} // namespace
} // namespace sylva::scene

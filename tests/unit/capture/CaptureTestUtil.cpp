#include "CaptureTestUtil.hpp"

namespace sylva::capture::testutil {

void expectEqual(const BladeModelFile& a, const BladeModelFile& b) {
  EXPECT_EQ(a.generator, b.generator);
  ASSERT_EQ(a.blades.size(), b.blades.size());
  for (std::size_t i = 0; i < a.blades.size(); ++i) {
    const BladeModel& x = a.blades[i];
    const BladeModel& y = b.blades[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.bendAxis, y.bendAxis);
    EXPECT_EQ(x.hasColour, y.hasColour);
    EXPECT_EQ(x.colour, y.colour);
    EXPECT_EQ(x.source.file, y.source.file);
    EXPECT_EQ(x.source.kind, y.source.kind);
    EXPECT_EQ(x.source.frame, y.source.frame);
    EXPECT_EQ(x.source.cluster, y.source.cluster);
    EXPECT_EQ(x.source.blade, y.source.blade);
    EXPECT_EQ(x.source.intrinsics, y.source.intrinsics);
    EXPECT_EQ(x.source.relativeDepth, y.source.relativeDepth);
    EXPECT_EQ(x.source.medialAxis, y.source.medialAxis);
    EXPECT_EQ(x.source.motionFrames, y.source.motionFrames);
    EXPECT_EQ(x.source.mu, y.source.mu);
    ASSERT_EQ(x.lods.size(), y.lods.size());
    for (std::size_t l = 0; l < x.lods.size(); ++l) {
      EXPECT_EQ(x.lods[l].positions, y.lods[l].positions);
      EXPECT_EQ(x.lods[l].widths, y.lods[l].widths);
      EXPECT_EQ(x.lods[l].normals, y.lods[l].normals);
    }
  }
}

} // namespace sylva::capture::testutil

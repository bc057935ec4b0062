// The editing layer the folding editor is built on: random command sequences undo exactly, dirty tracking,
// autosave and recovery, import/export of zones and profiles, motion templates.
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Field.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/folding/Templates.hpp>

#include "Patterns.hpp"
#include "TempDir.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>

namespace sylva::folding {
namespace {

using nlohmann::json;

json sessionProject() {
  return json::parse(R"({"format":"sylva-fold","version":1,"seed":5,
    "atlas":{"images":[{"id":"img","file":"img.png"}]},
    "profiles":[{"id":"p","period_s":2,"fn":{"type":"sine"}},{"id":"q","period_s":3,"fn":{"type":"linear"}}],
    "zones":[{"id":"z","image":"img","profile":"p",
              "shape":{"type":"polygon","pts":[[8,8],[88,10],[86,56],[10,54]]},
              "tools":[{"type":"points","pairs":[[[40,30],[44,34]],[[60,20],[58,26]]]}]},
             {"id":"r","image":"img","profile":"q","shape":{"type":"rect","min":[20,20],"max":[60,50]},
              "tools":[{"type":"translate","v":[2,1]}]}]})");
}

std::string dump(const Project& p) {
  return toJson(p).dump();
}

TEST(FoldingSession, RandomEditSequencesUndoToTheOriginalByteForByte) {
  const Project start = parseProject(sessionProject(), "s.json");
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    EditHistory history(start);
    Rng rng(seed);
    int applied = 0;
    int refused = 0;
    for (int step = 0; step < 150; ++step) {
      const int zone = static_cast<int>(rng.below(2));
      const Project before = history.project();
      try {
        switch (rng.below(8)) {
        case 0:
          moveZoneVertex(history, zone, static_cast<int>(rng.below(4)),
                         Vec2(rng.uniform(0, 96), rng.uniform(0, 64)));
          break;
        case 1:
          addTool(history, zone, TranslateTool{Vec2(rng.uniform(-5, 5), rng.uniform(-5, 5))});
          break;
        case 2:
          removeTool(history, zone, static_cast<int>(rng.below(3)));
          break;
        case 3:
          movePointAnchor(history, 0, 0, static_cast<int>(rng.below(2)), static_cast<int>(rng.below(2)),
                          Vec2(rng.uniform(8, 88), rng.uniform(8, 56)));
          break;
        case 4: {
          Interpolation interp;
          interp.type = static_cast<Interpolation::Type>(rng.below(3));
          interp.radius = rng.uniform(5, 80);
          interp.ring = rng.uniform(-1, 0.9f * static_cast<float>(interp.radius)); // sometimes invalid
          setInterpolation(history, zone, interp);
          break;
        }
        case 5: {
          PositionFunction fn;
          fn.type = static_cast<PositionFunction::Type>(rng.below(5));
          fn.knots = {{0, 0}, {rng.uniform(0.1f, 0.9f), 1}, {1, 0}};
          fn.k = rng.uniform(-5, 5);
          setProfileFunction(history, static_cast<int>(rng.below(2)), fn);
          break;
        }
        case 6:
          setProfileTiming(history, static_cast<int>(rng.below(2)), rng.uniform(-1, 5), rng.uniform(-2, 2));
          break;
        default:
          applyMotionTemplate(history, zone, motionTemplates()[rng.below(5)]);
          break;
        }
        ++applied;
      } catch (const Error&) {
        ++refused;
        ASSERT_EQ(history.project(), before) << "a refused edit must change nothing";
      }
    }
    EXPECT_GT(applied, 60);
    EXPECT_GT(refused, 5) << "the sequence must also try invalid edits";
    const std::string edited = dump(history.project());
    while (history.canUndo()) {
      history.undo();
    }
    EXPECT_EQ(dump(history.project()), dump(start)) << "seed " << seed;
    EXPECT_FALSE(history.dirty());
    while (history.canRedo()) {
      history.redo();
    }
    EXPECT_EQ(dump(history.project()), edited) << "seed " << seed;
  }
}

TEST(FoldingSession, DirtyFollowsTheSavedState) {
  EditHistory history(parseProject(sessionProject(), "s.json"));
  EXPECT_FALSE(history.dirty());
  setProfileTiming(history, 0, 4.0, 0.0);
  EXPECT_TRUE(history.dirty());
  history.markSaved();
  EXPECT_FALSE(history.dirty());
  history.undo();
  EXPECT_TRUE(history.dirty()) << "undoing past the save differs from the file";
  history.redo();
  EXPECT_FALSE(history.dirty()) << "redo returns to the saved state";
  history.undo();
  setProfileTiming(history, 0, 4.0, 0.0); // the same content, but a new state after a branch
  EXPECT_TRUE(history.dirty());
}

TEST(FoldingSession, AutosaveRecoversAfterACrashAndSavingClearsIt) {
  test::TempDir dir;
  const std::filesystem::path file = dir / "p.json";
  Project start = parseProject(sessionProject(), "s.json");
  start.baseDir = dir.path();
  saveProject(file, start);
  EditHistory history(loadProject(file));
  EXPECT_FALSE(recoverAutosave(file).has_value()) << "no sidecar yet";
  addTool(history, 1, ScaleTool{1.2, Vec2(40, 35)});
  autosave(history, file);
  EXPECT_TRUE(std::filesystem::exists(autosavePath(file)));
  EXPECT_EQ(autosavePath(file).filename(), ".p.json.autosave");
  // "Crash": a new session finds the sidecar newer than the file.
  const std::optional<Project> recovered = recoverAutosave(file);
  ASSERT_TRUE(recovered.has_value());
  EXPECT_EQ(*recovered, history.project());
  EXPECT_EQ(recovered->baseDir, dir.path());
  saveEdited(history, file);
  EXPECT_FALSE(history.dirty());
  EXPECT_FALSE(std::filesystem::exists(autosavePath(file)));
  EXPECT_EQ(loadProject(file), history.project());
  // A sidecar equal to the file is nothing to recover; a broken one is reported and ignored.
  autosave(history, file);
  EXPECT_FALSE(recoverAutosave(file).has_value());
  std::ofstream(autosavePath(file)) << "{ not json";
  std::string warning;
  EXPECT_FALSE(recoverAutosave(file, &warning).has_value());
  EXPECT_THAT(warning, ::testing::HasSubstr(".p.json.autosave"));
}

TEST(FoldingSession, ZonesAndProfilesExportAndImportOnTheirOwn) {
  EditHistory history(parseProject(sessionProject(), "s.json"));
  const json zones = exportZones(history.project(), {0});
  EXPECT_EQ(zones["format"], "sylva-fold-zones");
  ASSERT_EQ(zones["zones"].size(), 1u);
  importZones(history, zones, "zones.json");
  ASSERT_EQ(history.project().zones.size(), 3u);
  EXPECT_EQ(history.project().zones[2].id, "z-2") << "a taken id gets a suffix";
  Zone copy = history.project().zones[2];
  copy.id = "z";
  EXPECT_EQ(copy, history.project().zones[0]);
  history.undo();
  EXPECT_EQ(history.project().zones.size(), 2u) << "one import is one edit";
  // Errors name the imported file and the field.
  json bad = zones;
  bad["zones"][0]["image"] = "nope";
  try {
    importZones(history, bad, "zones.json");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("zones.json: /zones/0/image: no image with id 'nope'"));
  }
  EXPECT_THROW(importZones(history,
                           json{{"format", "sylva-fold-zones"}, {"version", 2}, {"zones", json::array()}},
                           "new.json"),
               Error);
  // Profiles: same id replaces, a new id appends.
  json profiles = exportProfiles(history.project());
  profiles["profiles"][0]["period_s"] = 7.5;
  profiles["profiles"][1]["id"] = "extra";
  importProfiles(history, profiles, "profiles.json");
  ASSERT_EQ(history.project().profiles.size(), 3u);
  EXPECT_EQ(history.project().profiles[0].periodS, 7.5);
  EXPECT_EQ(history.project().profiles[2].id, "extra");
}

TEST(FoldingSession, MotionTemplatesAnimateTheirZoneOnly) {
  json j = sessionProject();
  j["zones"].erase(1);
  const Project start = parseProject(j, "t.json");
  ProjectImages images;
  images.images.push_back(test::patternImage(96, 64));
  images.freezeMasks.resize(1);
  images.foldMasks.resize(1);
  for (MotionTemplate motion : motionTemplates()) {
    SCOPED_TRACE(motionTemplateName(motion));
    EXPECT_EQ(parseMotionTemplate(motionTemplateName(motion)), motion);
    EditHistory history(start);
    applyMotionTemplate(history, 0, motion);
    const Project& p = history.project();
    EXPECT_EQ(p.zones[0].profile, motionTemplateName(motion));
    const Textures tex = synthesize(p, images);
    const Profile& profile = p.profiles[static_cast<std::size_t>(p.profileIndex(p.zones[0].profile))];
    int moved = 0;
    for (double phase : {0.2, 0.4, 0.6}) {
      const Image frame = renderFrame(tex, p.profiles, p.jumpLayers, phase * profile.periodS);
      const std::span<const float> init = tex.init.values<float>();
      const auto* a = reinterpret_cast<const std::uint8_t*>(frame.data());
      const auto* b = reinterpret_cast<const std::uint8_t*>(tex.atlas.color.data());
      for (std::size_t i = 0; i < init.size() / 4; ++i) {
        const bool differs = std::memcmp(a + i * 4, b + i * 4, 4) != 0;
        if (init[i * 4 + 3] < 0.0f) {
          ASSERT_FALSE(differs) << "a texel outside the zone moved";
        }
        moved += differs;
      }
    }
    EXPECT_GT(moved, 200) << "the template must move the zone";
    history.undo();
    EXPECT_EQ(history.project(), start);
  }
  EXPECT_FALSE(parseMotionTemplate("dance").has_value());
}

TEST(FoldingSession, FlagRippleRunsDownwindAndGrowsTowardsTheFreeEnd) {
  // A flag held at its pole: the swing is 0 at the hoist and grows to the template's strength at the fly, and
  // the wave's crests travel from the hoist to the fly. Both ways round and for a vertical flag.
  struct Case {
    glm::dvec2 min;
    glm::dvec2 max;
    Vec2 direction;
    Vec2 hoist; ///< a point on the hoist's side of the centre line, 5 % in
    Vec2 fly;   ///< the same 85 % along
  };
  const std::vector<Case> cases = {{{8, 20}, {88, 44}, {0, 1}, {12, 32}, {76, 32}},
                                   {{8, 20}, {88, 44}, {-1, 0}, {84, 32}, {20, 32}},
                                   {{30, 4}, {54, 60}, {0, 1}, {42, 6.8}, {42, 51.6}}};
  for (const Case& c : cases) {
    json j = sessionProject();
    j["zones"].erase(1);
    j["zones"][0]["shape"] = {{"type", "rect"}, {"min", {c.min.x, c.min.y}}, {"max", {c.max.x, c.max.y}}};
    EditHistory history(parseProject(j, "flag.json"));
    TemplateParams params;
    params.strength = 6.0;
    params.direction = c.direction;
    applyMotionTemplate(history, 0, MotionTemplate::FlagRipple, params);
    const Zone& zone = history.project().zones[0];
    const ZoneField field(zone, {}, {96, 64}, 1);
    const Vec2 step = (c.fly - c.hoist) / 16.0;
    double previous = -1.0;
    for (int k = 0; k <= 16; ++k) {
      const Vec2 x = c.hoist + static_cast<double>(k) * step;
      const double swing = glm::length(field.evaluate(x, 0));
      EXPECT_GE(swing, previous - 0.05) << "the swing grows towards the fly, at " << k;
      previous = swing;
    }
    EXPECT_LT(glm::length(field.evaluate(c.hoist, 0)), 0.1 * params.strength) << "the hoist barely moves";
    EXPECT_GT(glm::length(field.evaluate(c.fly, 0)), 0.75 * params.strength) << "the fly swings most";
    // φ = fract(t/T + dt) with dt = phaseGradient · x: a crest reaches smaller dt later, so dt must fall
    // downwind for the crests to run from the hoist to the fly.
    EXPECT_LT(glm::dot(zone.phaseGradient, c.fly - c.hoist), 0.0);
  }
}

TEST(FoldingSession, AStrongerTemplateNeverCrossesWhereItsSidesMeet) {
  // The class of the blink whose lids crossed when made stronger: the templates that close something (blink,
  // wound_opening) cap their strength where the two sides meet. Stronger than that gives the same tools.
  const Project start = parseProject(sessionProject(), "s.json");
  for (const MotionTemplate motion : {MotionTemplate::Blink, MotionTemplate::WoundOpening}) {
    SCOPED_TRACE(motionTemplateName(motion));
    EditHistory meeting(start);
    TemplateParams capped;
    capped.strength = 1e4;
    applyMotionTemplate(meeting, 0, motion, capped);
    EditHistory stronger(start);
    TemplateParams more;
    more.strength = 1e6;
    applyMotionTemplate(stronger, 0, motion, more);
    EXPECT_EQ(meeting.project().zones[0].tools, stronger.project().zones[0].tools);
    // And each side's anchors end on their own side of the meeting line, or on it.
    const Zone& zone = meeting.project().zones[0];
    const auto* points = std::get_if<PointsTool>(&zone.tools[0]);
    ASSERT_NE(points, nullptr);
    double lo = 1e9;
    double hi = -1e9;
    for (const Vec2& p : zone.shape.outline()) {
      lo = std::min(lo, p.y);
      hi = std::max(hi, p.y);
    }
    for (const auto& [from, to] : points->pairs) {
      if (motion == MotionTemplate::WoundOpening) {
        const double axis = 0.5 * (lo + hi);
        EXPECT_GE((from.y - axis) * (to.y - axis), -1e-9) << "a side crossed the cut's axis";
      } else {
        EXPECT_GE(to.y, from.y - 1e-9) << "the upper lid only moves down";
        EXPECT_LE(to.y, lo + 0.88 * (hi - lo) + 0.05 * (hi - lo)) << "the lid stops on the lower lid";
      }
    }
  }
}

} // namespace
} // namespace sylva::folding

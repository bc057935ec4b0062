// The editor's GL-free model: coalesced drags, handles, canvas zoom/pan/snapping, and the Session that keeps
// a project, its images and its textures in step (region re-synthesis equals a full one).
#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/folding/Canvas.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Handles.hpp>
#include <sylva/folding/Session.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/folding/Templates.hpp>

#include "Patterns.hpp"
#include "TempDir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace sylva::folding {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;
using test::patternImage;

Project modelProject() {
  return parseProject(json::parse(R"({"format":"sylva-fold","version":1,"seed":3,
    "atlas":{"images":[{"id":"img","file":"img.png"},{"id":"two","file":"two.png"}]},
    "profiles":[{"id":"p","period_s":2,"fn":{"type":"sine"}}],
    "zones":[{"id":"z","image":"img","profile":"p",
              "shape":{"type":"polygon","pts":[[8,8],[88,10],[86,56],[10,54]]},
              "tools":[{"type":"points","pairs":[[[40,30],[44,34]],[[60,20],[58,26]]]},
                       {"type":"scale","factor":1.1,"centre":[50,30]},
                       {"type":"zero","pts":[[12,50],[30,52]]}],
              "folding":{"type":"polygon","pts":[[30,20],[60,20],[60,40],[30,40]]}},
             {"id":"r","image":"img","profile":"p","shape":{"type":"rect","min":[20,20],"max":[60,50]},
              "tools":[{"type":"translate","v":[2,1]}]}]})"),
                      "model.json");
}

std::string projectText(const Project& p) {
  return toJson(p).dump();
}

TEST(FoldingEditorModel, ADragIsOneUndoStep) {
  const Project start = modelProject();
  EditHistory history(start);
  const Handle h = zoneHandles(start, 0).at(4); // first PointFrom
  ASSERT_EQ(h.kind, Handle::Kind::PointFrom);
  for (int i = 1; i <= 20; ++i) {
    moveHandle(history, h, h.pos + Vec2(0.5 * i, 0.25 * i), true);
  }
  history.endCoalescing();
  EXPECT_EQ(history.undoNames().size(), 1u);
  for (int i = 1; i <= 5; ++i) {
    moveHandle(history, h, h.pos + Vec2(-0.5 * i, 0.0), true);
  }
  history.endCoalescing();
  EXPECT_EQ(history.undoNames().size(), 2u) << "a new drag is a new step";
  history.undo();
  EXPECT_EQ(std::get<PointsTool>(history.project().zones[0].tools[0]).pairs[0][0], h.pos + Vec2(10.0, 5.0));
  history.undo();
  EXPECT_EQ(projectText(history.project()), projectText(start));
}

TEST(FoldingEditorModel, EveryHandleMovesExactlyItsPoint) {
  const Project start = modelProject();
  for (int z = 0; z < 2; ++z) {
    const std::vector<Handle> handles = zoneHandles(start, z);
    EXPECT_EQ(handles.size(), z == 0 ? 4u + 4u + 1u + 2u + 4u : 4u);
    for (std::size_t i = 0; i < handles.size(); ++i) {
      Project same = start;
      setHandle(same, handles[i], handles[i].pos);
      EXPECT_EQ(projectText(same), projectText(start)) << "handle " << i << " set to itself";
      Project moved = start;
      const Vec2 to = handles[i].pos + Vec2(1.0, 2.0);
      setHandle(moved, handles[i], to);
      const std::vector<Handle> after = zoneHandles(moved, z);
      ASSERT_EQ(after.size(), handles.size());
      EXPECT_EQ(after[i].pos, to);
      int changed = 0;
      for (std::size_t k = 0; k < after.size(); ++k) {
        changed += after[k].pos != handles[k].pos ? 1 : 0;
      }
      // A rect corner also moves the two corners next to it; any other handle moves alone.
      EXPECT_EQ(changed, z == 1 ? 3 : 1) << "handle " << i;
    }
  }
  const std::vector<Handle> all = imageHandles(start, "img");
  const std::optional<Handle> near = nearestHandle(all, Vec2(44.4, 34.2), 1.0);
  ASSERT_TRUE(near);
  EXPECT_EQ(near->kind, Handle::Kind::PointTo);
  EXPECT_FALSE(nearestHandle(all, Vec2(70.0, 45.0), 1.0));
}

const std::vector<std::string> kImageIds{"img", "two"};

/** A rectangular zone with no tools. */
Zone rectZone(const std::string& id, const std::string& image, const std::string& profile, Vec2 min,
              Vec2 max) {
  Zone z;
  z.id = id;
  z.image = image;
  z.profile = profile;
  z.shape.type = Shape::Type::Rect;
  z.shape.min = min;
  z.shape.max = max;
  return z;
}

TEST(FoldingEditorModel, NewEditsUndoByteForByte) {
  const Project start = modelProject();
  EditHistory history(start);
  Rng rng(11);
  int applied = 0;
  for (int step = 0; step < 120; ++step) {
    const Project before = history.project();
    const int zones = static_cast<int>(before.zones.size());
    try {
      switch (rng.below(6)) {
      case 0: {
        const Vec2 min(rng.uniform(0, 40), rng.uniform(0, 30));
        // Sometimes too big for its image: refused.
        addZone(history, rectZone("z", kImageIds[rng.below(2)], "p", min,
                                  min + Vec2(rng.uniform(2, 60), rng.uniform(2, 40))));
        break;
      }
      case 1:
        removeZone(history, static_cast<int>(rng.below(static_cast<std::uint32_t>(zones + 1))));
        break;
      case 2:
        if (zones > 0) {
          moveZoneToImage(history, static_cast<int>(rng.below(static_cast<std::uint32_t>(zones))),
                          kImageIds[rng.below(2)]);
        }
        break;
      case 3: {
        Profile p = before.profiles[0];
        p.periodS = rng.uniform(-1, 4);
        replaceProfile(history, 0, p, rng.below(2) == 0);
        break;
      }
      case 4:
        if (zones > 0) {
          const int z = static_cast<int>(rng.below(static_cast<std::uint32_t>(zones)));
          const std::vector<Handle> h = zoneHandles(before, z);
          moveHandle(history, h[rng.below(static_cast<std::uint32_t>(h.size()))],
                     Vec2(rng.uniform(-10, 100), rng.uniform(-10, 70)), rng.below(2) == 0);
        }
        break;
      default:
        history.endCoalescing();
        addProfile(history, before.profiles[0]);
        break;
      }
      ++applied;
    } catch (const Error&) {
      ASSERT_EQ(projectText(history.project()), projectText(before)) << "a refused edit must change nothing";
    }
  }
  EXPECT_GT(applied, 40);
  const std::string edited = projectText(history.project());
  while (history.canUndo()) {
    history.undo();
  }
  EXPECT_EQ(projectText(history.project()), projectText(start));
  while (history.canRedo()) {
    history.redo();
  }
  EXPECT_EQ(projectText(history.project()), edited);
}

TEST(FoldingEditorModel, SnappingPrefersPointsThenPixelCentres) {
  CanvasView v;
  v.zoom = 4.0; // radius 8 screen px = 2 image px
  const std::vector<Vec2> points{{10.3, 10.9}, {30.0, 30.0}};
  SnapOptions o;
  EXPECT_EQ(snapPoint({11.2, 11.5}, v, points, o), points[0]);
  EXPECT_EQ(snapPoint({20.2, 20.9}, v, points, o), Vec2(20.5, 20.5));
  o.pixelCentres = false;
  EXPECT_EQ(snapPoint({20.2, 20.9}, v, points, o), Vec2(20.2, 20.9));
  o.points = false;
  o.pixelCentres = true;
  EXPECT_EQ(snapPoint({11.2, 11.5}, v, points, o), Vec2(11.5, 11.5));
  v.zoom = 32.0; // radius ¼ image px: a pixel centre 0.36 px away no longer attracts
  EXPECT_EQ(snapPoint({11.2, 11.3}, v, points, o), Vec2(11.2, 11.3));
}

/** Writes img.png (96×64) and two.png (48×40) into `dir`. */
void writeImages(const fs::path& dir) {
  saveImage(dir / "img.png", patternImage(96, 64));
  saveImage(dir / "two.png", patternImage(48, 40));
}

void expectTexturesEqual(const Textures& a, const Textures& b) {
  ASSERT_EQ(a.atlas.entries, b.atlas.entries);
  EXPECT_TRUE(a.init == b.init);
  ASSERT_EQ(a.jump.size(), b.jump.size());
  for (std::size_t i = 0; i < a.jump.size(); ++i) {
    EXPECT_TRUE(a.jump[i] == b.jump[i]) << "jump layer " << i;
  }
  EXPECT_EQ(a.fold.size(), b.fold.size());
}

TEST(FoldingEditorSession, RegionUpdatesEqualAFullSynthesis) {
  test::TempDir dir;
  writeImages(dir.path());
  auto s = Session::fromImages({dir.path() / "img.png", dir.path() / "two.png"}, dir.path() / "new.json");
  EXPECT_TRUE(s->history().dirty());
  EXPECT_EQ(s->project().images[1].file, fs::path("two.png"));
  Session::Update u = s->synthesize();
  EXPECT_TRUE(u.full);
  EXPECT_FALSE(s->stale());
  EXPECT_TRUE(s->synthesize().region.empty()) << "nothing changed";

  Zone z = rectZone("eye", "img", "motion", {10, 10}, {70, 50});
  const int zone = addZone(s->history(), z);
  addTool(s->history(), zone, PointsTool{{{Vec2(30, 30), Vec2(34, 33)}, {Vec2(50, 20), Vec2(50, 26)}}});
  s->synthesize();
  expectTexturesEqual(*s->textures(), synthesize(s->project(), s->images()));

  // A drag: each step re-synthesises the hinted region only, and always equals a full synthesis.
  for (int step = 1; step <= 4; ++step) {
    const Handle h = zoneHandles(s->project(), zone).at(5); // PointTo of pair 0
    const Vec2 to = h.pos + Vec2(1.5, -0.5);
    moveHandle(s->history(), h, to, true);
    u = s->synthesize();
    EXPECT_FALSE(u.full) << "the canvas image is never cropped: same layout";
    EXPECT_LT(u.region.width() * u.region.height(), 96 * 64);
    expectTexturesEqual(*s->textures(), synthesize(s->project(), s->images()));
  }
  s->history().endCoalescing();
  s->history().undo();
  s->synthesize();
  expectTexturesEqual(*s->textures(), synthesize(s->project(), s->images()));
  // A zone on the second (cropped) image changes the layout: a full synthesis.
  z.image = "two";
  z.shape.max = {30, 30};
  addZone(s->history(), z);
  EXPECT_TRUE(s->synthesize().full);
  expectTexturesEqual(*s->textures(), synthesize(s->project(), s->images()));
}

TEST(FoldingEditorSession, BackgroundSynthesisInstallsAndCatchesUp) {
  test::TempDir dir;
  writeImages(dir.path());
  auto s = Session::fromImages({dir.path() / "img.png"}, dir.path() / "bg.json");
  const int zone = addZone(s->history(), rectZone("eye", "img", "motion", {10, 10}, {70, 50}));
  addTool(s->history(), zone, PointsTool{{{Vec2(30, 30), Vec2(34, 33)}}});
  EXPECT_TRUE(s->needsFullSynthesis());
  // The worker's copy: the masks are loaded for the zones it has (none were loaded for this zone yet).
  const Session::Snapshot snap = s->snapshot();
  ASSERT_EQ(snap.images.freezeMasks.size(), 1u);
  Textures background = synthesize(snap.project, snap.images);
  // Edits go on while it runs...
  addTool(s->history(), zone, TranslateTool{Vec2(1.0, 2.0)});
  ASSERT_TRUE(s->install(std::move(background), snap.project, snap.images));
  EXPECT_TRUE(s->stale());
  EXPECT_FALSE(s->needsFullSynthesis());
  // ...and are caught up by region.
  EXPECT_FALSE(s->synthesize().full);
  expectTexturesEqual(*s->textures(), synthesize(s->project(), s->images()));
  // A result for pixels that changed on disk meanwhile is dropped.
  const Session::Snapshot old = s->snapshot();
  saveImage(dir.path() / "img.png", patternImage(96, 64, true));
  s->reloadImages();
  EXPECT_FALSE(s->install(synthesize(old.project, old.images), old.project, old.images));
  EXPECT_EQ(s->textures(), nullptr);
}

TEST(FoldingEditorSession, EditsMustFitTheLoadedImages) {
  test::TempDir dir;
  writeImages(dir.path());
  auto s = Session::fromImages({dir.path() / "img.png", dir.path() / "two.png"}, dir.path() / "p.json");
  Zone z = rectZone("big", "img", "motion", {10, 10}, {70, 50});
  const int zone = addZone(s->history(), z);
  const std::string before = projectText(s->project());
  EXPECT_THROW(moveZoneToImage(s->history(), zone, "two"), Error) << "70×50 does not fit 48×40";
  EXPECT_THROW(moveHandle(s->history(), zoneHandles(s->project(), zone)[2], Vec2(120, 40)), Error);
  EXPECT_EQ(projectText(s->project()), before);
}

TEST(FoldingEditorSession, SaveOpenRecoverAndReloadKeepTheZones) {
  test::TempDir dir;
  writeImages(dir.path());
  fs::create_directories(dir.path() / "sub");
  auto s = Session::fromImages({dir.path() / "img.png"}, dir.path() / "p.json");
  Zone z = rectZone("eye", "img", "motion", {10, 10}, {70, 50});
  addZone(s->history(), z);
  addTool(s->history(), 0, TranslateTool{Vec2(2.0, 1.0)});
  s->synthesize();
  s->save();
  EXPECT_FALSE(s->history().dirty());

  // Save as into another directory: image paths follow, textures stay current.
  s->saveAs(dir.path() / "sub" / "q.json");
  EXPECT_EQ(s->project().images[0].file, fs::path("../img.png"));
  EXPECT_FALSE(s->stale());
  EXPECT_FALSE(s->history().dirty());

  // An unsaved edit, autosaved, then a "crash": reopening recovers it as one undoable step.
  addTool(s->history(), 0, TranslateTool{Vec2(-1.0, 3.0)});
  s->autosaveNow();
  const std::string edited = projectText(s->project());
  s.reset();
  std::string notice;
  auto r = Session::open(dir.path() / "sub" / "q.json", true, &notice);
  EXPECT_NE(notice.find("recovered"), std::string::npos) << notice;
  EXPECT_EQ(projectText(r->project()), edited);
  EXPECT_TRUE(r->history().dirty());
  r->history().undo();
  EXPECT_EQ(r->project().zones[0].tools.size(), 1u);
  r->history().redo();

  // The image changes on disk (an external editor saved it): zones stay, textures follow the new pixels.
  r->synthesize();
  const Image before = r->textures()->atlas.color;
  saveImage(dir.path() / "img.png", patternImage(96, 64, true));
  r->reloadImages();
  EXPECT_TRUE(r->stale());
  EXPECT_TRUE(r->synthesize().full);
  EXPECT_FALSE(r->textures()->atlas.color == before);
  EXPECT_EQ(projectText(r->project()), edited);
  // A resized image that no longer holds the zone is refused; the old images stay.
  saveImage(dir.path() / "img.png", patternImage(32, 32));
  EXPECT_THROW(r->reloadImages(), Error);
  EXPECT_EQ(r->imageSize(0), glm::ivec2(96, 64));
}

} // namespace
} // namespace sylva::folding

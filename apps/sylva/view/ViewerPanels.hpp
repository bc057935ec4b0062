#pragma once
// The viewer's editing sections (docs/cli.md "view"): terrain LOD, grass, simulation and trees, each an ImGui
// section over the world the viewer draws (scene::SceneWorld). They change the world through its description
// (a rebuilt grass layer or forest) or its drawables (culling, bark, foliage, far field), never by drawing.

#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/ui/CameraRig.hpp>

#include "flags/WorldFlags.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sylva::app {

/** The terrain section: LOD parameters, crack method, debug views, frozen frustum, counts. */
struct TerrainPanel {
  terrain::QuadtreeConfig lod;
  int method = 1; // 0 paper, 1 ours, 2 none
  int view = 0;
  bool freeze = false;
  /** Whether the section starts open. */
  bool open = false;

  /** Starts at `world`'s terrain settings. */
  explicit TerrainPanel(scene::SceneWorld& world);
  /** Draws the section; `rig`'s walk toggle is shown here too (G). */
  void show(scene::SceneWorld& world, const render::Camera& camera, float aspect, ui::CameraRig& rig);
};

/**
 * The grass section (grass layer 0 and the shared wind): on/off (adding the layer of the options on the
 * first enable), view, live culling and wind, the field settings rebuilt on Apply, counts; and the
 * simulation section: bodies, tiles, throw a ball, drop ten, reset.
 */
struct GrassPanel {
  /** The layer added by the first enable when the world has none (the --grass options). */
  scene::GrassLayer fresh;
  /** Field settings being edited; the field changes only on Apply. */
  scene::GrassLayer pending;
  grass::CullSettings cull;
  std::string cullError;
  std::string buildError;
  int view = 0;
  /** The wind as the sliders show it: speed m/s, direction degrees (clockwise from north), gusts. */
  scene::WindDesc wind;
  /** Counters of this frame's cull (read after the draw while the panel shows). */
  std::optional<gpu::GrassCounters> counters;
  /** Balls dropped from the panel so far (each drop gets its own seed); the drops' base seed. */
  int drops = 0;
  std::uint64_t dropSeed = 7;
  std::string simError;
  bool open = false;

  GrassPanel(scene::SceneWorld& world, const WorldFlags& flags);
  /** Whether grass is drawn (a layer exists and its pass is on). */
  bool active(scene::SceneWorld& world) const;
  void show(scene::SceneWorld& world);
  /** A 0.35 m, 30 kg ball from `camera`, 8 m/s forward (starting the simulation of layer 0 if needed). */
  bool throwBall(scene::SceneWorld& world, const render::Camera& camera);
  /** Ten seeded balls on the steepest grassy slope near `camera`. */
  bool dropBalls(scene::SceneWorld& world, const render::Camera& camera, int count);
  void showSimulation(scene::SceneWorld& world, const render::Camera& camera);

private:
  /** Starts the simulation on layer 0 when none runs; false (message shown) on errors or without grass. */
  bool ensureSimulation(scene::SceneWorld& world);
};

/** A species mix the trees section offers: its label and the species (presets or files). */
struct SpeciesMix {
  std::string label;
  std::vector<std::string> species;
};

/**
 * The trees section (forest 0): on/off (adding the forest of the options on the first enable), species mix
 * (rebuilds at once), count, seed and spacing (Rebuild), live tessellation, draw distance, wind and view,
 * bark and foliage (at once), the far field (Apply), and counts, GPU time and memory.
 */
struct TreesPanel {
  /** The forest added by the first enable when the world has none; then the forest built. */
  scene::ForestDesc desc;
  trees::ForestLook look;
  std::vector<SpeciesMix> mixes;
  int mix = 0;
  int pendingCount = 0;
  int pendingSeed = 0;
  float pendingSpacing = 0.0f;
  float pendingAutumn = 0.0f;
  float pendingLeafFall = 0.0f;
  std::string buildError;
  std::string surfaceError;
  /** A tile-set directory given as --trees-bark (the bark combo's fourth choice), else empty. */
  std::string barkDirectory;
  bool pendingFar = false;
  float pendingFarDistance = 150.0f;
  float pendingFarBand = 25.0f;
  int pendingFarCount = 0;
  /** Whether the section showed last frame (the visible counts are read only then). */
  bool open = false;
  std::vector<std::uint32_t> visible;
  std::optional<std::uint32_t> farVisible;

  TreesPanel(scene::SceneWorld& world, const TreeFlags& flags);
  bool active(scene::SceneWorld& world) const;
  void show(scene::SceneWorld& world, const render::GpuTimers& timers);
  /** After the frame's draw, while the section shows: the visible counts of the cull just done. */
  void readCounts(scene::SceneWorld& world);

private:
  void resetPending();
  void resetPendingFar();
  /** Rebuilds forest 0 from `next`; on an error keeps the old forest and shows the message. */
  void rebuild(scene::SceneWorld& world, const scene::ForestDesc& next);
  /** Re-bakes the far field after bark or foliage changed (nothing without one). */
  void rebakeFarField(scene::SceneWorld& world);
  void applyBark(scene::SceneWorld& world, const std::string& mode);
};

} // namespace sylva::app

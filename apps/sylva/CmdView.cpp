#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/ui/ImGuiLayer.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/DemoScene.hpp>
#include <sylva/render/GpuTimers.hpp>
#include <sylva/render/RenderTarget.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/trees/Species.hpp>

#include "GrassFlags.hpp"
#include "GrassSim.hpp"
#include "TerrainFlags.hpp"
#include "TreeFlags.hpp"
#include "ViewScene.hpp"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <optional>

namespace sylva::app {

namespace {

struct ViewOptions {
  std::string file; ///< a scene file (runSceneViewer); empty: --scene
  std::string scene = "terrain";
  TerrainFlags terrain;
  CameraFlags camera;
  GrassFlags grass;
  SimulationFlags simulation;
  TreeFlags trees;
  int width = 1280;
  int height = 720;
  std::string shaderDir;
  int frames = 0;
  std::string screenshot;
  bool noUi = false;
  double fixedStep = 0.0;
};

/** What the viewer draws: the terrain (with its LOD panel) or the built-in demo scene. */
struct ViewerScene {
  std::unique_ptr<terrain::TerrainScene> terrain;
  std::unique_ptr<render::DemoScene> demo;
  terrain::TerrainDrawOptions draw;
  terrain::QuadtreeConfig lod;
  int method = 1; // 0 paper, 1 ours, 2 none
  int view = 0;
  bool freeze = false;
  bool walk = false;
};

/** The terrain section of the panel: LOD parameters, crack method, debug views, frozen frustum and counts. */
void terrainPanel(ViewerScene& v, const render::Camera& camera, float aspect) {
  terrain::TerrainScene& scene = *v.terrain;
  const terrain::QuadtreeSelection& sel = scene.selection();
  if (ImGui::CollapsingHeader("Terrain LOD", ImGuiTreeNodeFlags_DefaultOpen)) {
    bool changed = false;
    const char* methods[] = {"paper (quadtree search)", "ours (restricted level map)", "none (shows cracks)"};
    changed |= ImGui::Combo("crack method", &v.method, methods, 3);
    changed |= ImGui::SliderInt("tessellation", &v.lod.patchTessLevel, 1, terrain::kMaxPatchTessLevel);
    changed |= ImGui::SliderFloat("LOD distance factor", &v.lod.lodDistanceFactor,
                                  terrain::kMinRestrictedLodFactor, 8.0f);
    changed |= ImGui::SliderInt("max depth", &v.lod.maxDepth, 0, 8);
    changed |= ImGui::Checkbox("LOD enabled", &v.lod.lodEnabled);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("frustum culling", &v.lod.frustumCull);
    if (changed) {
      v.lod.method = v.method == 0   ? terrain::CrackMethod::PaperSearch
                     : v.method == 1 ? terrain::CrackMethod::RestrictedLevelMap
                                     : terrain::CrackMethod::None;
      scene.setQuadtreeConfig(v.lod);
    }
    const char* views[] = {"shaded", "LOD colours", "normals", "splat layers"};
    ImGui::Combo("view", &v.view, views, 4);
    v.draw.view = static_cast<terrain::TerrainView>(v.view);
    ImGui::Checkbox("wireframe", &v.draw.wireframe);
    ImGui::SameLine();
    ImGui::Checkbox("skirts (crack check)", &v.draw.skirts);
    if (ImGui::Checkbox("freeze frustum", &v.freeze)) {
      scene.setFrozenFrustum(v.freeze ? std::optional<Frustum>(camera.frustum(aspect)) : std::nullopt);
    }
    ImGui::Checkbox("walk on the ground (G)", &v.walk);
  }
  if (ImGui::CollapsingHeader("Counts", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Text("nodes drawn       %d", sel.stats.leaves);
    ImGui::Text("nodes culled      %d", sel.stats.nodesCulled);
    ImGui::Text("edges doubled     %d", sel.stats.doubledEdges);
    const std::int64_t measured = scene.renderer().lastVertexInvocations();
    ImGui::Text("vertices (GPU)    %lld", static_cast<long long>(measured));
    ImGui::Text("vertices (CPU est) %llu", static_cast<unsigned long long>(sel.stats.processedVertices));
    ImGui::Text("LOD update        %.3f ms", scene.lastUpdateMs());
    if (v.draw.skirts) {
      ImGui::Text("crack pixels      %lld", static_cast<long long>(scene.renderer().lastCrackSamples()));
    }
    const float ground = terrain::heightAt(scene.field(), camera.position.x, camera.position.z);
    ImGui::Text("camera %.0f, %.0f m, %.1f m above ground", camera.position.x, camera.position.z,
                camera.position.y - ground);
  }
}

/**
 * The viewer's grass field: built from the --grass options at start (or on the panel's first enable) and
 * rebuilt by the panel's Apply; culling distances, view and wind change live.
 */
struct ViewerGrass {
  /** The options the field was built from; the wind fields are the live wind. */
  GrassFlags flags;
  bool enabled = false;
  /** Where new renderers read their shaders: the viewer's library, or the last hot reload's directory. */
  shader::Library shaders;
  std::unique_ptr<grass::GrassRenderer> renderer;
  /** Culling settings as the sliders show them, and the last valid set (the renderer's). */
  grass::CullSettings cull;
  grass::CullSettings applied;
  std::string cullError;
  /** Field settings being edited; the field changes only on Apply. */
  grass::FieldSettings pending;
  std::string buildError;
  /** Blades of the whole field, estimated from the mean density at the last build (any terrain size). */
  double fieldBlades = 0.0;
  int view = 0;
  /** Counters of this frame's cull (read after the draw while the panel shows). */
  std::optional<gpu::GrassCounters> counters;
  /** --physics and the simulation's settings: for the scene at start and for any made later (B, panel). */
  SimulationFlags simFlags;
  /**
   * The bodies and the simulated grass tiles (docs/grass-simulation.md), or null until --physics, a throw or
   * the panel makes them. Registered with `renderer`: declared after it so it is destroyed first, and rebuilt
   * (empty) whenever the renderer is.
   */
  std::unique_ptr<scene::GrassSimulation> simulation;
  /** Simulation time of `simulation`: seconds it has run since it was built (stops with the viewer's pause).
   */
  double simTime = 0.0;
  /** Balls dropped from the panel so far (each drop gets its own seed). */
  int drops = 0;
  std::string simError;

  /** The renderer to draw with this frame, or null when grass is off. */
  grass::GrassRenderer* active() const { return enabled ? renderer.get() : nullptr; }
  grass::GrassDrawOptions drawOptions() const {
    grass::GrassDrawOptions options;
    options.view = static_cast<grass::GrassView>(view);
    options.wind = flags.wind();
    return options;
  }
};

/**
 * (Re)builds the simulation of `g` with no bodies on its current renderer (which must exist), its clock back
 * at 0; throws on errors, leaving no simulation.
 */
void buildSimulation(ViewerGrass& g, const terrain::TerrainScene& scene) {
  g.simulation.reset(); // unregisters from the renderer before the new one registers
  g.simTime = 0.0;
  g.simulation = std::make_unique<scene::GrassSimulation>(g.shaders, scene.field(), *g.renderer,
                                                          g.renderer->fieldPointer(), g.simFlags.settings());
  log::info("grass simulation: {} solver, pool of {} tiles", g.simulation->onGpu() ? "GPU" : "CPU",
            g.simFlags.pool);
}

/** buildSimulation for the panel and the keys: false, with the message shown in the panel, on errors. */
bool resetSimulation(ViewerGrass& g, const terrain::TerrainScene& scene) {
  try {
    buildSimulation(g, scene);
    g.simError.clear();
    return true;
  } catch (const Error& e) {
    g.simError = e.what();
    log::error("{}", e.what());
    return false;
  }
}

/**
 * Builds the field of `g.flags` over `scene` and its renderer; throws, leaving `g` as it was, on errors. A
 * simulation on the old renderer is rebuilt on the new one, empty (its tiles belong to the old field).
 */
void buildGrass(ViewerGrass& g, const terrain::TerrainScene& scene) {
  std::shared_ptr<const grass::GrassField> field = g.flags.buildField(scene);
  auto renderer = std::make_unique<grass::GrassRenderer>(g.shaders, field, g.applied);
  const double blades = field->estimateBlades();
  log::info("grass: {} blade types, {} tiles of {} m, about {:.3g} blades in the field, patch {:.2f} MB",
            field->types().size(), static_cast<long long>(field->layout().tilesX) * field->layout().tilesZ,
            field->layout().tileSize, blades,
            static_cast<double>(grass::patchBytes(field->patch().size(), field->types().size())) / 1e6);
  const bool simulated = g.simulation != nullptr;
  g.simulation.reset(); // registered with the old renderer: goes before it
  g.renderer = std::move(renderer);
  g.fieldBlades = blades;
  g.counters.reset();
  if (simulated) {
    resetSimulation(g, scene);
  }
}

/**
 * Throws a ball from `camera`: 1 m ahead of the eye (at least resting on the ground when the camera looks
 * steeply down) at 8 m/s forward and 1 m/s up (0.35 m, 30 kg), making the simulation first if there is none.
 * Does nothing while grass is off; false then or on errors.
 */
bool throwBall(ViewerGrass& g, const terrain::TerrainScene& scene, const render::Camera& camera) {
  if (g.active() == nullptr || (!g.simulation && !resetSimulation(g, scene))) {
    return false;
  }
  constexpr float kRadius = 0.35f;
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  glm::vec3 at = camera.position + forward;
  const float ground = terrain::heightAt(scene.field(), at.x, at.z);
  if (!std::isnan(ground)) {
    at.y = std::max(at.y, ground + kRadius);
  }
  g.simulation->spawnBall(at, 8.0f * forward + glm::vec3(0.0f, 1.0f, 0.0f), kRadius, 30.0f);
  return true;
}

/**
 * Drops `count` balls (seeded, a new seed each time) on the steepest grassy slope near `camera`, as `sylva
 * view --physics balls` does at start; makes the simulation first if there is none.
 */
bool dropBalls(ViewerGrass& g, const terrain::TerrainScene& scene, const render::Camera& camera, int count) {
  if (g.active() == nullptr || (!g.simulation && !resetSimulation(g, scene))) {
    return false;
  }
  const glm::vec2 drop = ballDropPoint(scene.field(), g.renderer->field(), camera);
  g.simulation->spawnBalls(drop, 1.5f, count, g.simFlags.seed + static_cast<std::uint64_t>(++g.drops), 0.5f);
  return true;
}

/** Rebuilds with the pending field settings; on an error keeps the old field and shows the message. */
void applyGrassField(ViewerGrass& g, const terrain::TerrainScene& scene) {
  const grass::FieldSettings before = g.flags.field;
  g.flags.field = g.pending;
  try {
    buildGrass(g, scene);
    g.enabled = true;
    g.buildError.clear();
  } catch (const Error& e) {
    g.flags.field = before;
    g.buildError = e.what();
    log::error("{}", e.what());
  }
}

/** Applies the sliders' culling settings, or shows why not (overlapping bands, lists too large). */
void applyGrassCull(ViewerGrass& g) {
  try {
    if (g.renderer) {
      g.renderer->setCullSettings(g.cull);
    } else {
      grass::validate(g.cull);
    }
    g.applied = g.cull;
    g.cullError.clear();
  } catch (const Error& e) {
    g.cullError = e.what();
  }
}

/** Red wrapped text for an error message (nothing when empty). */
void errorText(const std::string& message) {
  if (message.empty()) {
    return;
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 420.0f);
  ImGui::TextUnformatted(message.c_str());
  ImGui::PopTextWrapPos();
  ImGui::PopStyleColor();
}

/**
 * The grass section of the panel: on/off (building the field on the first enable), view, live culling and
 * wind sliders, the field settings rebuilt on Apply, and the field's and the last cull's counts.
 */
void grassPanel(ViewerGrass& g, const terrain::TerrainScene& scene) {
  if (!ImGui::CollapsingHeader("Grass", g.enabled ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
    return;
  }
  const ImGuiSliderFlags clamp = ImGuiSliderFlags_AlwaysClamp;
  if (ImGui::Checkbox("grass enabled", &g.enabled) && g.enabled && !g.renderer) {
    try {
      buildGrass(g, scene);
      g.buildError.clear();
    } catch (const Error& e) {
      g.enabled = false;
      g.buildError = e.what();
      log::error("{}", e.what());
    }
  }
  const char* views[] = {"shaded", "LOD colours", "tiles"};
  ImGui::Combo("grass view", &g.view, views, 3);
  bool cullChanged = false;
  cullChanged |= ImGui::SliderFloat("draw distance (m)", &g.cull.maxDistance, 5.0f, 500.0f, "%.0f", clamp);
  cullChanged |=
      ImGui::SliderFloat("LOD 16 > 8 knots (m)", &g.cull.lodDistances[0], 0.0f, 200.0f, "%.1f", clamp);
  cullChanged |=
      ImGui::SliderFloat("LOD 8 > 4 knots (m)", &g.cull.lodDistances[1], 0.0f, 400.0f, "%.1f", clamp);
  cullChanged |= ImGui::SliderFloat("LOD cross-fade (m)", &g.cull.lodFade, 0.0f, 20.0f, "%.1f", clamp);
  cullChanged |= ImGui::SliderFloat("far fade (m)", &g.cull.farFade, 0.0f, 125.0f, "%.1f", clamp);
  if (cullChanged) {
    applyGrassCull(g);
  }
  errorText(g.cullError);
  ImGui::SliderFloat("wind speed (m/s)", &g.flags.windSpeed, 0.0f, 60.0f, "%.1f", clamp);
  ImGui::SliderFloat("wind direction (deg)", &g.flags.windDirection, -180.0f, 180.0f, "%.0f", clamp);
  ImGui::SliderFloat("gust strength", &g.flags.gusts, 0.0f, 10.0f, "%.2f", clamp);

  ImGui::Separator();
  ImGui::TextUnformatted("field (rebuilt on Apply)");
  ImGui::SliderFloat("density", &g.pending.density.base, 0.0f, 1.0f, "%.2f", clamp);
  ImGui::SliderFloat("coverage", &g.pending.density.coverage, 0.0f, 1.0f, "%.2f", clamp);
  const ImGuiSliderFlags logarithmic = clamp | ImGuiSliderFlags_Logarithmic;
  ImGui::SliderInt("patch blades", &g.pending.patch.blades, 1, 1 << 22, "%d", logarithmic);
  ImGui::SliderInt("blades per tile", &g.pending.bladesPerTile, 1, 1 << 16, "%d", logarithmic);
  ImGui::SliderFloat("tile size (m)", &g.pending.patch.tileSize, 0.25f, 20.0f, "%.2f", logarithmic);
  const grass::FieldSettings& built = g.flags.field;
  const bool edited =
      g.pending.density.base != built.density.base || g.pending.density.coverage != built.density.coverage ||
      g.pending.patch.blades != built.patch.blades || g.pending.bladesPerTile != built.bladesPerTile ||
      g.pending.patch.tileSize != built.patch.tileSize;
  ImGui::BeginDisabled(!edited && g.renderer != nullptr);
  if (ImGui::Button("Apply")) {
    applyGrassField(g, scene);
  }
  ImGui::EndDisabled();
  if (g.simulation && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("rebuilds the field: the simulation restarts empty (its bodies are removed)");
  }
  if (edited) {
    ImGui::SameLine();
    if (ImGui::Button("Revert")) {
      g.pending = g.flags.field;
    }
  }
  errorText(g.buildError);

  if (g.renderer) {
    ImGui::Separator();
    const grass::GrassField& field = g.renderer->field();
    const grass::FieldLayout& layout = field.layout();
    ImGui::Text("blade types       %zu", field.types().size());
    ImGui::Text("tiles             %d x %d of %.2f m", layout.tilesX, layout.tilesZ, layout.tileSize);
    ImGui::Text("patch blades      %zu (%d per tile)", field.patch().size(), layout.bladesPerTile);
    ImGui::Text("field blades      %.3g (estimate)", g.fieldBlades);
    if (g.enabled && g.counters) {
      const gpu::GrassCounters& c = *g.counters;
      ImGui::Text("visible tiles     %u", c.dispatch.x);
      ImGui::Text("drawn blades      %u", c.blades.x);
      ImGui::Text("instances 16/8/4  %u / %u / %u", c.draws[0].y, c.draws[1].y, c.draws[2].y);
      ImGui::Text("culled: frustum %u, distance %u, edge-on %u", c.blades.y, c.blades.z, c.blades.w);
      if (c.overflow.x != 0 || c.overflow.y != 0) {
        errorText(fmt::format("lists full: {} instances and {} tiles dropped", c.overflow.x, c.overflow.y));
      }
    }
    ImGui::Text("GPU memory        %.1f MB", static_cast<double>(g.renderer->gpuBytes()) / 1e6);
  }
}

/** Tooltip of the last item, shown even when it is disabled (`text` empty: none). */
void disabledTooltip(const char* text) {
  if (text != nullptr && *text != '\0' && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", text);
  }
}

/**
 * The simulation section of the panel: bodies, simulated tiles and blades, refused tiles (pool full), this
 * frame's steps and the solver; throw a ball, drop ten, or reset to an empty simulation. Needs grass.
 */
void simulationPanel(ViewerGrass& g, const terrain::TerrainScene& scene, const render::Camera& camera) {
  if (!ImGui::CollapsingHeader("Simulation", g.simulation ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
    return;
  }
  const bool grassOn = g.active() != nullptr;
  const char* why = grassOn ? "" : "needs grass: turn it on in the Grass section";
  if (g.simulation) {
    const grass::SimStats& s = g.simulation->stats();
    ImGui::Text("bodies            %zu", g.simulation->bodies());
    ImGui::Text("active tiles      %zu / %d", s.activeTiles, g.simFlags.pool);
    ImGui::Text("simulated blades  %zu", s.simulatedBlades);
    if (s.refusedTiles > 0) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
    }
    ImGui::Text("refused tiles     %zu", s.refusedTiles);
    if (s.refusedTiles > 0) {
      ImGui::PopStyleColor();
      disabledTooltip("tiles near a body found the pool full (--grass-pool): their blades ignore the bodies");
    }
    ImGui::Text("steps this frame  %d", s.steps);
    ImGui::Text("solver            %s", g.simulation->onGpu() ? "GPU (compute shader)" : "CPU (reference)");
    ImGui::Text("time              %.2f s", g.simTime);
  } else {
    ImGui::TextUnformatted("no bodies yet (B or the buttons below start the simulation)");
    ImGui::Text("solver            %s",
                g.simFlags.solver == "gpu" ? "GPU (compute shader)" : "CPU (reference)");
  }
  ImGui::BeginDisabled(!grassOn);
  if (ImGui::Button("Throw ball (B)")) {
    throwBall(g, scene, camera);
  }
  disabledTooltip(grassOn ? "a 0.35 m, 30 kg ball from the camera, 8 m/s forward" : why);
  ImGui::SameLine();
  if (ImGui::Button("Drop 10 balls")) {
    dropBalls(g, scene, camera, 10);
  }
  disabledTooltip(grassOn ? "on the steepest grassy slope within 40 m of the camera" : why);
  ImGui::SameLine();
  if (ImGui::Button("Reset")) {
    resetSimulation(g, scene);
  }
  disabledTooltip(grassOn ? "removes every body and restarts the simulation" : why);
  ImGui::EndDisabled();
  errorText(g.simError);
}

/** A species mix the Trees panel offers: its label and the species (presets or files). */
struct SpeciesMix {
  std::string label;
  std::vector<std::string> species;
};

/** "a, b, c". */
std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) {
    out += (out.empty() ? "" : ", ") + n;
  }
  return out;
}

/**
 * The mixes of the Trees panel: the one of --trees-species (the default mix unless given), all presets, then
 * each preset alone.
 */
std::vector<SpeciesMix> speciesMixes(const std::vector<std::string>& given) {
  std::vector<SpeciesMix> mixes;
  const bool isDefault = given == TreeFlags::defaultForest().species;
  mixes.push_back({(isDefault ? "default mix: " : "--trees-species: ") + joinNames(given), given});
  const std::vector<std::string> presets = trees::speciesPresetNames();
  if (presets != given) {
    mixes.push_back({"all presets", presets});
  }
  for (const std::string& name : presets) {
    if (given != std::vector<std::string>{name}) {
      mixes.push_back({name, {name}});
    }
  }
  return mixes;
}

/** The Bark combo's choices (--trees-bark values); a tile-set directory given on the command line comes last.
 */
constexpr const char* kBarkModes[] = {"auto", "procedural", "none"};
constexpr const char* kBarkLabels[] = {"photos (auto)", "procedural", "flat colours (none)"};

/**
 * The viewer's forest: built from the --trees options at start (or on the panel's first enable) and rebuilt
 * by the panel (species mix, count, seed, spacing); tessellation, draw distance, view, wind, bark and foliage
 * change live; the far field is re-baked by its Apply button.
 */
struct ViewerTrees {
  /** The options the forest was built from; lod is the live level of detail. */
  TreeFlags flags;
  bool enabled = false;
  /** Where new scenes read their shaders: the viewer's library, or the last hot reload's directory. */
  shader::Library shaders;
  std::unique_ptr<trees::ForestScene> scene;
  /** Mixes of the species combo and the one built. */
  std::vector<SpeciesMix> mixes;
  int mix = 0;
  /** Forest settings being edited; the forest changes only on Rebuild. */
  int pendingCount = 0;
  int pendingSeed = 0;
  float pendingSpacing = 0.0f;
  std::string buildError;
  /** The last bark, foliage or far-field change's error (the scene keeps what it drew). */
  std::string surfaceError;
  bool wind = true;
  /** Multiplies the shared wind's mean speed for the trees (gusts are a fraction of it). */
  float windStrength = 1.0f;
  int view = 0;
  /** A tile-set directory given as --trees-bark (the combo's fourth choice), else empty. */
  std::string barkDirectory;
  /** Far field being edited; the scene changes only on Apply. */
  bool pendingFar = false;
  float pendingFarDistance = 150.0f;
  float pendingFarBand = 25.0f;
  int pendingFarCount = 0;
  /** Whether the panel's Trees section showed last frame (the visible counts are read only then). */
  bool panelOpen = false;
  /** Visible instances per piece type of this frame's cull (read after the draw while the section shows). */
  std::vector<std::uint32_t> visible;
  /** Far trees the last impostor cull kept (read like `visible`; empty without a far field or when not
   * drawn). */
  std::optional<std::uint32_t> farVisible;

  /** Starts the far-field editor at the flags' values. */
  void resetPendingFar() {
    pendingFar = flags.farDistance > 0.0f;
    pendingFarDistance = pendingFar ? flags.farDistance : 150.0f;
    pendingFarBand = flags.farBand;
    pendingFarCount = flags.farCount;
  }

  /** The scene to draw this frame, or null when the trees are off. */
  trees::ForestScene* active() const { return enabled ? scene.get() : nullptr; }
  /** The wind the trees feel: the shared wind (Grass section sliders) × windStrength. */
  wind::WindSettings windFor(const GrassFlags& grassFlags) const {
    wind::WindSettings w = grassFlags.wind();
    w.speed *= windStrength;
    return w;
  }
};

/** Builds the forest of `t.flags` on `scene` and its GPU state; throws, leaving `t` as it was, on errors. */
void buildTrees(ViewerTrees& t, const terrain::TerrainScene& scene) {
  std::shared_ptr<trees::Forest> forest = t.flags.buildForest(scene);
  auto built = std::make_unique<trees::ForestScene>(t.shaders, forest, t.wind);
  built->setBark(t.flags.barkSources());
  t.flags.applyFoliage(*built);
  t.flags.applyFarField(*built, scene);
  log::info("trees: {} trees, {} pieces, {} joints", forest->trees.size(),
            built->renderer().instances().instances.size(), forest->jointCount);
  t.scene = std::move(built);
  t.visible.clear();
}

/** Rebuilds with `settings`; on an error keeps the old forest and settings and shows the message. */
void rebuildTrees(ViewerTrees& t, const terrain::TerrainScene& scene, const trees::ForestSettings& settings) {
  const trees::ForestSettings before = t.flags.forest;
  t.flags.forest = settings;
  try {
    buildTrees(t, scene);
    t.enabled = true;
    t.buildError.clear();
  } catch (const Error& e) {
    t.flags.forest = before;
    t.buildError = e.what();
    log::error("{}", e.what());
  }
}

/**
 * Sum of the GPU times of this frame's tree passes ("trees cull", "trees", "trees wind", "foliage bake",
 * "foliage", "impostors cull", "impostors"), ms.
 */
double treesGpuMs(const render::GpuTimers& timers) {
  double ms = 0.0;
  for (const render::PassTiming& p : timers.lastFrame()) {
    const bool tree =
        p.name.rfind("trees", 0) == 0 || p.name.rfind("foliage", 0) == 0 || p.name.rfind("impostors", 0) == 0;
    ms += tree ? p.gpuMs : 0.0;
  }
  return ms;
}

/** "bark: N tile sets of T×T texels (M layers)" or "bark: flat colours", as the scene draws it now. */
std::string barkStatus(const trees::ForestScene& scene) {
  const std::vector<trees::BarkSet>& sets = scene.barkSets();
  if (sets.empty()) {
    return "bark: flat colours";
  }
  std::size_t layers = 0;
  for (const trees::BarkSet& set : sets) {
    layers += set.colour.size();
  }
  return fmt::format("bark: {} tile set{} of {}x{} texels ({} layers)", sets.size(),
                     sets.size() == 1 ? "" : "s", sets[0].tileSize, sets[0].tileSize, layers);
}

/**
 * Re-bakes the far field after bark or foliage changed, so the impostors look like the trees they replace
 * (nothing without a far field). Throws like applyFarField.
 */
void rebakeFarField(ViewerTrees& t, const terrain::TerrainScene& scene) {
  if (t.scene && t.scene->impostors() != nullptr) {
    t.flags.applyFarField(*t.scene, scene);
  }
}

/** Bark from --trees-bark `mode`; on an error keeps the bark drawn and shows the message. */
void applyBark(ViewerTrees& t, const terrain::TerrainScene& scene, const std::string& mode) {
  const std::string before = t.flags.bark;
  t.flags.bark = mode;
  bool changed = false;
  try {
    if (t.scene) {
      t.scene->setBark(t.flags.barkSources());
      changed = true;
      rebakeFarField(t, scene);
    }
    t.surfaceError.clear();
  } catch (const Error& e) {
    if (!changed) {
      t.flags.bark = before; // the scene kept its bark: the combo shows it
    }
    t.surfaceError = e.what();
    log::error("{}", e.what());
  }
}

/**
 * The trees section of the panel: on/off (building the forest on the first enable), species mix (rebuilds at
 * once), count, seed and spacing (rebuilt by Rebuild), live tessellation, draw distance, wind and view, bark
 * and foliage (at once), the far field (applied by Apply), and the forest's, the foliage's, the impostors'
 * and the last cull's counts, GPU time and memory.
 */
void treesPanel(ViewerTrees& t, const terrain::TerrainScene& scene, const render::GpuTimers& timers) {
  t.panelOpen = ImGui::CollapsingHeader("Trees", t.enabled ? ImGuiTreeNodeFlags_DefaultOpen : 0);
  if (!t.panelOpen) {
    return;
  }
  const ImGuiSliderFlags clamp = ImGuiSliderFlags_AlwaysClamp;
  const ImGuiSliderFlags logarithmic = clamp | ImGuiSliderFlags_Logarithmic;
  if (ImGui::Checkbox("trees enabled", &t.enabled) && t.enabled && !t.scene) {
    try {
      buildTrees(t, scene);
      t.buildError.clear();
    } catch (const Error& e) {
      t.enabled = false;
      t.buildError = e.what();
      log::error("{}", e.what());
    }
  }
  const int mixBefore = t.mix;
  if (ImGui::BeginCombo("species", t.mixes[static_cast<std::size_t>(t.mix)].label.c_str())) {
    for (std::size_t i = 0; i < t.mixes.size(); ++i) {
      if (ImGui::Selectable(t.mixes[i].label.c_str(), static_cast<int>(i) == t.mix)) {
        t.mix = static_cast<int>(i);
      }
    }
    ImGui::EndCombo();
  }
  if (t.mix != mixBefore) {
    trees::ForestSettings settings = t.flags.forest;
    settings.species = t.mixes[static_cast<std::size_t>(t.mix)].species;
    rebuildTrees(t, scene, settings);
    if (t.flags.forest.species != settings.species) {
      t.mix = mixBefore; // the rebuild failed: the combo shows what is drawn
    }
  }
  ImGui::SliderInt("count", &t.pendingCount, 0, 20000, "%d", logarithmic);
  ImGui::InputInt("seed", &t.pendingSeed);
  t.pendingSeed = std::max(t.pendingSeed, 0);
  ImGui::SliderFloat("spacing (m)", &t.pendingSpacing, 0.0f, 100.0f, "%.1f", clamp);
  const trees::ForestSettings& built = t.flags.forest;
  const bool edited = t.pendingCount != built.count ||
                      static_cast<std::uint64_t>(t.pendingSeed) != built.seed ||
                      t.pendingSpacing != built.spacing;
  ImGui::BeginDisabled(!edited && t.scene != nullptr);
  if (ImGui::Button("Rebuild")) {
    trees::ForestSettings settings = t.flags.forest;
    settings.count = t.pendingCount;
    settings.seed = static_cast<std::uint64_t>(t.pendingSeed);
    settings.spacing = t.pendingSpacing;
    rebuildTrees(t, scene, settings);
  }
  ImGui::EndDisabled();
  if (edited) {
    ImGui::SameLine();
    if (ImGui::Button("Revert##trees")) {
      t.pendingCount = built.count;
      t.pendingSeed = static_cast<int>(built.seed);
      t.pendingSpacing = built.spacing;
    }
  }
  errorText(t.buildError);

  ImGui::Separator();
  trees::TreeLod& lod = t.flags.lod;
  ImGui::SliderFloat("pixels per segment", &lod.pixelsPerSegment, 0.5f, 100.0f, "%.1f", logarithmic);
  ImGui::SliderFloat("max level", &lod.maxLevel, 1.0f, 64.0f, "%.0f", clamp);
  ImGui::SliderFloat("fixed level (0: by distance)", &lod.fixedLevel, 0.0f, 64.0f, "%.0f", clamp);
  ImGui::SliderFloat("tree distance (m, 0: all)", &lod.drawDistance, 0.0f, 5000.0f, "%.0f", logarithmic);
  if (ImGui::Checkbox("wind on trees", &t.wind) && t.scene) {
    try {
      t.scene->setWind(t.wind);
    } catch (const Error& e) {
      t.wind = false;
      t.buildError = e.what();
      log::error("{}", e.what());
    }
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!t.wind);
  ImGui::SetNextItemWidth(120.0f);
  ImGui::SliderFloat("strength", &t.windStrength, 0.0f, 4.0f, "%.2f", clamp);
  ImGui::EndDisabled();
  disabledTooltip("times the wind speed of the Grass section (direction and gusts from there too)");
  const char* views[] = {"shaded", "piece types", "bones (root weights)", "LOD levels", "bark tiles (ids)"};
  ImGui::Combo("trees view", &t.view, views, 5);
  disabledTooltip("foliage and far impostors show in the shaded view only");

  ImGui::Separator();
  const int barkModes = t.barkDirectory.empty() ? 3 : 4;
  int bark = 3;
  for (int i = 0; i < 3; ++i) {
    bark = t.flags.bark == kBarkModes[i] ? i : bark;
  }
  const std::string directoryLabel = "tile set: " + t.barkDirectory;
  auto barkLabel = [&](int i) { return i < 3 ? kBarkLabels[i] : directoryLabel.c_str(); };
  if (ImGui::BeginCombo("bark", barkLabel(bark))) {
    for (int i = 0; i < barkModes; ++i) {
      if (ImGui::Selectable(barkLabel(i), i == bark) && i != bark) {
        applyBark(t, scene, i < 3 ? kBarkModes[i] : t.barkDirectory);
      }
    }
    ImGui::EndCombo();
  }
  disabledTooltip("photos: each species' bark photos synthesised into tiles (procedural where missing); "
                  "synthesis takes a while the first time, then comes from the cache");
  if (t.scene) {
    ImGui::TextUnformatted(barkStatus(*t.scene).c_str());
  }
  if (ImGui::Checkbox("foliage", &t.flags.foliage) && t.scene) {
    try {
      t.flags.applyFoliage(*t.scene);
      rebakeFarField(t, scene);
      t.surfaceError.clear();
    } catch (const Error& e) {
      t.flags.foliage = t.scene->foliage() != nullptr; // the checkbox shows what is drawn
      t.surfaceError = e.what();
      log::error("{}", e.what());
    }
  }
  disabledTooltip("2.5D leaf impostors at the branch tips (with a far field, its impostors are re-baked)");

  ImGui::Checkbox("far field (impostors)", &t.pendingFar);
  ImGui::BeginDisabled(!t.pendingFar);
  ImGui::SliderFloat("far distance (m)", &t.pendingFarDistance, 1.0f, 5000.0f, "%.0f", logarithmic);
  disabledTooltip("trees farther than this become octahedral impostors");
  ImGui::SliderFloat("band (m)", &t.pendingFarBand, 0.1f, 1000.0f, "%.1f", logarithmic);
  disabledTooltip("over how many metres they dissolve into their impostors");
  ImGui::InputInt("impostor-only trees", &t.pendingFarCount, 100, 1000);
  t.pendingFarCount = std::clamp(t.pendingFarCount, 0, 2000000);
  disabledTooltip("trees added around the forest out to the terrain's edge, drawn as impostors only");
  ImGui::EndDisabled();
  const bool farOn = t.flags.farDistance > 0.0f;
  const bool farEdited =
      t.pendingFar != farOn ||
      (t.pendingFar && (t.pendingFarDistance != t.flags.farDistance || t.pendingFarBand != t.flags.farBand ||
                        t.pendingFarCount != t.flags.farCount));
  ImGui::BeginDisabled(!farEdited);
  if (ImGui::Button("Apply##far")) {
    const TreeFlags before = t.flags;
    t.flags.farDistance = t.pendingFar ? t.pendingFarDistance : 0.0f;
    if (t.pendingFar) {
      t.flags.farBand = t.pendingFarBand;
      t.flags.farCount = t.pendingFarCount;
    }
    try {
      if (t.scene) {
        t.flags.applyFarField(*t.scene, scene); // bakes the atlas: seconds on llvmpipe
      }
      t.surfaceError.clear();
    } catch (const Error& e) {
      t.flags = before; // setFarField replaces the impostors only when it succeeds
      t.surfaceError = e.what();
      log::error("{}", e.what());
    }
  }
  ImGui::EndDisabled();
  disabledTooltip("bakes every species' impostor atlas (a few seconds on a software renderer)");
  if (farEdited) {
    ImGui::SameLine();
    if (ImGui::Button("Revert##far")) {
      t.resetPendingFar();
    }
  }
  errorText(t.surfaceError);

  if (t.scene) {
    ImGui::Separator();
    const trees::Forest& forest = t.scene->forest();
    const trees::TreeRenderer& renderer = t.scene->renderer();
    ImGui::Text("trees             %zu", forest.trees.size());
    ImGui::Text("pieces            %zu", renderer.instances().instances.size());
    ImGui::Text("joints            %zu", forest.jointCount);
    if (t.enabled && !t.visible.empty()) {
      std::size_t total = 0;
      for (std::size_t type = 0; type < t.visible.size(); ++type) {
        total += t.visible[type];
        const std::string& name = type < forest.pieces.size() ? forest.pieces[type].name
                                                              : std::string("type ") + std::to_string(type);
        ImGui::Text("  visible %-8s %u / %u", name.c_str(), t.visible[type],
                    type < renderer.instances().count.size() ? renderer.instances().count[type] : 0u);
      }
      ImGui::Text("visible pieces    %zu", total);
    }
    if (t.scene->windOn()) {
      ImGui::Text("wind steps        %d this frame (%.0f Hz)", t.scene->lastSteps(),
                  1.0 / trees::kForestWindStep);
    }
    if (const trees::FoliageRenderer* foliage = t.scene->foliage()) {
      const trees::FoliageStats stats = foliage->stats();
      ImGui::Text("foliage           %zu billboards, %d px cloud, %zu bakes", stats.anchors,
                  stats.textureSize, stats.bakes);
    } else {
      ImGui::TextUnformatted("foliage           off"); // a line either way: the rows above stay in place
    }
    if (const trees::ImpostorRenderer* impostors = t.scene->impostors()) {
      ImGui::Text("far trees         %zu (%d species baked)", impostors->treeCount(),
                  impostors->speciesCount());
      if (t.enabled && t.farVisible) {
        ImGui::Text("  visible far     %u", *t.farVisible);
      }
      ImGui::Text("impostor memory   %.1f MB", static_cast<double>(impostors->gpuBytes()) / 1e6);
    }
    ImGui::Text("GPU time          %.3f ms (cull, wind, draw, foliage, impostors)", treesGpuMs(timers));
    ImGui::Text("GPU memory        %.1f MB", static_cast<double>(t.scene->gpuBytes()) / 1e6);
  }
}

void runViewer(const ViewOptions& o) {
  platform::GlfwWindow window(o.width, o.height, "Sylva viewer");
  window.setVsync(o.frames == 0);
  const gl::ContextInfo info = gl::queryContextInfo();
  shader::Library library(o.shaderDir);
  ViewerScene v;
  ViewerGrass grass;
  ViewerTrees woods; // the forest (not `trees`: that would hide the namespace)
  render::Camera start;
  if (o.scene == "terrain") {
    v.terrain = o.terrain.build(library);
    v.lod = v.terrain->quadtree().config();
    v.method = v.lod.method == terrain::CrackMethod::PaperSearch ? 0
               : v.lod.method == terrain::CrackMethod::None      ? 2
                                                                 : 1;
    // The same framing as `sylva render` with the same flags; fog stays fixed from there on.
    const glm::ivec2 size = window.framebufferSize();
    start = o.camera.camera(*v.terrain, static_cast<float>(std::max(size.x, 1)) /
                                            static_cast<float>(std::max(size.y, 1)));
    grass.flags = o.grass;
    grass.flags.windDirection = std::remainder(o.grass.windDirection, 360.0f); // the slider's -180..180
    grass.enabled = o.grass.enabled;
    grass.shaders = library;
    grass.cull = grass.applied = o.grass.cullSettings();
    grass.pending = o.grass.field;
    grass.view = static_cast<int>(o.grass.grassView());
    grass.simFlags = o.simulation;
    if (grass.enabled) {
      buildGrass(grass, *v.terrain);
      if (o.camera.cameraPos.empty()) {
        start = grassCamera(*v.terrain, grass.renderer->field(), start.fovY, o.grass.windDirection);
      }
      if (o.simulation.enabled()) {
        // As `sylva render --physics balls`: balls dropped on a slope near the grass camera, watched from
        // downhill unless --camera-pos says where to look from.
        buildSimulation(grass, *v.terrain);
        const glm::vec2 drop = ballDropPoint(v.terrain->field(), grass.renderer->field(), start);
        grass.simulation->spawnBalls(drop, 1.5f, o.simulation.balls, o.simulation.seed, 0.5f);
        if (o.camera.cameraPos.empty()) {
          start = ballCamera(*v.terrain, drop, start.fovY);
        }
      }
    }
    woods.flags = o.trees;
    woods.enabled = o.trees.enabled;
    woods.shaders = library;
    woods.mixes = speciesMixes(o.trees.forest.species);
    woods.pendingCount = o.trees.forest.count;
    woods.pendingSeed = static_cast<int>(std::min<std::uint64_t>(o.trees.forest.seed, 0x7fffffff));
    woods.pendingSpacing = o.trees.forest.spacing;
    woods.wind = o.trees.wind;
    woods.view = static_cast<int>(o.trees.treeView());
    const bool barkPreset = o.trees.bark == "auto" || o.trees.bark == "procedural" || o.trees.bark == "none";
    woods.barkDirectory = barkPreset ? std::string() : o.trees.bark;
    woods.resetPendingFar();
    if (woods.enabled) {
      buildTrees(woods, *v.terrain);
      if (o.camera.cameraPos.empty() && !grass.enabled) {
        // As `sylva render --trees`: a tree near the centre, from a little above eye height.
        start = forestCamera(*v.terrain, woods.scene->forest(), start.fovY);
      }
    }
    v.draw = v.terrain->drawOptions(start, o.camera.fog);
    v.draw.countVertices = true;
  } else {
    v.demo = std::make_unique<render::DemoScene>(library);
    start = v.demo->defaultCamera();
  }
  render::OrbitController orbit = render::OrbitController::from(start);
  if (v.terrain) {
    // Zoom out until the whole terrain is a small part of the view, in until a few samples fill it.
    const Aabb box = v.terrain->bounds();
    orbit.maxDistance = std::max(4.0f * orbit.distance, 2.0f * glm::length(box.max - box.min));
    orbit.minDistance =
        std::max(0.5f, 2.0f * std::min(v.terrain->field().spacingX(), v.terrain->field().spacingZ()));
  }
  render::FlyController fly;
  fly.speed = std::max(10.0f, 0.05f * orbit.distance);
  bool flyMode = false;
  bool paused = false;
  std::string status = v.terrain
                           ? "F5: reload shaders  F: fly/orbit  G: walk  B: throw a ball  Tab: hide panel"
                           : "F5: reload shaders  F: fly/orbit  Tab: hide panel";
  bool throwRequested = false;
  bool showUi = !o.noUi;
  render::GpuTimers timers;
  render::FrameClock clock(o.fixedStep);
  std::deque<float> frameTimes;
  double sceneTime = 1.0;

  auto reload = [&] {
    // Reload from the source tree unless a directory was given: the point is editing shaders live.
    shader::Library disk(o.shaderDir.empty() ? shader::Library::sourceDirectory()
                                             : std::filesystem::path(o.shaderDir));
    try {
      if (v.terrain) {
        v.terrain->renderer().reloadShaders(disk);
        if (grass.renderer) {
          grass.renderer->reloadShaders(disk);
        }
        if (grass.simulation) {
          grass.simulation->reloadShaders(disk);
        }
        grass.shaders = disk; // fields built from now on use the edited shaders too
        if (woods.scene) {
          woods.scene->reloadShaders(disk);
        }
        woods.shaders = disk;
      } else {
        v.demo->reloadShaders(disk);
      }
      status = "shaders reloaded from " + disk.directory().string();
    } catch (const Error& e) {
      status = e.what();
      log::error("{}", e.what());
    }
  };
  window.setKeyCallback([&](int key, int) {
    if (ImGui::GetIO().WantCaptureKeyboard) {
      return;
    }
    if (key == GLFW_KEY_F5) {
      reload();
    } else if (key == GLFW_KEY_F) {
      flyMode = !flyMode;
    } else if (key == GLFW_KEY_G) {
      v.walk = !v.walk;
      flyMode = flyMode || v.walk;
    } else if (key == GLFW_KEY_B) {
      throwRequested = v.terrain != nullptr; // thrown once the frame's camera is known
    } else if (key == GLFW_KEY_TAB) {
      showUi = !showUi;
    } else if (key == GLFW_KEY_ESCAPE) {
      glfwSetWindowShouldClose(window.handle(), GLFW_TRUE);
    }
  });

  ui::ImGuiLayer ui(window);
  int frame = 0;
  render::Camera camera = start;
  while (window.pollEvents()) {
    const double dt = clock.tick();
    if (!paused) {
      sceneTime += dt;
    }
    const glm::ivec2 size = window.framebufferSize();
    if (size.x == 0 || size.y == 0) {
      continue;
    }
    const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);
    const platform::InputState& in = window.input();
    const bool mouseFree = !ImGui::GetIO().WantCaptureMouse;
    if (flyMode) {
      const glm::vec3 move = ui::flyKeys(window);
      const bool look = mouseFree && in.mouseLeft;
      fly.update(move, look ? static_cast<float>(in.cursorDelta.x) : 0.0f,
                 look ? static_cast<float>(in.cursorDelta.y) : 0.0f, static_cast<float>(dt));
      if (v.walk && v.terrain) {
        // Ground query: eyes 1.8 m above the interpolated surface, the height the terrain pass draws.
        const float ground = terrain::heightAt(v.terrain->field(), fly.position.x, fly.position.z);
        if (!std::isnan(ground)) {
          fly.position.y = ground + 1.8f;
        }
      }
      fly.apply(camera);
      camera.fovY = start.fovY;
    } else {
      if (mouseFree && in.mouseLeft) {
        orbit.rotate(static_cast<float>(in.cursorDelta.x), static_cast<float>(in.cursorDelta.y));
      }
      if (mouseFree && (in.mouseRight || in.mouseMiddle)) {
        orbit.pan(static_cast<float>(in.cursorDelta.x), static_cast<float>(in.cursorDelta.y));
      }
      if (mouseFree) {
        orbit.zoom(static_cast<float>(in.scrollDelta));
      }
      orbit.apply(camera);
      camera.fovY = start.fovY;
      fly.position = camera.position; // switching to fly mode starts where the orbit camera is
      const glm::vec3 d = glm::normalize(camera.target - camera.position);
      fly.yaw = std::atan2(d.x, d.z);
      fly.pitch = std::asin(d.y);
    }

    if (v.terrain) {
      Aabb box = v.terrain->bounds();
      if (woods.active() != nullptr) {
        // Crowns reach above the terrain's highest point: keep them between the clip planes too.
        box.min = glm::min(box.min, woods.active()->bounds().min);
        box.max = glm::max(box.max, woods.active()->bounds().max);
      }
      render::fitClipPlanes(camera, box); // wherever the orbit or fly camera went
      if (grass.active() != nullptr) {
        camera.nearPlane = std::min(camera.nearPlane, 0.05f); // blades right below the eye (as grassCamera)
      }
    } else {
      camera.nearPlane = start.nearPlane;
      camera.farPlane = start.farPlane;
    }
    timers.beginFrame();
    if (v.terrain) {
      if (throwRequested) {
        throwBall(grass, *v.terrain, camera); // nothing while grass is off
        throwRequested = false;
      }
      if (grass.simulation && grass.active() != nullptr) {
        // Simulation time follows the frames (the fixed step when scripted, so screenshots repeat) and stops
        // with the pause; a long real-time hitch counts as 0.1 s so Bullet does not catch up all at once.
        if (!paused) {
          grass.simTime += clock.fixed() ? dt : std::min(dt, 0.1);
        }
        timers.begin("grass sim");
        grass.simulation->advance(grass.simTime, grass.flags.wind());
        timers.end();
      }
      if (woods.active() != nullptr) {
        // The springs follow the scene time at their fixed rate (the fixed step when scripted, so
        // screenshots repeat) and stop with the pause.
        woods.active()->advance(sceneTime, woods.windFor(grass.flags), 8, &timers);
      }
    }
    gl::bindDefaultFramebuffer(size.x, size.y);
    gl::setDepthTest(true);
    const glm::vec3 sky = v.terrain ? v.draw.environment.fogColor : glm::vec3(0.62f, 0.72f, 0.85f);
    gl::clear(glm::vec4(sky, 1.0f), true);
    if (v.terrain) {
      drawTerrainWithGrass(*v.terrain, grass.active(), camera, size.x, size.y, sceneTime, v.draw,
                           grass.drawOptions(), &timers);
      if (woods.active() != nullptr) {
        trees::TreeDrawOptions treeOptions;
        treeOptions.view = static_cast<trees::TreeView>(woods.view);
        treeOptions.environment = v.draw.environment;
        woods.active()->draw(camera, size.x, size.y, sceneTime, woods.flags.lod, treeOptions, &timers);
      }
      if (grass.simulation && grass.active() != nullptr) {
        timers.begin("bodies");
        grass.simulation->drawBodies(camera, size.x, size.y, sceneTime, v.draw.environment);
        timers.end();
      }
      if (showUi && grass.active() != nullptr) {
        grass.counters = grass.active()->readCounters();
      }
      if (showUi && woods.panelOpen && woods.active() != nullptr) {
        woods.visible = woods.active()->renderer().readVisibleCounts(); // synchronous: only while shown
        const trees::ImpostorRenderer* impostors = woods.active()->impostors();
        woods.farVisible.reset();
        if (impostors != nullptr && woods.view == static_cast<int>(trees::TreeView::Shaded)) {
          woods.farVisible = impostors->readVisibleCount(); // drawn in the shaded view only
        }
      }
    } else {
      v.demo->render(camera, size.x, size.y, sceneTime, &timers, v.draw.wireframe);
    }
    if (showUi) {
      timers.begin("ui");
      ui.begin();
      const float avg = ui::beginPanel("Sylva", info.renderer, frameTimes);
      ImGui::Text("frame %.2f ms (%.0f fps)", avg, avg > 0.0f ? 1000.0f / avg : 0.0f);
      std::vector<float> plot(frameTimes.begin(), frameTimes.end());
      ImGui::PlotLines("##frametimes", plot.data(), static_cast<int>(plot.size()), 0, nullptr, 0.0f, 50.0f,
                       ImVec2(260, 40));
      passTimingTable(timers);
      if (v.terrain) {
        terrainPanel(v, camera, aspect);
        grassPanel(grass, *v.terrain);
        simulationPanel(grass, *v.terrain, camera);
        treesPanel(woods, *v.terrain, timers);
      } else {
        ImGui::Checkbox("wireframe", &v.draw.wireframe);
      }
      ImGui::Separator();
      ImGui::Checkbox("pause time", &paused);
      ImGui::SameLine();
      ImGui::Checkbox("fly camera (F)", &flyMode);
      if (ImGui::Button("reload shaders (F5)")) {
        reload();
      }
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 420.0f);
      ImGui::TextUnformatted(status.c_str());
      ImGui::PopTextWrapPos();
      ImGui::PopItemWidth();
      ImGui::End();
      ui.end();
      timers.end();
    }
    timers.endFrame();
    if (ui::endWindowFrame(window, size, o.screenshot, o.frames, frame, dt, frameTimes)) {
      break;
    }
  }
}

} // namespace

void registerView(CLI::App& app) {
  auto* command =
      app.add_subcommand("view", "Open the interactive viewer on a scene file (docs/scenes.md) or "
                                 "--scene (orbit: drag/right-drag/wheel; F: "
                                 "fly with WASD/QE; G: walk on the ground; "
                                 "B: throw a ball into the grass; F5: reload shaders)");
  auto o = std::make_shared<ViewOptions>();
  command
      ->add_option("file", o->file,
                   "A scene file (data/scenes/*.json): starts at its output camera; a checkbox per pass "
                   "(keys 1-8), its cameras, Space pauses, per-pass timings")
      ->check(CLI::ExistingFile);
  command->add_option("--scene", o->scene, "terrain, or demo (the small built-in pipeline test scene)")
      ->check(CLI::IsMember({"terrain", "demo"}))
      ->capture_default_str();
  o->terrain.add(*command);
  o->camera.add(*command);
  o->grass.add(*command);
  o->simulation.add(*command);
  o->trees.add(*command);
  command->add_option("--width", o->width, "Window width")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  command->add_option("--height", o->height, "Window height")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  command
      ->add_option("--shader-dir", o->shaderDir,
                   "Load shaders from this directory (default: embedded; F5 reloads from the source tree)")
      ->check(CLI::ExistingDirectory);
  addScriptedWindowOptions(*command, o->frames, o->screenshot, o->fixedStep);
  command->add_flag("--no-ui", o->noUi, "Start with the ImGui panel hidden");
  command->callback([o] {
    if (!o->file.empty()) {
      if (o->grass.enabled || o->trees.enabled || o->simulation.enabled()) {
        fail("--grass, --trees and --physics: a scene file says what it holds ({})", o->file);
      }
      SceneViewOptions scene;
      scene.file = o->file;
      scene.width = o->width;
      scene.height = o->height;
      scene.shaderDir = o->shaderDir;
      scene.frames = o->frames;
      scene.screenshot = o->screenshot;
      scene.fixedStep = o->fixedStep;
      scene.noUi = o->noUi;
      runSceneViewer(scene);
      return;
    }
    o->camera.check();
    // Checked even without --grass: the panel can turn the field on with these settings.
    o->grass.check();
    if (o->grass.enabled && o->scene != "terrain") {
      fail("--grass: grass grows on a terrain (--scene terrain), not on the {} scene", o->scene);
    }
    if (o->simulation.enabled() && !o->grass.enabled) {
      fail("--physics: needs --grass (the bodies move through the grass field)");
    }
    // Checked even without --trees: the panel can turn the forest on with these settings.
    o->trees.check();
    if (o->trees.enabled && o->scene != "terrain") {
      fail("--trees: trees grow on a terrain (--scene terrain), not on the {} scene", o->scene);
    }
    // Checked even without --physics: B and the panel start a simulation with these settings.
    (void)o->simulation.solverSettings();
    (void)o->simulation.poolSettings();
    runViewer(*o);
  });
}

} // namespace sylva::app

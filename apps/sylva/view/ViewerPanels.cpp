#include "view/ViewerPanels.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/scene/Viewpoints.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/scene/SceneForest.hpp>
#include <sylva/scene/SceneGrass.hpp>
#include <sylva/scene/gpu/GrassSimulation.hpp>
#include <sylva/scene/gpu/Ground.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/trees/Species.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>
#include <sylva/ui/ImGuiLayer.hpp>

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace sylva::app {

namespace {

constexpr ImGuiSliderFlags kClamp = ImGuiSliderFlags_AlwaysClamp;
constexpr ImGuiSliderFlags kLogarithmic = kClamp | ImGuiSliderFlags_Logarithmic;

/** Runs `change`; on sylva::Error shows its message in `error` (and the log) and returns false. */
template <typename F> bool attempt(std::string& error, F&& change) {
  try {
    change();
    error.clear();
    return true;
  } catch (const Error& e) {
    error = e.what();
    log::error("{}", e.what());
    return false;
  }
}

/** A collapsing section, open at first when `open`. */
bool section(const char* label, bool open) {
  return ImGui::CollapsingHeader(label, open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

/** "a, b, c". */
std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) {
    out += (out.empty() ? "" : ", ") + n;
  }
  return out;
}

std::vector<std::string> speciesOf(const scene::ForestDesc& forest) {
  std::vector<std::string> names;
  for (const auto& [name, weight] : forest.species) {
    names.push_back(name);
  }
  return names;
}

/**
 * The mixes of the trees section: the one given (the default mix unless given), all presets, then each
 * preset alone.
 */
std::vector<SpeciesMix> speciesMixes(const std::vector<std::string>& given) {
  std::vector<SpeciesMix> mixes;
  std::vector<std::string> defaults = TreeFlags::defaultForest().species;
  std::sort(defaults.begin(), defaults.end());
  mixes.push_back({(given == defaults ? "default mix: " : "given: ") + joinNames(given), given});
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

/** The bark combo's choices (--trees-bark values); a tile-set directory given on the command line comes last.
 */
constexpr const char* kBarkModes[] = {"auto", "procedural", "none"};
constexpr const char* kBarkLabels[] = {"photos (auto)", "procedural", "flat colours (none)"};

/** Sum of the GPU times of this frame's tree passes (trees*, foliage*, impostors*), ms. */
double treesGpuMs(const render::GpuTimers& timers) {
  double ms = 0.0;
  for (const render::PassTiming& p : timers.lastFrame()) {
    const bool tree =
        p.name.rfind("trees", 0) == 0 || p.name.rfind("foliage", 0) == 0 || p.name.rfind("impostors", 0) == 0;
    ms += tree ? p.gpuMs : 0.0;
  }
  return ms;
}

/** "bark: N tile sets of T×T texels (M layers)" or "bark: flat colours", as the forest draws it now. */
std::string barkStatus(const trees::ForestScene& forest) {
  const std::vector<trees::BarkSet>& sets = forest.barkSets();
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

} // namespace

// ---------------------------------------------------------------------------------------------------------
// Terrain

TerrainPanel::TerrainPanel(scene::SceneWorld& world) : lod(world.terrain().quadtree().config()) {
  method = lod.method == terrain::CrackMethod::PaperSearch ? 0
           : lod.method == terrain::CrackMethod::None      ? 2
                                                           : 1;
  scene::SceneDrawOptions draw = world.drawOptions();
  draw.countVertices = true;
  view = static_cast<int>(draw.terrainView);
  world.setDrawOptions(draw);
}

void TerrainPanel::show(scene::SceneWorld& world, const render::Camera& camera, float aspect,
                        ui::CameraRig& rig) {
  terrain::TerrainScene& scene = world.terrain();
  scene::SceneDrawOptions draw = world.drawOptions();
  if (section("Terrain LOD", open)) {
    bool changed = false;
    const char* methods[] = {"paper (quadtree search)", "ours (restricted level map)", "none (shows cracks)"};
    changed |= ImGui::Combo("crack method", &method, methods, 3);
    changed |= ImGui::SliderInt("tessellation", &lod.patchTessLevel, 1, terrain::kMaxPatchTessLevel);
    changed |= ImGui::SliderFloat("LOD distance factor", &lod.lodDistanceFactor,
                                  terrain::kMinRestrictedLodFactor, 8.0f);
    changed |= ImGui::SliderFloat("screen error (px, 0: distance LOD)", &lod.lodErrorPixels, 0.0f, 8.0f);
    changed |= ImGui::SliderInt("max depth", &lod.maxDepth, 0, 8);
    changed |= ImGui::Checkbox("LOD enabled", &lod.lodEnabled);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("frustum culling", &lod.frustumCull);
    if (changed) {
      lod.method = method == 0   ? terrain::CrackMethod::PaperSearch
                   : method == 1 ? terrain::CrackMethod::RestrictedLevelMap
                                 : terrain::CrackMethod::None;
      scene.setQuadtreeConfig(lod);
    }
    const char* views[] = {"shaded", "LOD colours", "normals", "splat layers"};
    ImGui::Combo("view", &view, views, 4);
    draw.terrainView = static_cast<terrain::TerrainView>(view);
    ImGui::Checkbox("wireframe", &draw.wireframe);
    ImGui::SameLine();
    ImGui::Checkbox("skirts (crack check)", &draw.terrainSkirts);
    if (ImGui::Checkbox("freeze frustum", &freeze)) {
      draw.frozenFrustum = freeze ? std::optional<Frustum>(camera.frustum(aspect)) : std::nullopt;
    }
    bool walk = rig.walking();
    if (ImGui::Checkbox("walk on the ground (G)", &walk)) {
      rig.toggleWalk();
    }
    const terrain::QuadtreeSelection& sel = scene.selection();
    ImGui::Text("nodes drawn       %d", sel.stats.leaves);
    ImGui::Text("nodes culled      %d", sel.stats.nodesCulled);
    ImGui::Text("edges doubled     %d", sel.stats.doubledEdges);
    ImGui::Text("vertices (GPU)    %lld", static_cast<long long>(scene.renderer().lastVertexInvocations()));
    ImGui::Text("vertices (CPU est) %llu", static_cast<unsigned long long>(sel.stats.processedVertices));
    ImGui::Text("LOD update        %.3f ms", scene.lastUpdateMs());
    if (draw.terrainSkirts) {
      ImGui::Text("crack pixels      %lld", static_cast<long long>(scene.renderer().lastCrackSamples()));
    }
  }
  world.setDrawOptions(draw);
}

// ---------------------------------------------------------------------------------------------------------
// Grass and simulation

GrassPanel::GrassPanel(scene::SceneWorld& world, const WorldFlags& flags)
    : fresh(flags.grass.layerDesc()), wind(world.desc().wind), dropSeed(flags.simulation.seed) {
  fresh.simulate = false;
  pending = world.grassCount() > 0 ? world.desc().grass[0] : fresh;
  cull = world.grassCount() > 0 ? world.grassCull(0) : flags.grass.cullSettings();
  pending.cull = cull;
  view = static_cast<int>(world.drawOptions().grassView);
  open = world.grassCount() > 0;
}

bool GrassPanel::active(scene::SceneWorld& world) const {
  return world.grassCount() > 0 && world.passes().enabled(scene::Pass::Grass);
}

void GrassPanel::show(scene::SceneWorld& world) {
  if (!section("Grass", open)) {
    return;
  }
  scene::ScenePasses& passes = world.passes();
  bool enabled = active(world);
  if (ImGui::Checkbox("grass enabled", &enabled)) {
    if (enabled && world.grassCount() == 0) {
      fresh.cull = cull;
      enabled = attempt(buildError, [&] { world.setGrassLayer(0, fresh); });
    }
    passes.setEnabled(scene::Pass::Grass, enabled);
  }
  scene::SceneDrawOptions draw = world.drawOptions();
  const char* views[] = {"shaded", "LOD colours", "tiles"};
  if (ImGui::Combo("grass view", &view, views, 3)) {
    draw.grassView = static_cast<grass::GrassView>(view);
    world.setDrawOptions(draw);
  }
  bool cullChanged = false;
  cullChanged |= ImGui::SliderFloat("draw distance (m)", &cull.maxDistance, 5.0f, 500.0f, "%.0f", kClamp);
  cullChanged |=
      ImGui::SliderFloat("LOD 16 > 8 knots (m)", &cull.lodDistances[0], 0.0f, 200.0f, "%.1f", kClamp);
  cullChanged |=
      ImGui::SliderFloat("LOD 8 > 4 knots (m)", &cull.lodDistances[1], 0.0f, 400.0f, "%.1f", kClamp);
  cullChanged |= ImGui::SliderFloat("LOD cross-fade (m)", &cull.lodFade, 0.0f, 20.0f, "%.1f", kClamp);
  cullChanged |= ImGui::SliderFloat("far fade (m)", &cull.farFade, 0.0f, 125.0f, "%.1f", kClamp);
  cullChanged |= ImGui::SliderInt("near tufts (blades per blade)", &cull.nearLayers, 1, 16, "%d", kClamp);
  cullChanged |= ImGui::SliderFloat("near tufts reach (m)", &cull.nearDistance, 0.0f, 30.0f, "%.1f", kClamp);
  if (cullChanged) {
    attempt(cullError, [&] {
      if (world.grassCount() > 0) {
        world.setGrassCull(0, cull);
        cull = world.grassCull(0); // as the scene file would have it (the far fade at most a quarter)
      } else {
        grass::validate(cull);
      }
      pending.cull = cull;
    });
  }
  ui::errorText(cullError);
  bool windChanged = ImGui::SliderFloat("wind speed (m/s)", &wind.speed, 0.0f, 60.0f, "%.1f", kClamp);
  windChanged |= ImGui::SliderFloat("wind towards (deg)", &wind.direction, 0.0f, 360.0f, "%.0f", kClamp);
  ui::disabledTooltip("clockwise from north (-z); trees and the simulation feel it too");
  windChanged |= ImGui::SliderFloat("gust strength", &wind.gusts, 0.0f, 4.0f, "%.2f", kClamp);
  if (windChanged) {
    world.setWind(wind);
  }

  ImGui::Separator();
  ImGui::TextUnformatted("field (rebuilt on Apply)");
  ImGui::SliderFloat("density", &pending.density, 0.0f, 1.0f, "%.2f", kClamp);
  ImGui::SliderFloat("coverage", &pending.coverage, 0.0f, 1.0f, "%.2f", kClamp);
  ImGui::SliderInt("patch blades", &pending.patchBlades, 1, 1 << 22, "%d", kLogarithmic);
  ImGui::SliderInt("blades per tile", &pending.bladesPerTile, 1, 1 << 16, "%d", kLogarithmic);
  ImGui::SliderFloat("tile size (m)", &pending.tileSize, 0.25f, 20.0f, "%.2f", kLogarithmic);
  const scene::GrassLayer& built = world.grassCount() > 0 ? world.desc().grass[0] : fresh;
  const bool edited = pending.density != built.density || pending.coverage != built.coverage ||
                      pending.patchBlades != built.patchBlades ||
                      pending.bladesPerTile != built.bladesPerTile || pending.tileSize != built.tileSize;
  ImGui::BeginDisabled(!edited && world.grassCount() > 0);
  if (ImGui::Button("Apply")) {
    scene::GrassLayer next = built;
    next.density = pending.density;
    next.coverage = pending.coverage;
    next.patchBlades = pending.patchBlades;
    next.bladesPerTile = pending.bladesPerTile;
    next.tileSize = pending.tileSize;
    next.cull = cull;
    if (attempt(buildError, [&] { world.setGrassLayer(0, next); })) {
      passes.setEnabled(scene::Pass::Grass, true);
      counters.reset();
    }
  }
  ImGui::EndDisabled();
  if (world.simulation() != nullptr) {
    ui::disabledTooltip("rebuilds the field: the simulation restarts with the scene's own bodies");
  }
  if (edited) {
    ImGui::SameLine();
    if (ImGui::Button("Revert")) {
      pending = built;
      pending.cull = cull;
    }
  }
  ui::errorText(buildError);

  if (world.grassCount() > 0) {
    ImGui::Separator();
    const grass::GrassField& field = world.grass(0).field();
    const grass::FieldLayout& layout = field.layout();
    ImGui::Text("blade types       %zu", field.types().size());
    ImGui::Text("tiles             %d x %d of %.2f m", layout.tilesX, layout.tilesZ, layout.tileSize);
    ImGui::Text("patch blades      %zu (%d per tile)", field.patch().size(), layout.bladesPerTile);
    ImGui::Text("field blades      %.3g (estimate)", field.estimateBlades());
    if (active(world) && counters) {
      const gpu::GrassCounters& c = *counters;
      ImGui::Text("visible tiles     %u", c.dispatch.x);
      ImGui::Text("drawn blades      %u", c.blades.x);
      ImGui::Text("instances 16/8/4  %u / %u / %u", c.draws[0].y, c.draws[1].y, c.draws[2].y);
      ImGui::Text("culled: frustum %u, distance %u, edge-on %u", c.blades.y, c.blades.z, c.blades.w);
      if (c.overflow.x != 0 || c.overflow.y != 0) {
        ui::errorText(
            fmt::format("lists full: {} instances and {} tiles dropped", c.overflow.x, c.overflow.y));
      }
    }
    ImGui::Text("GPU memory        %.1f MB", static_cast<double>(world.grass(0).gpuBytes()) / 1e6);
  }
}

bool GrassPanel::ensureSimulation(scene::SceneWorld& world) {
  if (world.simulation() != nullptr) {
    return true;
  }
  if (!active(world)) {
    return false;
  }
  return attempt(simError, [&] { world.simulateGrass(0); });
}

bool GrassPanel::throwBall(scene::SceneWorld& world, const render::Camera& camera) {
  if (!ensureSimulation(world)) {
    return false;
  }
  constexpr float kRadius = 0.35f;
  const glm::vec3 forward = camera.forward();
  glm::vec3 at = camera.position + forward;
  const float ground = world.groundHeight(at.x, at.z);
  if (!std::isnan(ground)) {
    at.y = std::max(at.y, ground + kRadius);
  }
  world.spawnBall(at, 8.0f * forward + glm::vec3(0.0f, 1.0f, 0.0f));
  log::info("ball thrown at ({:.1f}, {:.1f}, {:.1f}) m: {} bodies", at.x, at.y, at.z, world.bodies());
  return true;
}

bool GrassPanel::dropBalls(scene::SceneWorld& world, const render::Camera& camera, int count) {
  if (!ensureSimulation(world)) {
    return false;
  }
  const auto layer = static_cast<std::size_t>(world.simulatedLayer());
  const glm::vec2 drop = scene::ballDropPoint(world.terrain().field(), world.grass(layer).field(), camera);
  world.simulation()->spawnBalls(drop, 1.5f, count, dropSeed + static_cast<std::uint64_t>(++drops), 0.5f);
  return true;
}

void GrassPanel::showSimulation(scene::SceneWorld& world, const render::Camera& camera) {
  const scene::GrassSimulation* simulation = world.simulation();
  if (!section("Simulation", open && simulation != nullptr)) {
    return;
  }
  const bool grassOn = active(world);
  const char* why = grassOn ? "" : "needs grass: turn it on in the Grass section";
  const int pool = world.desc().grassSim.pool.tiles;
  if (simulation != nullptr) {
    const grass::SimStats& s = simulation->stats();
    ImGui::Text("bodies            %zu", simulation->bodies());
    ImGui::Text("active tiles      %zu / %d", s.activeTiles, pool);
    ImGui::Text("simulated blades  %zu", s.simulatedBlades);
    if (s.refusedTiles > 0) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
    }
    ImGui::Text("refused tiles     %zu", s.refusedTiles);
    if (s.refusedTiles > 0) {
      ImGui::PopStyleColor();
      ui::disabledTooltip(
          "tiles near a body found the pool full (--grass-pool): their blades ignore the bodies");
    }
    ImGui::Text("steps this frame  %d", s.steps);
    ImGui::Text("solver            %s", simulation->onGpu() ? "GPU (compute shader)" : "CPU (SIMD)");
    ImGui::Text("time              %.2f s", simulation->time());
  } else {
    ImGui::TextUnformatted("no bodies yet (B or the buttons below start the simulation)");
    const scene::GrassSolve solve = world.desc().grassSim.solve;
    ImGui::Text("solver            %s", solve == scene::GrassSolve::Gpu   ? "GPU (compute shader)"
                                        : solve == scene::GrassSolve::Cpu ? "CPU (SIMD)"
                                                                          : "auto (CPU on llvmpipe)");
  }
  ImGui::BeginDisabled(!grassOn);
  if (ImGui::Button("Throw ball (B)")) {
    throwBall(world, camera);
  }
  ui::disabledTooltip(grassOn ? "a 0.35 m, 30 kg ball from the camera, 8 m/s forward" : why);
  ImGui::SameLine();
  if (ImGui::Button("Drop 10 balls")) {
    dropBalls(world, camera, 10);
  }
  ui::disabledTooltip(grassOn ? "on the steepest grassy slope within 40 m of the camera" : why);
  ImGui::SameLine();
  if (ImGui::Button("Reset") && ensureSimulation(world)) {
    attempt(simError, [&] { world.clearBodies(); });
  }
  ui::disabledTooltip(grassOn ? "removes every body and restarts the simulation" : why);
  ImGui::EndDisabled();
  ui::errorText(simError);
}

// ---------------------------------------------------------------------------------------------------------
// Trees

TreesPanel::TreesPanel(scene::SceneWorld& world, const TreeFlags& flags) {
  if (world.forestCount() > 0) {
    desc = world.desc().forests[0];
    look =
        desc.look ? *desc.look : scene::forestLook(desc, scene::sceneFieldName(world.desc(), "/forests/0"));
  } else {
    desc = flags.forestDesc();
    look = flags.look();
  }
  desc.look = look;
  mixes = speciesMixes(speciesOf(desc));
  const bool barkPreset = look.bark == "auto" || look.bark == "procedural" || look.bark == "none";
  barkDirectory = barkPreset ? std::string() : look.bark;
  open = world.forestCount() > 0;
  resetPending();
  resetPendingFar();
}

void TreesPanel::resetPending() {
  pendingCount = desc.count;
  pendingSeed = static_cast<int>(std::min<std::uint64_t>(desc.seed, 0x7fffffff));
  pendingSpacing = desc.spacing;
  pendingAutumn = desc.autumn;
  pendingLeafFall = desc.leafFall;
}

void TreesPanel::resetPendingFar() {
  pendingFar = look.farDistance > 0.0f;
  pendingFarDistance = pendingFar ? look.farDistance : 150.0f;
  pendingFarBand = look.farBand;
  pendingFarCount = look.farCount;
}

bool TreesPanel::active(scene::SceneWorld& world) const {
  return world.forestCount() > 0 && world.passes().enabled(scene::Pass::Trees);
}

void TreesPanel::rebuild(scene::SceneWorld& world, const scene::ForestDesc& next) {
  if (attempt(buildError, [&] { world.setForest(0, next); })) {
    desc = next;
    visible.clear();
    world.passes().setEnabled(scene::Pass::Trees, true);
  }
}

void TreesPanel::rebakeFarField(scene::SceneWorld& world) {
  if (world.forestCount() > 0 && world.forest(0).impostors() != nullptr) {
    world.forest(0).applyFarField(look, world.forestPlacement(0), scene::farGround(world.terrain()));
  }
}

void TreesPanel::applyBark(scene::SceneWorld& world, const std::string& mode) {
  trees::ForestLook next = look;
  next.bark = mode;
  attempt(surfaceError, [&] {
    if (world.forestCount() > 0) {
      world.forest(0).setBark(trees::barkSources(next));
    }
    look = next; // the forest has the new bark: the combo shows it even if the far field fails below
    desc.look = look;
    rebakeFarField(world);
  });
}

void TreesPanel::readCounts(scene::SceneWorld& world) {
  if (!open || !active(world)) {
    return;
  }
  trees::ForestScene& forest = world.forest(0);
  visible = forest.renderer().readVisibleCounts(); // synchronous: only while shown
  farVisible.reset();
  const trees::ImpostorRenderer* impostors = forest.impostors();
  if (impostors != nullptr && world.drawOptions().treeView == trees::TreeView::Shaded) {
    farVisible = impostors->readVisibleCount(); // drawn in the shaded view only
  }
}

void TreesPanel::show(scene::SceneWorld& world, const render::GpuTimers& timers) {
  open = section("Trees", open);
  if (!open) {
    return;
  }
  const bool built = world.forestCount() > 0;
  bool enabled = active(world);
  if (ImGui::Checkbox("trees enabled", &enabled)) {
    if (enabled && !built) {
      rebuild(world, desc);
      enabled = world.forestCount() > 0;
    }
    world.passes().setEnabled(scene::Pass::Trees, enabled);
  }
  const int mixBefore = mix;
  if (ImGui::BeginCombo("species", mixes[static_cast<std::size_t>(mix)].label.c_str())) {
    for (std::size_t i = 0; i < mixes.size(); ++i) {
      if (ImGui::Selectable(mixes[i].label.c_str(), static_cast<int>(i) == mix)) {
        mix = static_cast<int>(i);
      }
    }
    ImGui::EndCombo();
  }
  if (mix != mixBefore) {
    scene::ForestDesc next = desc;
    next.species.clear();
    for (const std::string& name : mixes[static_cast<std::size_t>(mix)].species) {
      next.species[name] = 1.0f;
    }
    rebuild(world, next);
    if (desc.species != next.species) {
      mix = mixBefore; // the rebuild failed: the combo shows what is drawn
    }
  }
  ImGui::SliderInt("count", &pendingCount, 0, 20000, "%d", kLogarithmic);
  ImGui::InputInt("seed", &pendingSeed);
  pendingSeed = std::max(pendingSeed, 0);
  ImGui::SliderFloat("spacing (m)", &pendingSpacing, 0.0f, 100.0f, "%.1f", kClamp);
  ImGui::SliderFloat("autumn", &pendingAutumn, 0.0f, 1.0f, "%.2f", kClamp);
  ui::disabledTooltip("leaves: 0 summer green, 1 each species' autumn colour");
  ImGui::SliderFloat("leaf fall", &pendingLeafFall, 0.0f, 1.0f, "%.2f", kClamp);
  ui::disabledTooltip("deciduous leaves fallen: 0 none, 1 bare winter crowns (evergreens keep theirs)");
  const bool edited = pendingCount != desc.count || static_cast<std::uint64_t>(pendingSeed) != desc.seed ||
                      pendingSpacing != desc.spacing || pendingAutumn != desc.autumn ||
                      pendingLeafFall != desc.leafFall;
  ImGui::BeginDisabled(!edited && built);
  if (ImGui::Button("Rebuild")) {
    scene::ForestDesc next = desc;
    next.count = pendingCount;
    next.seed = static_cast<std::uint64_t>(pendingSeed);
    next.spacing = pendingSpacing;
    next.autumn = pendingAutumn;
    next.leafFall = pendingLeafFall;
    rebuild(world, next);
  }
  ImGui::EndDisabled();
  if (edited) {
    ImGui::SameLine();
    if (ImGui::Button("Revert##trees")) {
      resetPending();
    }
  }
  ui::errorText(buildError);

  ImGui::Separator();
  scene::SceneDrawOptions draw = world.drawOptions();
  trees::TreeLod& lod = draw.treeLod;
  ImGui::SliderFloat("pixels per segment", &lod.pixelsPerSegment, 0.5f, 100.0f, "%.1f", kLogarithmic);
  ImGui::SliderFloat("max level", &lod.maxLevel, 1.0f, 64.0f, "%.0f", kClamp);
  ImGui::SliderFloat("fixed level (0: by distance)", &lod.fixedLevel, 0.0f, 64.0f, "%.0f", kClamp);
  ImGui::SliderFloat("tree distance (m, 0: all)", &lod.drawDistance, 0.0f, 5000.0f, "%.0f", kLogarithmic);
  ImGui::SliderFloat("min size (pixels)", &lod.minPixels, 0.0f, 100.0f, "%.2f", kLogarithmic);
  ImGui::SliderFloat("min width (pixels)", &lod.minWidthPixels, 0.0f, 100.0f, "%.2f", kLogarithmic);
  if (ImGui::Checkbox("wind on trees", &desc.wind) && built) {
    if (!attempt(buildError, [&] { world.forest(0).setWind(desc.wind); })) {
      desc.wind = false;
    }
  }
  ui::disabledTooltip("the wind of the Grass section (speed, direction, gusts)");
  int view = static_cast<int>(draw.treeView);
  const char* views[] = {"shaded", "piece types", "bones (root weights)", "LOD levels", "bark tiles (ids)"};
  if (ImGui::Combo("trees view", &view, views, 5)) {
    draw.treeView = static_cast<trees::TreeView>(view);
  }
  ui::disabledTooltip("foliage and far impostors show in the shaded view only");
  world.setDrawOptions(draw);

  ImGui::Separator();
  const int barkModes = barkDirectory.empty() ? 3 : 4;
  int bark = 3;
  for (int i = 0; i < 3; ++i) {
    bark = look.bark == kBarkModes[i] ? i : bark;
  }
  const std::string directoryLabel = "tile set: " + barkDirectory;
  auto barkLabel = [&](int i) { return i < 3 ? kBarkLabels[i] : directoryLabel.c_str(); };
  if (ImGui::BeginCombo("bark", barkLabel(bark))) {
    for (int i = 0; i < barkModes; ++i) {
      if (ImGui::Selectable(barkLabel(i), i == bark) && i != bark) {
        applyBark(world, i < 3 ? kBarkModes[i] : barkDirectory);
      }
    }
    ImGui::EndCombo();
  }
  ui::disabledTooltip("photos: each species' bark photos synthesised into tiles (procedural where missing); "
                      "synthesis takes a while the first time, then comes from the cache");
  if (built) {
    ImGui::TextUnformatted(barkStatus(world.forest(0)).c_str());
  }
  if (ImGui::Checkbox("foliage", &look.foliage)) {
    desc.look = look;
    if (built) {
      attempt(surfaceError, [&] {
        world.forest(0).applyFoliage(look);
        rebakeFarField(world);
      });
      look.foliage = world.forest(0).foliage() != nullptr; // the checkbox shows what is drawn
      desc.look = look;
    }
  }
  ui::disabledTooltip(
      "2.5D leaf impostors at the branch tips (with a far field, its impostors are re-baked)");

  ImGui::Checkbox("far field (impostors)", &pendingFar);
  ImGui::BeginDisabled(!pendingFar);
  ImGui::SliderFloat("far distance (m)", &pendingFarDistance, 1.0f, 5000.0f, "%.0f", kLogarithmic);
  ui::disabledTooltip("trees farther than this become octahedral impostors");
  ImGui::SliderFloat("band (m)", &pendingFarBand, 0.1f, 1000.0f, "%.1f", kLogarithmic);
  ui::disabledTooltip("over how many metres they dissolve into their impostors");
  ImGui::InputInt("impostor-only trees", &pendingFarCount, 100, 1000);
  pendingFarCount = std::clamp(pendingFarCount, 0, 2000000);
  ui::disabledTooltip("trees added around the forest out to the terrain's edge, drawn as impostors only");
  ImGui::EndDisabled();
  const bool farOn = look.farDistance > 0.0f;
  const bool farEdited = pendingFar != farOn ||
                         (pendingFar && (pendingFarDistance != look.farDistance ||
                                         pendingFarBand != look.farBand || pendingFarCount != look.farCount));
  ImGui::BeginDisabled(!farEdited);
  if (ImGui::Button("Apply##far")) {
    trees::ForestLook next = look;
    next.farDistance = pendingFar ? pendingFarDistance : 0.0f;
    if (pendingFar) {
      next.farBand = pendingFarBand;
      next.farCount = pendingFarCount;
    }
    attempt(surfaceError, [&] {
      if (built) {
        // Bakes the atlases: seconds on llvmpipe; the impostors are replaced only when it succeeds.
        world.forest(0).applyFarField(next, world.forestPlacement(0), scene::farGround(world.terrain()));
      }
      look = next;
      desc.look = look;
    });
  }
  ImGui::EndDisabled();
  ui::disabledTooltip("bakes every species' impostor atlas (a few seconds on a software renderer)");
  if (farEdited) {
    ImGui::SameLine();
    if (ImGui::Button("Revert##far")) {
      resetPendingFar();
    }
  }
  ui::errorText(surfaceError);

  if (!built) {
    return;
  }
  ImGui::Separator();
  trees::ForestScene& forest = world.forest(0);
  const trees::Forest& placed = forest.forest();
  const trees::TreeRenderer& renderer = forest.renderer();
  ImGui::Text("trees             %zu", placed.trees.size());
  ImGui::Text("pieces            %zu", renderer.instances().instances.size());
  ImGui::Text("joints            %zu", placed.jointCount);
  if (active(world) && !visible.empty()) {
    std::size_t total = 0;
    for (std::size_t type = 0; type < visible.size(); ++type) {
      total += visible[type];
      const std::string& name = type < placed.pieces.size() ? placed.pieces[type].name
                                                            : std::string("type ") + std::to_string(type);
      ImGui::Text("  visible %-8s %u / %u", name.c_str(), visible[type],
                  type < renderer.instances().count.size() ? renderer.instances().count[type] : 0u);
    }
    ImGui::Text("visible pieces    %zu", total);
  }
  if (forest.windOn()) {
    ImGui::Text("wind steps        %d this frame (%.0f Hz)", forest.lastSteps(),
                1.0 / trees::kForestWindStep);
  }
  if (const trees::FoliageRenderer* foliage = forest.foliage()) {
    const trees::FoliageStats stats = foliage->stats();
    ImGui::Text("foliage           %zu billboards, %d px cloud, %zu bakes", stats.anchors, stats.textureSize,
                stats.bakes);
  } else {
    ImGui::TextUnformatted("foliage           off"); // a line either way: the rows above stay in place
  }
  if (const trees::ImpostorRenderer* impostors = forest.impostors()) {
    ImGui::Text("far trees         %zu (%d species baked)", impostors->treeCount(),
                impostors->speciesCount());
    if (active(world) && farVisible) {
      ImGui::Text("  visible far     %u", *farVisible);
    }
    ImGui::Text("impostor memory   %.1f MB", static_cast<double>(impostors->gpuBytes()) / 1e6);
  }
  ImGui::Text("GPU time          %.3f ms (cull, wind, draw, foliage, impostors)", treesGpuMs(timers));
  ImGui::Text("GPU memory        %.1f MB", static_cast<double>(forest.gpuBytes()) / 1e6);
}

} // namespace sylva::app

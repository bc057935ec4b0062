#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <set>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <sylva/core/FieldName.hpp>
#include <sylva/grass/Cull.hpp>
#include <sylva/grass/Simulation.hpp>
#include <sylva/grass/TileSimulation.hpp>
#include <sylva/terrain/TerrainSetup.hpp>
#include <sylva/trees/ForestLook.hpp>

/**
 * The scene file (docs/scenes.md): one versioned JSON document that composes terrain, grass, forests,
 * folding-textured water, physics bodies, sun, sky, fog, wind, shadows, cameras and the output sequence.
 *
 * All positions are world metres: x east, y up, z south; the terrain covers [0, extentX] × [0, extentZ] with
 * its minimum corner at the origin. Angles are degrees in JSON (and in these structs). Paths held here are
 * already resolved (absolute, against the scene file's directory) and were checked to exist when loaded.
 *
 * A description built in code (the command line: `sylva render --grass --trees`) may also set the fields
 * marked "code only", which say what a file cannot (a DEM's reading options, LOD bands, leaf images, ...);
 * files never set them.
 */
namespace sylva::scene {

/** The version this Sylva writes and reads ("sylva_scene": 1). Files with a higher number are refused. */
inline constexpr int kSceneVersion = 1;

/** Limits enforced by the loader (absurd counts are errors, not out-of-memory kills). */
inline constexpr int kMaxForestCount = 1'000'000;  ///< trees per forest
inline constexpr int kMaxBodies = 10'000;          ///< bodies + all drops' counts together
inline constexpr int kMaxFrames = 1'000'000;       ///< output frame numbers are in [0, kMaxFrames)
inline constexpr int kMaxImageSide = 16384;        ///< output width / height, pixels
inline constexpr float kMaxGrassDensity = 1000.0f; ///< grass density multiplier

/** A point whose y is either absolute (world metres) or, with `aboveGround`, measured up from the terrain. */
struct Vec3Ground {
  glm::vec3 p{0.0f};        ///< world metres; y absolute or above the terrain surface
  bool aboveGround = false; ///< JSON "above_ground": y is height above the terrain at (x, z)
};

/** The terrain: a DEM file or a procedural field, and its LOD settings. */
struct TerrainDesc {
  std::string dem;               ///< resolved absolute path of a height file; empty: procedural
  std::uint64_t seed = 1;        ///< procedural seed
  int size = 513;                ///< procedural samples per side (2^k + 1 preferred), [17, 8193]
  float spacing = 2.0f;          ///< metres between samples (procedural; overrides a DEM's spacing when set)
  bool spacingSet = false;       ///< whether "spacing" was given in the file (a DEM keeps its own otherwise)
  float relief = 120.0f;         ///< procedural height range, metres
  float exaggeration = 1.0f;     ///< vertical scale applied to the heights
  std::optional<float> seaLevel; ///< metres (data heights); below it the terrain reads as sea floor
  int tessLevel = 16;            ///< tessellation level per patch edge, [1, 32]
  float lodFactor = 2.0f;        ///< CDLOD distance factor, [1.05, 64]
  float lodError = 0.0f;         ///< screen-space-error LOD threshold, pixels, [0, 1000]; 0: distance LOD
  int maxDepth = -1;             ///< quadtree depth limit, [0, 16]; -1: automatic
  bool geomorph = true;          ///< morph vertices across LOD boundaries
  /** Code only: the terrain as the terrain module describes it, used instead of the fields above. */
  std::optional<terrain::TerrainSetup> setup;
};

/** One grass layer: blades on the terrain where the splat layer / paint map allow. */
struct GrassLayer {
  std::vector<std::string> blades; ///< resolved blade-model files; empty: the procedural blade
  float density = 1.0f;            ///< multiplier on the blade renderer's base density, [0, kMaxGrassDensity]
  float coverage = 1.0f;           ///< fraction of cells that hold grass, [0, 1]
  std::string layer = "grass";     ///< terrain splat layer that carries this grass; "none": everywhere
  std::string paint;               ///< resolved density-map PNG over the terrain extent; empty: none
  float maxSlope = 35.0f;          ///< true degrees (before exaggeration); steeper ground has no grass
  std::uint64_t seed = 1;          ///< placement seed
  bool simulate = false;           ///< blade physics simulation on (else wind-only animation)
  float distance = 60.0f;          ///< draw distance, metres
  int nearLayers = 8;         ///< grass::CullSettings::nearLayers: tufts up to this many times denser near
  float nearDistance = 8.0f;  ///< grass::CullSettings::nearDistance, metres
  bool extremeBlades = false; ///< accept blade models outside grass::BladeSizeLimits
  // Not in scene files (the command line sets them: --grass-blades, --grass-tile, --grass-per-tile).
  int patchBlades = 16384; ///< blades in the patch every tile draws from
  float tileSize = 2.0f;   ///< tile (and patch) side, metres
  int bladesPerTile = 256; ///< blades a tile draws at density 1 (at most patchBlades)
  /** Code only: draw distance, LOD bands and fades, instead of those derived from `distance`. */
  std::optional<grass::CullSettings> cull;
  /** Code only: the density noise's frequency, per metre (0: one density everywhere, as in the paper's
   * field); nullopt: the grass module's default. */
  std::optional<float> noiseFrequency;
};

/** One forest: a species mix placed by rules evaluated from the terrain. */
struct ForestDesc {
  std::map<std::string, float> species;  ///< preset name (e.g. "oak") or resolved species file → weight > 0
  int count = 100;                       ///< trees to place, [0, kMaxForestCount]
  std::uint64_t seed = 1;                ///< placement and growth seed
  float spacing = 4.0f;                  ///< minimum distance between trunks, metres
  float maxSlope = 30.0f;                ///< degrees
  float autumn = 0.0f;                   ///< leaves: 0 summer … 1 each species' full autumn colour
  float leafFall = 0.0f;                 ///< deciduous leaves fallen: 0 none … 1 bare (winter)
  std::optional<float> minHeight;        ///< metres (world heights, after exaggeration)
  std::optional<float> maxHeight;        ///< metres
  std::string densityMap;                ///< resolved PNG over the terrain extent (white dense); empty: none
  float clusterSize = 60.0f;             ///< metres; scale of the clustering noise
  float bare = 0.35f;                    ///< fraction of the noise field left without trees, [0, 1)
  std::optional<glm::vec2> regionCentre; ///< (x, z) metres; with regionRadius, limits placement to a disc
  float regionRadius = 0.0f;             ///< metres; 0: no region limit
  std::string bark = "auto";             ///< "auto", "none" or a bark tile-set name/file
  bool foliage = true;                   ///< draw leaves
  float farDistance = 0.0f;              ///< metres beyond which trees become far-field impostors; 0: off
  float farBand = 25.0f;                 ///< cross-fade band width at farDistance, metres
  int farCount = 0;                      ///< extra far-field-only trees, [0, kMaxForestCount]
  /** Code only: bark, foliage and far field with every setting (leaf images, bark photos, ...), instead of
   * bark, foliage and far_*. */
  std::optional<trees::ForestLook> look;
  /** Code only: false draws the trees in their rest pose (no joint springs). */
  bool wind = true;
  /** Code only: a region radius without a centre is centred on the terrain's footprint. */
  bool regionAroundCentre = false;
};

/** A water plane at a level; its shore band can use a folding texture (wave swash). */
struct WaterDesc {
  float level = 0.0f;  ///< metres, data heights (before exaggeration)
  std::string folding; ///< resolved folding project (.json); empty: ShoreSettings' default (the wave swash)
  float band = 6.0f;   ///< shore band width, metres of horizontal distance
  float tile = 12.0f;  ///< folding-texture tile size, metres
};

/** One rigid body. */
struct BodyDesc {
  /** A ball (radius) or a box (half extents). */
  enum class Shape { Ball, Box };
  /** The body's shape. */
  Shape shape = Shape::Ball;
  Vec3Ground position;         ///< centre, world metres
  glm::vec3 velocity{0.0f};    ///< metres per second
  float radius = 0.35f;        ///< metres (ball)
  glm::vec3 halfExtents{0.3f}; ///< metres (box)
  float mass = 30.0f;          ///< kg
};

/** A drop of `count` balls at random positions inside a disc, `height` metres above the terrain. */
struct BodyDrop {
  glm::vec2 centre{0.0f}; ///< (x, z) metres
  float radius = 2.0f;    ///< disc radius, metres
  int count = 8;          ///< balls
  /** Seed of where in the disc each ball drops. */
  std::uint64_t seed = 1;
  float height = 1.0f; ///< metres above the terrain
};

/** The sun. */
struct SunDesc {
  float azimuth = 135.0f; ///< degrees clockwise from north (-z) seen from above: 90 east (+x), 180 south (+z)
  float elevation = 35.0f; ///< degrees above the horizon, [-90, 90]
  float intensity = 1.1f;  ///< radiance multiplier
  /** Unit vector from the ground towards the sun, world space (x east, y up, z south). */
  glm::vec3 direction() const;
};

/** The analytic sky (atmosphere mode 1). */
struct SkyDesc {
  bool enabled = true;    ///< false: no analytic sky, plain fog colour (atmosphere mode 0)
  float turbidity = 3.0f; ///< [1.7, 10]
  float exposure = 1.0f;  ///< > 0
  bool flare = true;      ///< sun disc glare
};

/** Aerial perspective. */
struct FogDesc {
  float density = 0.0012f; ///< extinction per metre, ≥ 0
  /** Code only: instead of `density`, the fog of the farthest point of the terrain seen from the camera,
   * [0, 0.95] (`sylva render --fog`: the same look whatever the terrain's size). */
  std::optional<float> farSide;
};

/** The one wind field shared by grass and trees. */
struct WindDesc {
  float speed = 3.0f;      ///< metres per second
  float direction = 30.0f; ///< degrees clockwise from north, the direction the wind blows TOWARDS
  float gusts = 0.8f;      ///< gust strength, [0, 4]
  /** Seed of the gusts and turbulence. */
  std::uint64_t seed = 5;
};

/** Cascaded sun shadows. */
struct ShadowDesc {
  int cascades = 3;        ///< [0, 4]; 0: no shadows
  int size = 2048;         ///< shadow-map side, texels, [64, 8192]
  float distance = 300.0f; ///< metres covered by the cascades
  float lambda = 0.7f;     ///< practical split: 0 uniform, 1 logarithmic
};

/** Which grass solver steps the simulated tiles. */
enum class GrassSolve {
  /** The compute shader. */
  Gpu,
  /** The CPU solver (SIMD lanes, bit for bit the scalar reference). */
  Cpu,
  /** Cpu on a software rasteriser (llvmpipe runs compute shaders on the same cores, several times slower than
   * the CPU solver), Gpu otherwise. */
  Auto,
};

/** How simulated grass runs (code only: `--grass-sim`, `--grass-pool`, `--trample-recovery`). */
struct GrassSimSettings {
  /** The pool of simulated tiles: how many at once, how released tiles return to rest. */
  grass::PoolSettings pool;
  /** The constraint solver's step rate, damping and stiffness. */
  grass::SolverSettings solver;
  /** Where the solver runs: the GPU, the CPU, or Auto (the CPU on a software rasteriser). */
  GrassSolve solve = GrassSolve::Auto;
};

/** A camera key. */
struct CameraKey {
  double time = 0.0; ///< seconds; strictly increasing along a path
  /** Where the camera is at this key. */
  Vec3Ground position;
  /** What the camera looks at at this key. */
  Vec3Ground target;
  float fov = 50.0f; ///< vertical field of view, degrees, (0, 179)
};

/** A camera: one key is a still camera; more keys form a centripetal Catmull-Rom path (CameraPath.hpp). */
struct CameraDesc {
  std::vector<CameraKey> keys; ///< at least one, sorted by time
  bool loop = false;           ///< wrap time around the path's duration
};

/** The default frame sequence `sylva render` writes. */
struct OutputDesc {
  std::string camera = "main"; ///< a key of SceneDesc::cameras
  int width = 1280;            ///< pixels, [1, kMaxImageSide]
  int height = 720;            ///< pixels
  double fps = 24.0;           ///< frames per second of the fixed clock: frame f is at time f / fps
  int firstFrame = 0;          ///< first frame number, inclusive
  int lastFrame = 0;           ///< last frame number, inclusive
};

/** A whole scene, validated. */
struct SceneDesc {
  std::string path; ///< the scene file (as given to loadScene / parseScene)
  std::string name; ///< "name" in the file; default: the file's stem
  /** The terrain. */
  TerrainDesc terrain;
  /** Grass layers, drawn in order. */
  std::vector<GrassLayer> grass;
  /** Forests. */
  std::vector<ForestDesc> forests;
  /** Water planes (lakes, sea). */
  std::vector<WaterDesc> water;
  /** Rigid bodies at the start. */
  std::vector<BodyDesc> bodies;
  /** Balls dropped into the grass at given times. */
  std::vector<BodyDrop> drops;
  /** The sun. */
  SunDesc sun;
  /** The sky model. */
  SkyDesc sky;
  /** Fog. */
  FogDesc fog;
  /** The wind shared by grass and trees. */
  WindDesc wind;
  /** Sun shadows. */
  ShadowDesc shadows;
  GrassSimSettings grassSim; ///< code only
  /** Code only: names a field in errors from its JSON pointer ("/grass/0/paint" → "--grass-paint"); empty:
   * "<path>: <pointer>", as for a file. */
  std::function<std::string(std::string_view pointer)> fieldNames;
  std::map<std::string, CameraDesc> cameras; ///< at least the output camera
  /** What is rendered: size, frames, frame rate, camera, files. */
  OutputDesc output;
};

/**
 * Reads and validates a scene file; throws sylva::Error with one line "<file>: <json/path>: <what>", e.g.
 * "meadow.json: /forests/0/count: 2000000 is more than 1000000". Syntax errors read "<file>:<line>:<col>:
 * <what>". Relative paths in the file resolve against the file's directory; referenced files must exist.
 */
SceneDesc loadScene(const std::filesystem::path& file);

/**
 * Like loadScene, for JSON text already in memory; `fileForErrorsAndPaths` names the file in errors and its
 * directory resolves relative paths (it need not exist).
 */
SceneDesc parseScene(std::string_view json, const std::filesystem::path& fileForErrorsAndPaths);

/** The errors of a scene file read item by item (parseSceneAll). */
struct SceneFileErrors {
  std::vector<std::string> messages; ///< one line each, as parseScene would throw them, in file order
  std::set<std::string> items;       ///< list items that failed ("/grass/1"): the scene holds defaults there
};

/**
 * Like parseScene, but every section, list item and camera is read on its own: each error is appended to
 * `errors` and reading goes on, so one run lists them all (`sylva scene check`). Still throws for what stops
 * everything: JSON syntax, a root that is not an object, a missing or newer version.
 */
SceneDesc parseSceneAll(std::string_view json, const std::filesystem::path& fileForErrorsAndPaths,
                        SceneFileErrors& errors);

/**
 * Names the fields under JSON pointer `prefix` ("/terrain", "/grass/0", "/forests/1") of `scene` in errors:
 * through scene.fieldNames when code set it, else "<file>: <prefix>/<field>".
 */
FieldName sceneFieldName(const SceneDesc& scene, const std::string& prefix);

} // namespace sylva::scene

#pragma once
// Foliage as 2.5D impostors (seed 000 §6, specs/trees.md "2.5D impostor depth"): one leaf cloud, shared by
// every foliage-bearing piece of the forest, is rendered orthographically along the camera's view direction
// into a texture that keeps the lit colour in RGB and the depth across the cloud's bounding sphere in A; each
// foliage anchor then draws a camera-facing billboard on the front plane of its sphere that writes the depth
// the texel encodes, so billboards are depth-tested against each other and against the bark. This header is
// the CPU side: leaf clouds (procedural or from a model through Assimp), the depth encoding and the fragment
// depth rule as plain functions (twins of shaders/trees/leafcloud.frag and foliage.frag), and the anchors.
//
// Units: a leaf cloud lives in cloud units, inside the unit sphere around the origin; an anchor's sphere has
// a radius in metres, so one cloud unit is `radius` metres there. Cloud axes are world axes (the cloud is not
// turned per anchor, only its billboard image is turned in the image plane by a small angle).

#include <sylva/core/Image.hpp>
#include <sylva/trees/Forest.hpp>

#include <shared/Trees.h>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace sylva::trees {

/** One flat rectangular leaf of a cloud, cloud units. */
struct LeafCard {
  /** Centre of the card, cloud units. */
  glm::vec3 centre{0.0f};
  /** Unit normal of the side the texture faces. */
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  /** Direction of the texture's +v in the card's plane (made orthogonal to the normal). */
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  /** Width (along cross(up, normal), the texture's +u) and height (along up), cloud units. */
  glm::vec2 size{0.25f};
  /** Linear colour factor of this leaf (per-leaf variation; the species' leaf colour is applied on top). */
  glm::vec3 tint{1.0f};
};

/** One vertex of a cloud's triangles. */
struct LeafVertex {
  glm::vec3 position{0.0f}; ///< cloud units
  /** Unit normal. */
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec2 uv{0.0f}; ///< leaf texture coordinates, (0, 0) at the bottom left of the image
  /** Linear colour factor (per-leaf variation). */
  glm::vec3 tint{1.0f};
};
static_assert(sizeof(LeafVertex) == 44);

/** A leaf cloud: a triangle list (3 vertices per triangle), cloud units, inside the unit sphere. */
struct LeafCloud {
  /** The triangles' vertices, three per triangle. */
  std::vector<LeafVertex> vertices;

  /** Triangles in the cloud. */
  std::size_t triangles() const { return vertices.size() / 3; }
};

/** Appends `card` as two triangles (uv (0,0) at centre − right·w/2 − up·h/2). */
void appendCard(LeafCloud& cloud, const LeafCard& card);
/** The cards as triangles, positions as given (not normalised). */
LeafCloud leafCloudFromCards(std::span<const LeafCard> cards);

/**
 * Moves the cloud so its bounding sphere (centre: the middle of its bounding box, radius: the farthest vertex
 * from it) becomes the unit sphere at the origin. Throws sylva::Error "<where>: …" for a cloud without
 * triangles, with non-finite values, or with all vertices at one point.
 */
void normaliseLeafCloud(LeafCloud& cloud, const std::string& where);

/**
 * Throws sylva::Error "<where>: …" unless the cloud has 1 … 1,000,000 triangles, only finite values, unit
 * normals (within 1e-3) and every vertex within the unit sphere (1e-4 slack).
 */
void validate(const LeafCloud& cloud, const std::string& where);

/** How makeLeafCloud grows a cloud. */
struct LeafCloudSettings {
  /** Leaves (cards) in the cloud, 1 … 100,000. */
  int leaves = 320;
  /** Edge length of a leaf card before normalisation, in units of the cloud's radius, (0, 1]. */
  float leafSize = 0.26f;
  /** Clusters the leaves gather in (twig ends), 1 … 1,000. */
  int clusters = 14;
  /** Leaves lie on a shell between this fraction of the radius and the radius, [0, 1). */
  float shell = 0.45f;
  /** Random brightness and hue variation of the leaves, [0, 1]. */
  float tintVariation = 0.18f;
  /** Seed of the leaves' places, turns and tints. */
  std::uint64_t seed = 1;
};
/** Throws sylva::Error "<where>.<field>: …" for values out of range. */
void validate(const LeafCloudSettings& settings, const std::string& where);

/**
 * A procedural cloud: `leaves` cards, three in four in `clusters` clumps, on a spherical shell, facing mostly
 * outwards (and a little up), turned randomly in their plane, normalised into the unit sphere. Deterministic
 * in the settings.
 */
LeafCloud makeLeafCloud(const LeafCloudSettings& settings);

/** How makeNeedleCloud grows a conifer's needle sprays. */
struct NeedleCloudSettings {
  /** Shoots (twigs with needles all round), 1 … 1,000. */
  int shoots = 22;
  /** Needles per shoot, 1 … 1,000. */
  int needles = 44;
  /** Shoot length, in units of the cloud's radius, (0, 2]. */
  float shootLength = 0.75f;
  /** Needle length and width, in units of the cloud's radius, (0, 1]. */
  float needleLength = 0.13f;
  /** Needle width, in units of the cloud's radius, (0, 1]. */
  float needleWidth = 0.02f;
  /** Random brightness and hue variation of the needles, [0, 1]. */
  float tintVariation = 0.15f;
  /** Seed of the shoots and needles. */
  std::uint64_t seed = 1;
};
/** Throws sylva::Error "<where>.<field>: …" for values out of range. */
void validate(const NeedleCloudSettings& settings, const std::string& where);

/**
 * A procedural needle cloud: `shoots` twigs spread through the sphere (reaching outwards and drooping a
 * little at their tips), each set all round with `needles` narrow cards that leave the shoot at 40–70°
 * towards its tip (a bottle brush, as spruce and fir shoots are), normalised into the unit sphere. Drawn
 * without a leaf image: a needle is a card of its own. Deterministic in the settings.
 */
LeafCloud makeNeedleCloud(const NeedleCloudSettings& settings);

/**
 * Reads a leaf cloud from a model (any format Assimp reads: OBJ, glTF, Collada, FBX, …): every triangle of
 * every mesh (polygons triangulated, node transforms applied), texture coordinates from channel 0, normals
 * from the file or the triangles, vertex colours as tints, normalised into the unit sphere. Throws
 * sylva::Error with one line naming the file: Assimp's reason for a file it cannot read, `leaves.obj: no
 * triangles`, `leaves.obj: mesh 0 has no texture coordinates`, `leaves.obj: vertex 12 is not finite`, more
 * than `maxTriangles` triangles, or all vertices at one point.
 */
LeafCloud loadLeafCloud(const std::filesystem::path& file, std::size_t maxTriangles = 200000);

/**
 * A procedural leaf image (RGBA8, sRGB colour, straight alpha): an ovate leaf with a midrib and veins
 * pointing up the image, alpha 0 outside it; the fallback when no leaf texture is given. `size` texels
 * square, 8 … 4096.
 */
Image makeLeafImage(int size = 128);

/**
 * A leaf texture from an image file (PNG: grey+alpha or RGBA, 8 or 16 bits, palette images with transparency)
 * as 8-bit RGBA. Throws sylva::Error naming the file for unreadable files and images without an alpha channel
 * (leaves are alpha-tested).
 */
Image loadLeafImage(const std::filesystem::path& file);

/**
 * The mean linear colour of a leaf image's opaque texels (alpha ≥ 0.5; colour channels read as sRGB), or 1
 * when none is opaque. The renderer divides the species' leaf colour by it, so a species' leaves average to
 * its leafColour whatever the texture's own hue. Throws sylva::Error for images that are not 8-bit RGBA.
 */
glm::vec3 leafImageMean(const Image& image);

// ---- Depth across the sphere (twins of the shaders) ------------------------------------------------------

/** Steps of the depth code: A = (1 + ⌊254 t + ½⌋) / 255 for covered texels, 0 for empty ones. */
constexpr float kFoliageDepthSteps = 254.0f;

/** t = (z − (z_c − R)) / 2R: 0 on the sphere's front plane, 1 on its back plane (z along the view direction).
 */
float foliageDepthT(float z, float zCentre, float radius);
/** The alpha byte of a covered texel at depth t: 1 + ⌊254 · clamp(t, 0, 1) + ½⌋ (1 … 255; 0 means empty). */
std::uint8_t encodeFoliageDepth(float t);
/** The t an alpha byte stands for, (a − 1) / 254; a = 0 (empty) gives −1. */
float decodeFoliageDepth(std::uint8_t alpha);

/** The orthonormal basis of a bake: forward (view direction), right (the texture's +u), up (its +v). */
struct FoliageBasis {
  /** The view direction. */
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  /** The texture's +u. */
  glm::vec3 right{1.0f, 0.0f, 0.0f};
  /** The texture's +v. */
  glm::vec3 up{0.0f, 1.0f, 0.0f};
};
/**
 * The basis for a camera looking along `forward` with `up` (world): right = normalize(forward × up), up =
 * right × forward; an up parallel to forward is replaced by +z (or +x).
 */
FoliageBasis foliageBasis(glm::vec3 forward, glm::vec3 up);

/**
 * Orthographic world → clip matrix of the bake for cloud units: texel (u, v) ∈ [0, 1]² shows cloud point
 * p with (p·right, p·up) = (2u − 1, 2v − 1); window depth = t = (p·forward + 1) / 2.
 */
glm::mat4 foliageBakeMatrix(const FoliageBasis& basis);

/**
 * The billboard point of image point `xy` ∈ [−1, 1]² (cloud-plane coordinates, already turned by the anchor's
 * rotation) of a sphere at `centre` with `radius` metres: on the front plane, centre − forward·R + R(x·right
 * + y·up).
 */
glm::vec3 foliageQuadPoint(const FoliageBasis& basis, glm::vec3 centre, float radius, glm::vec2 xy);

/**
 * The fragment rule: the leaf a billboard point `quadPoint` (P_q, world metres) shows at depth `t` lies at
 * P = P_q + r·(2R·t) / dot(r, −n) with r the unit ray from `camera` through P_q and n = −forward the
 * billboard's normal; that is, 2R·t farther along the view direction than the front plane.
 */
glm::vec3 foliageFragmentPoint(glm::vec3 quadPoint, glm::vec3 camera, glm::vec3 forward, float radius,
                               float t);
/** Window depth (glDepthRange 0 … 1) of foliageFragmentPoint through `viewProj`. */
float foliageFragmentDepth(glm::vec3 quadPoint, glm::vec3 camera, glm::vec3 forward, float radius, float t,
                           const glm::mat4& viewProj);

// ---- Anchors
// -----------------------------------------------------------------------------------------------

/** Where billboards go and how the leaf texture is baked (scene files, `sylva render --trees`). */
struct FoliageSettings {
  /** Side of the square cloud texture, texels, 16 … 4096. */
  int textureSize = 256;
  /**
   * Sphere radius of an anchor, metres: radiusScale × the piece's bounding radius × its root joint's scale
   * (metres per rim unit), clamped to [minRadius, maxRadius]. Twig tips are a few centimetres across, so the
   * clamp decides most radii.
   */
  float radiusScale = 12.0f;
  /** Smallest anchor radius, metres. */
  float minRadius = 0.45f;
  /** Largest anchor radius, metres. */
  float maxRadius = 1.4f;
  /** Random per-anchor radius variation, ± fraction, [0, 0.9]. */
  float sizeVariation = 0.2f;
  /** Random per-anchor turn of the image in the billboard plane, ± radians, [0, π]. */
  float rotationVariation = 0.3f;
  /** Moves each cloud centre this fraction of its radius outwards along the branch tip (+y of the joint). */
  float lift = 0.35f;
  /** Seed of the per-anchor variations. */
  std::uint64_t seed = 1;
  /** The broad-leaf cloud (species with FoliageKind::Broadleaf). */
  LeafCloudSettings cloud;
  /** The needle cloud (species with FoliageKind::Needles). */
  NeedleCloudSettings needles;
};
/** Throws sylva::Error "<where>.<field>: …" for values out of range. */
void validate(const FoliageSettings& settings, const std::string& where);

/** One billboard: a sphere carried by a joint (so it follows the wind). */
struct FoliageAnchor {
  /** Global index of the root joint of the foliage-bearing piece instance. */
  std::uint32_t joint = 0;
  /** Index of the tree in the forest. */
  std::uint32_t tree = 0;
  /** Index of its species in the forest. */
  std::uint32_t species = 0;
  /** Sphere centre in the joint's frame, rim units. */
  glm::vec3 offset{0.0f};
  /** Sphere radius, metres (variation included). */
  float radius = 1.0f;
  /** In-plane turn of the image, radians. */
  float rotation = 0.0f;
};

/**
 * Whether `node` (a `piece`) of a tree of `species` carries a leaf cluster: a foliage-bearing piece (a twig
 * tip), or any non-root piece on an axis of the species' leafOrder or deeper (Species::leafOrder > 0).
 */
bool carriesLeaves(const Piece& piece, const TreeNode& node, const Species& species);

/**
 * One anchor per instance of a foliage-bearing piece (Piece::bearsFoliage) of every tree, and per piece on an
 * axis of its species' leafOrder or deeper (Species::leafOrder > 0), in tree order then
 * node order; radii from the rest frames (forestFrames without extra bends). Deterministic in the settings.
 */
std::vector<FoliageAnchor> foliageAnchors(const Forest& forest, const FoliageSettings& settings);

/** The GPU record of an anchor (FoliageAnchorGpu in shared/Trees.h). */
gpu::FoliageAnchorGpu packAnchor(const FoliageAnchor& anchor);

/** World position of an anchor's sphere centre for joint `frames` (the twin of foliage.vert). */
glm::vec3 anchorCentre(const FoliageAnchor& anchor, std::span<const gpu::JointFrame> frames);

} // namespace sylva::trees

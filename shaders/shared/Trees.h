// GPU layouts of trees (docs/trees.md), shared by C++ and GLSL.
#ifndef SYLVA_SHARED_TREES_H
#define SYLVA_SHARED_TREES_H

#include "Prelude.h"
#include "Wind.h"

SYLVA_GPU_BEGIN

#define SYLVA_TREE_BINDING 23           // uniform block TreeUniforms
#define SYLVA_TREE_JOINT_BINDING 24     // storage: JointFrame[] (every joint of every tree)
#define SYLVA_TREE_INSTANCE_BINDING 25  // storage: TreeInstanceGpu[] (every piece instance of every tree)
#define SYLVA_TREE_VISIBLE_BINDING 26   // storage: uint[] visible instance indices, one list per piece type
#define SYLVA_TREE_COMMAND_BINDING 27   // storage: the indirect draw commands (5 uints per piece type)
#define SYLVA_TREE_PIECE_BINDING 28     // storage: TreePieceGpu[] (bounds and inverse binds per piece type)
#define SYLVA_TREE_WIND_BINDING 29      // storage: joint wind state and constants (JointWind)
#define SYLVA_TREE_WIND_REST_BINDING 30 // storage: joint rest data (JointWind)
#define SYLVA_TREE_MAX_PIECE_JOINTS 4   // root + up to three terminal joints (Psi)
#define SYLVA_TREE_MAX_PIECES 8         // piece types in one renderer
#define SYLVA_TREE_CULL_GROUP 64
#define SYLVA_TREE_MAX_SPECIES 8 // species with their own bark colour in one renderer
// Storage bindings of the tree surface, foliage and far-field passes. They reuse numbers of the grass
// simulation's compute passes (never bound in one program together); every pass binds its buffers before use.
#define SYLVA_TREE_QUAD_BINDING                                                                              \
  16 // storage: uvec2[] per piece type per quad: x tile class | rotation << 8 | side flips << 10 | tile
     // repeat ratio << 16 | its growth << 24 (1/16), y its four edge ids (8 bits each; 255: a rim edge)
#define SYLVA_TREE_CENTRE_BINDING 17   // storage: vec4[] per tree: base (world xyz, m), crown height (w, m)
#define SYLVA_TREE_FOLIAGE_BINDING 18  // storage: foliage anchors (FoliageRenderer)
#define SYLVA_TREE_IMPOSTOR_BINDING 19 // storage: far-field impostor instances (ImpostorRenderer)
// Texture units of the tree passes.
#define SYLVA_TREE_BARK_COLOUR_UNIT 8 // sampler2DArray: bark tiles, colour (sRGB8_ALPHA8), one layer per tile
#define SYLVA_TREE_BARK_NORMAL_UNIT 9 // sampler2DArray: bark tiles, tangent-space normal (RGBA8, n = 2c - 1)
#define SYLVA_TREE_FOLIAGE_UNIT 10    // sampler2D: the 2.5D leaf-cloud impostor (rgb colour, a depth)
#define SYLVA_TREE_IMPOSTOR_UNIT 11   // sampler2DArray: far-field octahedral atlas (first of the units used)
#define SYLVA_TREE_MAX_TILE_CLASSES 4 // bark tile classes (the pieces use 0: plain, 1: by a fork, 2: crotch)
#define SYLVA_TREE_MAX_TILE_REPEAT 32 // most bark tiles along one quad's grain (sylva::trees::kMaxTileRepeat)

/**
 * A joint's world frame as three rows of a 3x4 matrix: world = (dot(x, p1), dot(y, p1), dot(z, p1)) with
 * p1 = (p, 1), p in the joint's frame (rim units). A child's root joint is its parent's terminal joint.
 */
struct JointFrame {
  vec4 x;
  vec4 y;
  vec4 z;
};
SYLVA_ASSERT_SIZE(JointFrame, 48);

/** One piece instance: x = root joint index, y = first terminal joint index, z = rim rotation (0 … 5) |
 * piece type << 4 | tile stretch << 8 (TreeNode::stretch × 16, rounded, 1 … 255: how many bark tiles its
 * quads take along the grain, sylva::trees::tileRepeat) | stretch reach << 16 (how far its stretch moves its
 * leaf rims up the root axis, model units in 8.8 fixed point; 0 unstretched), w = tree index | species << 24.
 * Read the fields of z with the macros below. */
struct TreeInstanceGpu {
  uvec4 joints;
};
SYLVA_ASSERT_SIZE(TreeInstanceGpu, 16);
#define SYLVA_TREE_INSTANCE_ROTATION(z) ((z)&15u)
#define SYLVA_TREE_INSTANCE_TYPE(z) (((z) >> 4) & 15u)
#define SYLVA_TREE_INSTANCE_STRETCH(z) (((z) >> 8) & 255u)
#define SYLVA_TREE_INSTANCE_REACH(z) ((z) >> 16)

/**
 * Per piece type: bounding sphere in model space (xyz centre, w radius, rim units), commands and list (x
 * first indirect command, y commands (quad chunks), z instance list offset, w index count), and the inverse
 * bind frame of each joint (rows).
 */
struct TreePieceGpu {
  vec4 sphere;
  uvec4 range;
  JointFrame inverseBind[SYLVA_TREE_MAX_PIECE_JOINTS];
};
SYLVA_ASSERT_SIZE(TreePieceGpu, 224);

/** Per draw: tessellation and culling settings. colours[s].w is species s's bark set (texture array layers
 * colours[s].w · bark.x onwards). */
struct TreeUniforms {
  vec4 frustum[6]; // world-space planes (xyz normal pointing inwards, w offset)
  vec4 tess;       // x: K (pixels-to-level factor: viewport height / (2 tan(fov/2)) / target pixels per
                   // segment), y: maximum level, z: fixed level (> 0 overrides the distance rule), w: cull
                   // distance in metres
  vec4 colours[SYLVA_TREE_MAX_SPECIES]; // bark colour (rgb) per species of the forest
  uvec4 info;         // x: instance count, y: piece types, z: view (TreeView), w: debug flags (1: break rims)
  vec4 cull;          // x: bounding-sphere slack factor for bends, y: quads per indirect command (a chunk's
                      // first quad is (gl_DrawID - the type's first command) * y); zw: size culling, a piece
                      // is dropped when its sphere's diameter < z * distance + w (sizeCullTerms)
  vec4 corners[6];    // rimCorner(k) exactly as the CPU computes it (xyz)
  vec4 rimNormals[6]; // rimNormal(k) (xyz)
  uvec4 quadTable[2]; // first entry of piece type t in the quad table at SYLVA_TREE_QUAD_BINDING: [t / 4][t %
                      // 4]
  uvec4 tileFirst;    // first layer of bark tile class c (0 … 3) within one species' bark set
  uvec4 tileCount;    // variants per edge colouring of class c (its tiles: K⁴ blocks of this many)
  vec4 bark;          // x: layers per bark set (0: untextured, flat colours), y: tile size in texels,
                      // z: normal-map strength (0: none), w: symmetric edge colours K
  vec4 far; // x: distance where trees begin to cross-fade into far-field impostors (m), y: where they
            // are impostors only (m); y <= x: no far field, every tree is drawn as pieces; zw: width
            // culling, a piece is dropped when its root rim's width (2 · frame scale) < z * distance + w
};
SYLVA_ASSERT_SIZE(TreeUniforms, 560);

// ---- Wind on the joints (sylva/trees/JointWind.hpp; shaders/trees/wind.comp and frames.comp)
// --------------- Binding 29 (SYLVA_TREE_WIND_BINDING) holds vec4 motion[] per global joint: xy bend θ
// (radians, about the joint's local x and z axes), zw angular velocity ω (rad/s). Binding 30
// (SYLVA_TREE_WIND_REST_BINDING) holds TreeJointRest[] per global joint. The step's uniform block is
// WindUniforms followed by JointWindStepGpu.
#define SYLVA_TREE_WIND_STEP_BINDING 31 // uniform block: WindUniforms, then JointWindStepGpu
#define SYLVA_TREE_WIND_GROUP 64        // invocations per work group of wind.comp and frames.comp
#define SYLVA_TREE_WIND_FIXED 1u        // TreeJointRest.info.w flag: a tree's base joint (never bends)
#define SYLVA_TREE_NO_PARENT 0xffffffffu
#define SYLVA_TREE_MAX_JOINT_CHAIN                                                                           \
  66 // joints from a base to the deepest joint (depth ≤ 64, plus base and self)

/**
 * Rest data of one joint. The joint's frame is parent frame · local · R(pose + θ) · bone scale, with R the
 * bend rotation (bendRotation in C++); a base joint's frame is `local` (the tree's base frame) alone.
 */
struct TreeJointRest {
  JointFrame local; // rimRotation(node rotation) · joint bind (rim units of the piece), or the base frame
  vec4 spring;      // x: k/I (1/s²), y: c/I (1/s), z: bone scale, w: the tree's wind time offset (s)
  vec4 torque;      // angular acceleration per |u|·u (rad/s² per m²/s², u = wind (x, z) in m/s):
               // θ̈.x = x·u.x + y·u.y, θ̈.y = z·u.x + w·u.y (drag, lever, areas and 1/I folded in)
  vec4 probe; // xy: world (x, z) of the subtree's area centroid where the wind is sampled (m);
              // zw: rest bend of the pose (radians)
  uvec4 info; // x: parent joint (global index) or SYLVA_TREE_NO_PARENT; y: tree index; z: chain
              // length from the base (base: 0); w: flags (SYLVA_TREE_WIND_FIXED) in the low 16 bits, the
              // joint's stop in the high 16 (its largest |θ| = maxBend × (w >> 16) / 65535)
};
SYLVA_ASSERT_SIZE(TreeJointRest, 112);

/** The step's constants after the WindUniforms in the uniform block at SYLVA_TREE_WIND_STEP_BINDING. */
struct JointWindStepGpu {
  vec4 step;    // x: time step (s), y: largest bend |θ| (radians), zw: unused
  uvec4 counts; // x: joints; yzw: unused
};
SYLVA_ASSERT_SIZE(JointWindStepGpu, 32);

// ---- Foliage: 2.5D leaf-cloud impostors (sylva/trees/Foliage.hpp, FoliageRenderer.hpp; shaders/trees/
// leafcloud.* bake the cloud texture, foliage.* draw the billboards) ---------------------------------------
// Storage at SYLVA_TREE_FOLIAGE_BINDING holds FoliageAnchorGpu[]; the cloud texture (rgb: lit colour, sRGB-
// encoded at half scale; a: depth code) is at SYLVA_TREE_FOLIAGE_UNIT. Both passes read FoliageUniforms from
// the uniform block binding of TreeUniforms (never bound in one program together; each pass binds its own).
#define SYLVA_TREE_FOLIAGE_UNIFORM_BINDING SYLVA_TREE_BINDING // uniform block FoliageUniforms
#define SYLVA_TREE_LEAF_UNIT 15 // sampler2D: the leaf texture the bake draws (sRGB8_ALPHA8, mipmapped)
// sampler2D: the needle cloud's baked texture, as the leaf cloud's at SYLVA_TREE_FOLIAGE_UNIT (the draw reads
// it for species whose leafColours[s].w is 1); shares a unit with the impostor bake's resolve (never together)
#define SYLVA_TREE_NEEDLE_UNIT 14

/** One foliage billboard, carried by a joint. */
struct FoliageAnchorGpu {
  vec4 place; // xyz: sphere centre in the root joint's frame (rim units); w: sphere radius (m)
  vec4 spin;  // xy: cos, sin of the image's turn in the billboard plane; zw: unused
  uvec4 info; // x: root joint (global index); y: tree index; z: species; w: unused
};
SYLVA_ASSERT_SIZE(FoliageAnchorGpu, 48);

/** Per bake and draw of the foliage passes. */
struct FoliageUniforms {
  mat4 bake;    // cloud units → clip of the orthographic bake (foliageBakeMatrix)
  vec4 forward; // xyz: view direction the texture was baked for (world, unit); w: anchor count
  vec4 right;   // xyz: the texture's +u axis (world, unit); w: colour code scale (rgb = srgb(lit · w))
  vec4 up;      // xyz: the texture's +v axis (world, unit); w: 1 with a leaf texture, 0 without
  vec4 sun;     // xyz: towards the sun (world, unit); w: sun intensity (bake lighting)
  vec4 far;     // xy: far-field range (m, TreeLod::farRange; y <= x: none); z: draw distance (m,
                // TreeLod::drawDistance; 0: none); w: unused
  vec4 leafColours[SYLVA_TREE_MAX_SPECIES]; // rgb: species leaf colour / leaf texture mean (linear; needles:
                                            // the colour itself); w: 1 needles, 0 broad leaves
};
SYLVA_ASSERT_SIZE(FoliageUniforms, 272);

// ---- Far field: octahedral impostors (sylva/trees/gpu/ImpostorRenderer.hpp; shaders/trees/impostor.*)
// --------- Storage at SYLVA_TREE_IMPOSTOR_BINDING holds ImpostorInstanceGpu[] (one per far tree). The atlas
// is two sampler2DArray, one layer per species, views × views cells (hemi-octahedral grid, FarField.hpp):
// colour at SYLVA_TREE_IMPOSTOR_UNIT (SRGB8_ALPHA8: albedo premultiplied by coverage, a coverage) and normal
// + depth at SYLVA_TREE_IMPOSTOR_NORMAL_UNIT (RGBA8, premultiplied by coverage: rgb object-space normal as
// 0.5 + 0.5 n, a depth towards the viewer as 0.5 + 0.5 · offset / bounding radius).
#define SYLVA_TREE_IMPOSTOR_UNIFORM_BINDING 22 // uniform block ImpostorUniforms
#define SYLVA_TREE_IMPOSTOR_NORMAL_UNIT 12     // sampler2DArray: normal + depth atlas
#define SYLVA_TREE_IMPOSTOR_SOURCE_UNIT 13     // bake resolve: a view's colour (13) and depth (14)
#define SYLVA_TREE_IMPOSTOR_RESOLVE_GROUP 8    // bake resolve work group side
#define SYLVA_TREE_IMPOSTOR_FAR_ONLY 1u        // ImpostorInstanceGpu.info.w flag: no pieces, never dissolved
#define SYLVA_TREE_IMPOSTOR_VISIBLE_BINDING 20 // storage: uint[] instances the cull kept (impostor_cull.comp)
#define SYLVA_TREE_IMPOSTOR_COMMAND_BINDING 21 // storage: the indirect draw (4 uints: 4, instances, 0, 0)
#define SYLVA_TREE_IMPOSTOR_CULL_GROUP 64

/** One far tree: x y z base (world, m), w crown height (m); info x tree id (dissolve), y species, z yaw
 * (float bits, radians), w flags. */
struct ImpostorInstanceGpu {
  vec4 placement;
  uvec4 info;
};
SYLVA_ASSERT_SIZE(ImpostorInstanceGpu, 32);

/** Per draw. sphere[s]: species s's bounding sphere, centre relative to the base (xyz) and radius (w), in
 * crown heights (a tree of height h: centre base + yaw(xyz · h), radius w · h). */
struct ImpostorUniforms {
  vec4 atlas; // x: views per side, y: cell pixels, z: alpha threshold, w: 1 to refine by the baked depth
  vec4 far;   // xy: far range (m): impostors dissolve in from x, alone from y; y <= x: far-only trees only
  uvec4 info; // x: instances, y: species, zw: unused
  vec4 sphere[SYLVA_TREE_MAX_SPECIES];
  vec4 frustum[6];   // world-space planes (xyz normal pointing inwards, w offset)
  WindUniforms wind; // the wind at the frame's time; flow.z 0: no sway (ImpostorRenderer::setWind)
  vec4 sway[SYLVA_TREE_MAX_SPECIES]; // per species: x lean per squared wind speed (1/(m/s)²), y largest lean
};
SYLVA_ASSERT_SIZE(ImpostorUniforms, 464);

SYLVA_GPU_END

#endif

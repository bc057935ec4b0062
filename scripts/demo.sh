#!/usr/bin/env bash
# Quick start, command 1: installs what is missing, builds, and renders the demo images headless into out/.
# The scene's still comes first (about 3½ minutes on a fresh 2-core machine, most of it the build), then the
# other stills, then the animations, the scene's fly-over last:
#   out/scene.png         the scene data/scenes/meadow.json: terrain, grass, trees, lake, bodies, sky, shadows
#   out/terrain.png       the procedural demo landscape, shaded (multi-textured, lit, fogged)
#   out/terrain-lod.png   the same view in wireframe with quadtree LOD colours
#   out/jacksboro.png     a real DEM (Jacksboro fault, Tennessee) fetched from a Debian package
#   out/coast.png         a real coastal DEM with bathymetry (British Columbia): sea level, water, 3x relief
#   out/grass.png         a grass field on the demo landscape from eye height, in wind
#   out/trees.png         a forest of trees built from interlocking pieces: photo bark tiles, leaves, wind
#   out/forest-far.png    1,000 trees and 100,000 impostor trees to the horizon
#   out/balls.gif         balls rolling down a slope through the simulated grass
#   out/fold-beach.gif    folding textures: waves swash up a procedural beach and wash back
#   out/fold-cat.gif      folding textures: a real cat photo (scikit-image's chelsea.png) squints
#   out/scene.gif         the scene's 5 s fly-over (120 frames, out/scene-flyover/frame_*.png, resumable)
# Each line it prints says which picture is being made and where the finished ones are.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
scripts/setup-debian.sh
scripts/fetch-sample-data.sh
scripts/build.sh release sylva
sylva=./build/release/bin/sylva
mkdir -p out
# step WHAT: says what comes next and how long the demo has run.
step() {
  echo "demo: $1 ($(( $(date +%s) - start )) s since start)"
}
# The scene (docs/scenes.md): terrain, grass, trees, the folding-textured lake, bodies, sky and shadows together.
step "rendering the scene's still"
"$sylva" render data/scenes/meadow.json --out out/scene.png
step "out/scene.png is ready; now the other stills"
"$sylva" render --out out/terrain.png
"$sylva" render --view lod --wireframe --out out/terrain-lod.png
"$sylva" render --dem data/external/jacksboro_fault_dem.npz --out out/jacksboro.png
"$sylva" render --dem data/external/topobathy.npz --exaggeration 3 --out out/coast.png
"$sylva" render --grass --wind-speed 5 --out out/grass.png
"$sylva" render --trees --trees-radius 40 --trees-spacing 3.5 --view-from top --look-at 1024,192,1024 \
  --camera-pos 1060,195,1060 --out out/trees.png
"$sylva" render --trees --trees-count 1000 --trees-radius 120 --trees-spacing 3.5 --trees-far 60 \
  --trees-far-count 100000 --view-from top --look-at 1024,192,1024 --camera-pos 1060,195,1060 \
  --out out/forest-far.png
step "stills ready in out/; now the animations"
"$sylva" render --grass --physics balls --balls 6 --frames 90 --width 400 --height 225 --gif out/balls.gif \
  --out out/balls.png
"$sylva" fold render data/folding/beach.json --fps 12 --gif out/fold-beach.gif
"$sylva" fold render data/folding/cat.json --fps 12 --gif out/fold-cat.gif
step "now the scene's fly-over (120 frames; an interrupted run resumes where it stopped)"
"$sylva" render data/scenes/meadow.json --camera flyover --frames 0-119 --width 384 --height 216 \
  --out out/scene-flyover --gif out/scene.gif
step "done: every picture is in out/"

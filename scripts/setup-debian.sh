#!/usr/bin/env bash
# Installs exactly the Debian 12 packages Sylva needs to build, test and render. Idempotent and
# non-interactive: packages already present are not touched, and nothing is fetched when all are there.
set -euo pipefail

packages=(
  # toolchain: Ninja schedules the build, mold links it (several times faster than GNU ld on the sanitizer build)
  g++ cmake make ninja-build mold pkg-config
  # engine libraries
  libglm-dev libepoxy-dev libglfw3-dev libimgui-dev libstb-dev nlohmann-json3-dev libcli11-dev libspdlog-dev
  libfmt-dev libpng-dev libopenexr-dev libgdal-dev libzip-dev libgif-dev
  # optical flow from reference videos (folding editor) and grass capture: OpenCV
  libopencv-video-dev libopencv-videoio-dev libopencv-imgproc-dev
  # reference videos in containers (AVI, MP4, WebM, …): FFmpeg's own libraries
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev
  # grass capture: Kinect v1 through libfreenect, and its fakenect replay library and tools
  libfreenect-dev libfreenect-bin
  # grass simulation: rigid bodies and the terrain collider (Bullet); the constraint solver's SIMD lanes (Highway)
  libbullet-dev libhwy-dev
  # trees: artist-made pieces (glTF, OBJ, Collada) through Assimp; exported trees read back by tinygltf and
  # checked by the Khronos gltf-validator (Node; scripts/fetch-node-tools.sh)
  libassimp-dev libtinygltf-dev
  # OpenGL/EGL runtime: glvnd loaders + Mesa (llvmpipe) so headless rendering works without a GPU
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  # tests and benchmarks: GoogleTest, Google Benchmark, reference GLSL compiler, virtual display for window tests
  libgtest-dev libgmock-dev libbenchmark-dev glslang-tools xvfb xauth
  # scene sequences as MP4 (`sylva render SCENE.json --mp4`)
  ffmpeg
  # the folding editor's end-to-end test: real X input and screenshots
  xdotool imagemagick x11-utils
  # web preview parity: headless Chromium (WebGL 2 on SwiftShader)
  chromium fonts-dejavu-core
  # the performance and terrain pages' plots (scripts/plot-performance.sh, scripts/plot-terrain.sh)
  gnuplot-nox jq
  # the render farm's test (`sylva farm`): a real single-node Slurm cluster started by scripts/slurm-local.sh
  slurmctld slurmd slurm-client munge
  # Sylva as a library (docs/library.md): the Debian packages (CPack; dpkg-shlibdeps finds their dependencies)
  # checked by lintian, the manual page from --help (help2man), the API reference (Doxygen)
  dpkg-dev lintian help2man doxygen
  # the sanitizer build and fuzzing: clang with libFuzzer and its sanitizer runtimes (the `asan` preset)
  clang libclang-rt-14-dev
)

# Node.js with npm for the glTF validator and the npm sample data: Debian's nodejs + npm, unless a Node.js that
# brings its own npm (e.g. NodeSource's nodejs, which conflicts with Debian's npm package) is already there.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup-debian: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup-debian: run as root (missing: ${missing[*]})" >&2; exit 1; }
  sudo="sudo"
fi
echo "setup-debian: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"

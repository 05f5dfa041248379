#!/usr/bin/env bash
# Installs every Debian package Tellus needs to build, test and run, skipping what is present.
# Safe to run repeatedly; needs root (or sudo). Quiet unless something must be installed.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libgdal-dev gdal-bin                     # DEM reading/writing
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev libglfw3-dev  # OpenGL
  xvfb xauth                               # windowed-context tests
  libglm-dev libtbb-dev                    # maths, parallel loops
  libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libstb-dev
  libimgui-dev                             # the viewer's panel (with GLFW + OpenGL 3 backends)
  libgtest-dev libgmock-dev libbenchmark-dev
  libzstd-dev libxxhash-dev liblerc-dev    # tile codecs and checksums
  libnanoflann-dev                         # k-d tree of the fractal encoder's domain search
  libabsl-dev                              # flat hash maps (per-frame LOD bookkeeping)
  libmeshoptimizer-dev                     # BDAM's patch simplifier
  clang libclang-rt-14-dev                 # libFuzzer targets
  python3-matplotlib                       # benchmark plots
  libtinygltf-dev                          # glTF export
  libcurl4-openssl-dev                     # HTTP client
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev ffmpeg  # video (H.264 / VP9), ffprobe in the tests
  dpkg-dev                                 # Debian packaging (dpkg-deb, dpkg-shlibdeps)
  libopenmpi-dev openmpi-bin               # mpirun -np N tellus build --global
  strace                                   # hostile tests: a SIGKILL injected at one system call
  nodejs chromium lighttpd                 # scripts/cesium-check: CesiumJS in headless Chromium, served on 127.0.0.1
)
# npm: a separate Debian package, but NodeSource's nodejs provides (and conflicts with) it.
command -v npm >/dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"

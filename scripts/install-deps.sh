#!/usr/bin/env bash
# Installs the Debian 12 packages giantbubble builds and tests with. Idempotent: a package already
# present is left alone, so running this before every build costs one `dpkg -s` per package.
set -euo pipefail

packages=(
  build-essential cmake pkg-config   # toolchain
  clang-format-14                    # the format check (scripts/check-format.sh, a test)
  libeigen3-dev                      # small fixed-size linear algebra
  libcgal-dev libgmp-dev libmpfr-dev # constrained Delaunay triangulation of the film
  libgtest-dev libgmock-dev          # tests
  libbenchmark-dev                   # bench/
  libomp-dev                         # OpenMP runtime (g++ uses libgomp; kept for clang builds)
  libcli11-dev                       # command line of the giantbubble executable
  nlohmann-json3-dev                 # JSON outputs (bench results)
  libpng-dev zlib1g-dev              # thickness images of a run; the show-proof test writes PNG CRCs
  libvulkan-dev glslang-tools        # Vulkan compute backend; shaders compiled to SPIR-V at build time
  mesa-vulkan-drivers                # lavapipe: the software Vulkan device the tests and CI run on
  vulkan-validationlayers            # the tests run with the Khronos validation layer
  libfreenect-dev libfreenect-bin    # Kinect v1 depth capture; fakenect plays recordings back
  libarchive-dev                     # recordings packed as .tar.gz (giantbubble evaluate, gb_hands_bench)
  libglfw3-dev xvfb xauth            # live window; the window test runs under Xvfb
  x11-utils                          # xwininfo: the full-screen test checks that the window covers the screen
  ffmpeg                             # MP4 output of rendered frames (optional at run time)
  libtomlplusplus-dev                # scene files
  liblo-dev liblo-tools              # OSC events for show control; oscdump in tests
  libwebsocketpp-dev libboost-dev    # live --control: the OSCQuery server's HTTP and WebSocket (Boost.Asio)
  chromium python3-websocket curl    # the control page's test in headless Chromium (a DevTools driver); curl
)

missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}; run this script as root (or install them with apt-get)" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"

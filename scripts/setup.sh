#!/usr/bin/env bash
# The whole set-up on a fresh Debian 12 machine (as root, or with sudo):
#   bash scripts/setup.sh demo   installs what is missing, builds (Release), renders demo.mp4
#   bash scripts/setup.sh test   installs what is missing, builds, runs the whole test suite
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-demo}

packages=(
  build-essential cmake ninja-build pkg-config git
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev
  libavformat-dev libavcodec-dev libavfilter-dev libswscale-dev libavutil-dev ffmpeg fonts-dejavu-core
  libxxhash-dev xxhash nlohmann-json3-dev libtinygltf-dev libgtest-dev libbenchmark-dev
  gnuplot-nox libopenmpi-dev openmpi-bin
  libhdf5-dev python3-h5py  # --hdf5 (docs/transient-outputs.md) and its read-back test
  pybind11-dev python3-dev python3-numpy  # the Python module (docs/python.md)
)
# Blender runs only the Blender add-on's tests (tests/blender/, registered when `blender` is on
# PATH; xvfb-run gives the one that runs Blender's interface a virtual display); the demo needs
# neither.
if [[ $what == test ]]; then packages+=(blender xvfb xauth); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=(); [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"

case "$what" in
  demo) ./build/slowlight render -o demo.mp4 && echo "setup: wrote demo.mp4" >&2 ;;
  # Each test runs once: a retried test would hide a flaky one.
  test) ctest --test-dir build --output-on-failure -j"$(nproc)" ;;
  build) ;;
  *) echo "usage: bash scripts/setup.sh demo|test|build" >&2; exit 2 ;;
esac

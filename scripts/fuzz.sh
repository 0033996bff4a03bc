#!/usr/bin/env bash
# Fuzzes the readers of untrusted files with libFuzzer under AddressSanitizer and
# UndefinedBehaviorSanitizer, each for a bounded time (default 60 s per target):
#   bash scripts/fuzz.sh [SECONDS]
# Targets (fuzz/fuzz_NAME.cpp): scene (scene JSON and the command line), obj (OBJ meshes),
# resume_exr (EXR frames read back by --resume). Seeds are in build-fuzz/corpus/NAME/,
# findings in build-fuzz/findings/. A new target: its file, a line in CMakeLists.txt, and its
# name (with its seeds) below.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
need=(clang-14 libclang-rt-14-dev)
missing=()
for p in "${need[@]}"; do dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p"); done
if ((${#missing[@]})); then
  sudo_cmd=(); [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
targets=(scene obj resume_exr)
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
      -DSLOWLIGHT_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build build-fuzz --target "${targets[@]/#/fuzz_}"
mkdir -p build-fuzz/findings
for t in "${targets[@]}"; do mkdir -p "build-fuzz/corpus/$t"; done
cp samples/*.json build-fuzz/corpus/scene/
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\nf 1 2 3 4\n' > build-fuzz/corpus/obj/tri.obj
printf 'o q\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nusemtl m\nf -4 -3 -2 -1\n' > build-fuzz/corpus/obj/quad.obj
export FUZZ_SEED_DIR=build-fuzz/corpus/resume_exr  # fuzz_resume_exr writes a valid frame there
for t in "${targets[@]}"; do
  echo "fuzz: $t for $seconds s" >&2
  "./build-fuzz/fuzz_$t" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix=build-fuzz/findings/ -print_final_stats=1 "build-fuzz/corpus/$t" 2>&1 | tail -n 12
done

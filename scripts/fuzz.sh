#!/usr/bin/env bash
# Fuzzes the scene parser and validator, and the command-line parser, with libFuzzer under
# AddressSanitizer and UndefinedBehaviorSanitizer, for a bounded time (default 60 s):
#   bash scripts/fuzz.sh [SECONDS]
# The seed corpus is samples/*.json; findings are written to build-fuzz/findings/.
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
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
      -DSLOWLIGHT_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build build-fuzz --target fuzz_scene
mkdir -p build-fuzz/corpus build-fuzz/findings
cp samples/*.json build-fuzz/corpus/
./build-fuzz/fuzz_scene -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix=build-fuzz/findings/ -print_final_stats=1 build-fuzz/corpus 2>&1 | tail -n 12

#!/usr/bin/env bash
# Builds the program and the pipeline tests with ThreadSanitizer (in build-tsan/) and runs
# them: the flow graph's stages run on oneTBB worker threads, and anything two stages touch at
# once must be reported here.      bash scripts/tsan.sh [GTEST_FILTER]
# Suppressions (scripts/tsan.supp) cover only what happens inside oneTBB's own library, which
# Debian builds without instrumentation; see that file for why each is there.
set -euo pipefail
cd "$(dirname "$0")/.."
filter=${1:-*}
start=$(date +%s)
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSLOWLIGHT_TSAN=ON >/dev/null
cmake --build build-tsan --target slowlight test_pipeline
export TSAN_OPTIONS="suppressions=$PWD/scripts/tsan.supp halt_on_error=1 second_deadlock_stack=1 history_size=4"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# K >= 2 sections with every writer on: the assemble and write stages overlap across sections.
./build-tsan/slowlight render samples/cornell_box.json --width 32 --height 32 --passes 2 --photons 3000 \
    --frames 6 --sections 3 -o "$out/v.mkv" --png-dir "$out/png" --exr-dir "$out/exr" --cube "$out/c.npy" \
    --stats "$out/s.json" --no-progress
./build-tsan/slowlight render samples/cornell_box.json --width 32 --height 32 --passes 2 --photons 3000 \
    --frames 6 --sections 3 --emission pulse --png-dir "$out/png2" --no-progress
# The pipeline tests run the in-process pipeline (and the TSan-built program) many times.
./build-tsan/test_pipeline --gtest_brief=1 --gtest_filter="$filter"
echo "tsan: no data race reported ($(( $(date +%s) - start )) s)" >&2

#!/usr/bin/env bash
# Builds the program and the pipeline tests with ThreadSanitizer (in build-tsan/) and runs a
# render with every writer on and K = 3 sections, then the pipeline tests, printing a summary of
# what TSan reports:      bash scripts/tsan.sh [GTEST_FILTER]
#
# What it can show: Debian's oneTBB (libtbb.so.12) is not built with -fsanitize=thread. Its
# scheduler hands tasks between threads with atomics compiled into that library, which TSan
# cannot see, so every hand-over (a task's own fields, and the data a task was given) looks
# unsynchronised: a render reports 150-200 "races", nearly all of them inside oneTBB's header
# templates (partitioner, task objects, spin mutexes) or on data a parallel_for or a flow-graph
# node received. Those are suppressed only where the racing frame itself is oneTBB code
# (scripts/tsan.supp); the rest are listed by source line, to be read, not trusted. A clean
# verdict needs oneTBB built from source with -fsanitize=thread (not done here: it is not
# packaged). The script therefore does not fail on reports and is not part of CI.
set -euo pipefail
cd "$(dirname "$0")/.."
# Left out by default: tests that measure peak memory (TSan's shadow memory changes it) and the
# render of every sample (slow under TSan).
filter=${1:--MaxMemory.PeakRss*:Sections.FourSectionsNeedAThirdOfTheMemoryOfOne:RenderSamples.*}
start=$(date +%s)
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSLOWLIGHT_TSAN=ON >/dev/null
cmake --build build-tsan --target slowlight test_pipeline
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export TSAN_OPTIONS="suppressions=$PWD/scripts/tsan.supp halt_on_error=0 exitcode=0 history_size=4 log_path=$out/tsan"
# K >= 2 sections with every writer on: the assemble and write stages overlap across sections.
./build-tsan/slowlight render samples/cornell_box.json --width 32 --height 32 --passes 2 --photons 3000 \
    --frames 6 --sections 3 -o "$out/v.mkv" --png-dir "$out/png" --exr-dir "$out/exr" --cube "$out/c.npy" \
    --stats "$out/s.json" --no-progress
./build-tsan/slowlight render samples/cornell_box.json --width 32 --height 32 --passes 2 --photons 3000 \
    --frames 6 --sections 3 --emission pulse --png-dir "$out/png2" --no-progress
./build-tsan/test_pipeline --gtest_brief=1 --gtest_filter="$filter"
reports=$(cat "$out"/tsan.* 2>/dev/null | grep -c "WARNING: ThreadSanitizer" || true)
echo "tsan: $reports report(s) after suppressions; racing frames in slowlight's own sources:" >&2
cat "$out"/tsan.* 2>/dev/null | grep -A1 -E "^  (Read|Write|Atomic|Previous)" | grep -oE "/(config|core|stages|pipeline)/[a-z_/]+\.(cpp|h):[0-9]+" \
    | sort | uniq -c | sort -rn | head -n 30 >&2 || true
echo "tsan: done in $(( $(date +%s) - start )) s" >&2

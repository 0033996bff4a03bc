#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer and runs the unit tests and a small
# render under them (the end-to-end suites, which run the program many times, are left to the
# normal build):   bash scripts/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSLOWLIGHT_SANITIZE=ON >/dev/null
cmake --build build-asan --target slowlight test_config test_output test_render
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
for t in test_config test_output test_render; do
  echo "sanitize: $t" >&2
  ./build-asan/$t --gtest_brief=1
done
out=$(mktemp -d)
./build-asan/slowlight render samples/cornell_box.json --width 48 --height 48 --passes 3 --photons 5000 \
    --frames 6 --sections 2 -o "$out/v.mp4" --exr-dir "$out/exr" --cube "$out/c.npy" --no-progress
./build-asan/slowlight retime "$out/c.npy" --emission pulse -o "$out/p.mkv"
# Imported OBJ/MTL: the strict reader, per-triangle materials, smooth normals, emissive triangles.
./build-asan/slowlight render samples/cornell_box_obj.json --width 32 --height 32 --passes 2 --photons 5000 \
    --frames 4 -o "$out/obj.mp4" --no-progress
rm -rf "$out"
echo "sanitize: unit tests and a small render passed under ASan+UBSan" >&2

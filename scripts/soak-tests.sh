#!/usr/bin/env bash
# Is the suite flaky? Two copies of the whole test suite (each test once, as `setup.sh test`
# runs it) loop side by side, so that every run has a second copy beside it for load, until N
# runs have finished between them; the first failing run stops both.
# Usage: bash scripts/soak-tests.sh [N=30] [LOG=soak.log]   (after a build)
set -uo pipefail
cd "$(dirname "$0")/.."
n=${1:-30}
log=${2:-soak.log}
[[ -x build/slowlight ]] || { echo "soak: build first (bash scripts/setup.sh build)" >&2; exit 2; }
count=$log.count   # one line per finished run: "<copy> <run> passed|FAILED <seconds>"
: >"$log"
: >"$count"

# Each copy keeps its ctest logs apart (the tests themselves work in fresh temporary folders).
for name in A B; do mkdir -p "build/soak-$name" && cp build/CTestTestfile.cmake "build/soak-$name/"; done

copy() {  # copy NAME: runs the suite until N runs are counted or one fails
  local name=$1 i=0 start out
  while (($(grep -c . "$count") < n)) && ! grep -q FAILED "$count"; do
    i=$((i + 1))
    start=$(date +%s)
    out=$log.$name.$i
    if ctest --test-dir "build/soak-$name" -j"$(nproc)" --output-on-failure >"$out" 2>&1; then
      echo "$name $i passed $(( $(date +%s) - start ))" >>"$count"
      rm -f "$out"
    else
      echo "$name $i FAILED $(( $(date +%s) - start ))" >>"$count"
    fi
  done
}
copy A &
a=$!
copy B &
b=$!
wait $a $b

passed=$(grep -c passed "$count")
{
  echo "soak: $(grep -c . "$count") runs of the suite, two at a time ($(nproc) cores), $passed passed:"
  cat "$count"
  for f in "$log".[AB].*; do [[ -e $f ]] && { echo "--- $f"; grep -E "Failed|\*\*\*|Failure|tests passed" "$f"; }; done
} | tee "$log"
[[ $passed -ge $n ]] && ! grep -q FAILED "$count"

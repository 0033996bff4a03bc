#!/usr/bin/env bash
# Runs one add-on test in a fresh factory-startup Blender, headless, with its own empty user
# folders (the add-on is installed there from the zip the build made, then removed with them).
#   run_blender_test.sh BLENDER TEST.py ADDON.zip SLOWLIGHT     (BLENDER_UI=1: with the interface)
set -euo pipefail
blender=$1 test=$2 zip=$3 program=$4
home=$(mktemp -d "${TMPDIR:-/tmp}/slowlight_blender_test.XXXXXX")
trap 'rm -rf "$home"' EXIT
export BLENDER_USER_SCRIPTS=$home/scripts BLENDER_USER_CONFIG=$home/config
export SLOWLIGHT_TEST_WORK=$home/work
mkdir -p "$BLENDER_USER_SCRIPTS" "$BLENDER_USER_CONFIG" "$SLOWLIGHT_TEST_WORK"
if [[ ${BLENDER_UI:-} ]]; then  # the interface, in a virtual display
  nice -n 15 timeout "${BLENDER_UI_TIMEOUT:-600}" xvfb-run -a -s "-screen 0 1280x800x24" \
    "$blender" --factory-startup --python-exit-code 1 -P "$test" -- "$zip" "$program"
else
  nice -n 15 "$blender" -b --factory-startup --python-exit-code 1 -P "$test" -- "$zip" "$program"
fi

#!/usr/bin/env bash
# Fuzzes the readers of untrusted files with libFuzzer under AddressSanitizer and
# UndefinedBehaviorSanitizer, each for a bounded time (default 60 s per target):
#   bash scripts/fuzz.sh [SECONDS]
# Dictionaries (fuzz/dict/NAME.dict) give the fuzzer the keys and numbers that reach the checks.
# Targets (fuzz/fuzz_NAME.cpp): scene (scene JSON and the command line), obj (OBJ meshes and
# .mtl), gltf (binary glTF), resume_exr (EXR frames read back by --resume). Seeds are in build-fuzz/corpus/NAME/,
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
targets=(scene obj gltf resume_exr)
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
      -DSLOWLIGHT_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build build-fuzz --target "${targets[@]/#/fuzz_}"
mkdir -p build-fuzz/findings
for t in "${targets[@]}"; do mkdir -p "build-fuzz/corpus/$t"; done
cp samples/*.json build-fuzz/corpus/scene/
# Inputs that once crashed a target (fuzz/regressions/), replayed as seeds of their target.
cp fuzz/regressions/*.glb build-fuzz/corpus/gltf/
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\nf 1 2 3 4\n' > build-fuzz/corpus/obj/tri.obj
printf 'o q\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nusemtl m\nf -4 -3 -2 -1\n' > build-fuzz/corpus/obj/quad.obj
# A glTF seed: the Cornell box of the import tests is made by a test; here, the smallest valid
# .glb (one triangle) written by python3's standard library.
python3 - build-fuzz/corpus/gltf/tri.glb <<'PY'
import json, struct, sys
pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
idx = struct.pack("<3H", 0, 1, 2) + b"\0\0"
gl = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}, "emissiveFactor": [1, 1, 1]}],
      "buffers": [{"byteLength": len(pos) + len(idx)}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                      {"buffer": 0, "byteOffset": len(pos), "byteLength": 6}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}
js = json.dumps(gl).encode()
js += b" " * (-len(js) % 4)
binary = pos + idx
out = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(binary))
out += struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(binary), 0x004E4942) + binary
open(sys.argv[1], "wb").write(out)
PY
# Seeds that reach mtllib (several names, several lines) and the glTF reader's node and camera checks.
printf 'mtllib a.mtl b.mtl\nmtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n' > build-fuzz/corpus/obj/mtllib.obj
python3 - build-fuzz/corpus/gltf/nodes.glb build-fuzz/corpus/gltf/tri.glb <<'PY'
import json, struct, sys
data = open(sys.argv[2], "rb").read()
n = struct.unpack_from("<I", data, 12)[0]
gl = json.loads(data[20:20 + n])
gl["scenes"] = [{"nodes": [0, 1, 2]}]
gl["nodes"] = [{"mesh": 0, "rotation": [0, 0, 0.7071, 0.7071], "children": [3]},
               {"camera": 0, "translation": [0, 0, 3]},
               {"extensions": {"KHR_lights_punctual": {"light": 0}}, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1]},
               {"mesh": 0, "scale": [2, 2, 2]}]
gl["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1, "aspectRatio": 1.5}}]
gl["extensionsUsed"] = ["KHR_lights_punctual"]
gl["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 10,
                    "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}}]}}
gl["bufferViews"][0]["byteStride"] = 12
js = json.dumps(gl).encode()
js += b" " * (-len(js) % 4)
binary = data[20 + n + 8:]
out = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(binary))
out += struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(binary), 0x004E4942) + binary
open(sys.argv[1], "wb").write(out)
PY
export FUZZ_SEED_DIR=build-fuzz/corpus/resume_exr  # fuzz_resume_exr writes a valid frame there
for t in "${targets[@]}"; do
  echo "fuzz: $t for $seconds s" >&2
  dict=(); [[ -f fuzz/dict/$t.dict ]] && dict=(-dict="fuzz/dict/$t.dict")
  "./build-fuzz/fuzz_$t" "${dict[@]}" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix=build-fuzz/findings/ -print_final_stats=1 "build-fuzz/corpus/$t" 2>&1 | tail -n 12
done

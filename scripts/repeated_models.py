#!/usr/bin/env python3
"""Writes the model files that measure repeated geometry (docs/bad-inputs.md, "memory blow-ups"):

  copies  DIR --copies 2000 --grid 100   a .gltf of one grid mesh (2 x grid^2 triangles) placed by
                                         N nodes, lit by a point lamp; plus DIR/copies_scene.json,
                                         the same grid as a .obj placed N times by a scene file
  corners FILE --faces 7000000           an OBJ of one triangle written N times ("f 1 2 3"): every
                                         face repeats the same corners; plus FILE_scene.json, lit

Generated, never checked in: the files are large and their only content is their size.
"""
import argparse
import base64
import json
import math
import os
import struct


def grid_mesh(n):
    """A unit square in x-z, n x n quads, facing +y, with normals."""
    pos, nor, idx = [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            pos += [i / n - 0.5, 0.02 * math.sin(7 * i / n) * math.cos(5 * j / n), j / n - 0.5]
            nor += [0.0, 1.0, 0.0]
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            idx += [a, d, c, a, c, b]  # counter-clockwise seen from +y
    return pos, nor, idx


def write_copies(folder, copies, grid):
    os.makedirs(folder, exist_ok=True)
    pos, nor, idx = grid_mesh(grid)
    nv = len(pos) // 3
    blob = struct.pack(f"<{len(pos)}f", *pos) + struct.pack(f"<{len(nor)}f", *nor) + struct.pack(f"<{len(idx)}I", *idx)
    side = math.ceil(math.sqrt(copies))
    nodes = [{"mesh": 0, "translation": [1.2 * (k % side), 0.0, 1.2 * (k // side)]} for k in range(copies)]
    mid = 1.2 * (side - 1) / 2
    nodes.append({"translation": [mid, 3.0, mid],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    gltf = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": list(range(copies + 1))}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
                                                "roughnessFactor": 1}}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 5000.0}]}},
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * nv},
                        {"buffer": 0, "byteOffset": 12 * nv, "byteLength": 12 * nv},
                        {"buffer": 0, "byteOffset": 24 * nv, "byteLength": 4 * len(idx)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3",
                       "min": [-0.5, -0.02, -0.5], "max": [0.5, 0.02, 0.5]},
                      {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}],
    }
    with open(os.path.join(folder, "copies.gltf"), "w") as f:
        json.dump(gltf, f)
    with open(os.path.join(folder, "grid.obj"), "w") as f:
        for k in range(nv):
            f.write("v %g %g %g\nvn 0 1 0\n" % tuple(pos[3 * k:3 * k + 3]))
        for t in range(len(idx) // 3):
            a, b, c = (i + 1 for i in idx[3 * t:3 * t + 3])
            f.write(f"f {a}//{a} {b}//{b} {c}//{c}\n")
    shapes = [{"type": "mesh", "file": "grid.obj", "material": "grey",
               "translate": [1.2 * (k % side), 0, 1.2 * (k // side)]} for k in range(copies)]
    scene = {"camera": {"position": [mid, 8, mid + 12], "look_at": [mid, 0, mid], "vfov_deg": 50,
                        "width": 64, "height": 48},
             "time": {"start_ns": 0, "end_ns": 60, "frames": 4},
             "materials": {"grey": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}},
             "shapes": shapes,
             "lights": [{"type": "point", "position": [mid, 3, mid], "power": [500, 500, 500]}]}
    with open(os.path.join(folder, "copies_scene.json"), "w") as f:
        json.dump(scene, f, indent=1)


def write_corners(path, faces):
    with open(path, "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
        chunk = "f 1 2 3\n" * 100000
        for _ in range(faces // 100000):
            f.write(chunk)
        f.write("f 1 2 3\n" * (faces % 100000))
    scene = {"camera": {"position": [0.3, 0.3, 2], "look_at": [0.3, 0.3, 0], "width": 64, "height": 48},
             "time": {"start_ns": 0, "end_ns": 20, "frames": 2},
             "materials": {"grey": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}},
             "shapes": [{"type": "mesh", "file": os.path.basename(path), "material": "grey"}],
             "lights": [{"type": "point", "position": [0.3, 0.3, 1], "power": [10, 10, 10]}]}
    with open(os.path.splitext(path)[0] + "_scene.json", "w") as f:
        json.dump(scene, f, indent=1)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="what", required=True)
    c = sub.add_parser("copies")
    c.add_argument("folder")
    c.add_argument("--copies", type=int, default=2000)
    c.add_argument("--grid", type=int, default=100, help="quads per side: 2 x grid^2 triangles")
    o = sub.add_parser("corners")
    o.add_argument("file")
    o.add_argument("--faces", type=int, default=7000000)
    a = p.parse_args()
    if a.what == "copies":
        write_copies(a.folder, a.copies, a.grid)
    else:
        write_corners(a.file, a.faces)


if __name__ == "__main__":
    main()

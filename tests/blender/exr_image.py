# Reads a linear EXR (slowlight's or Cycles') through Blender into rows of (R+G+B)/3 per pixel,
# rows from the top; also the RGB of one pixel. Used by the add-on's tests.
import bpy


def load(path):
    img = bpy.data.images.load(path, check_existing=False)
    w, h = img.size
    c = img.channels
    px = list(img.pixels[:])  # rows bottom-up
    bpy.data.images.remove(img)
    rows = []
    for y in range(h):
        base = (h - 1 - y) * w * c
        rows.append([(px[base + x * c] + px[base + x * c + 1] + px[base + x * c + 2]) / 3 for x in range(w)])
    return rows


def mean(rows, rect=None):
    h, w = len(rows), len(rows[0])
    x0, x1, y0, y1 = rect or (0, w, 0, h)
    vals = [rows[y][x] for y in range(y0, y1) for x in range(x0, x1)]
    return sum(vals) / len(vals)

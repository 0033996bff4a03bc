# Compares slowlight's steady image with Cycles' in named regions, in absolute units (both are
# linear radiance in W sr^-1 m^-2). Runs in Blender's Python (which reads EXR):
#
#   blender -b --factory-startup -P bench/blender/compare.py -- REGIONS.json SLOWLIGHT.exr CYCLES.exr [CYCLES2.exr]
#
# Prints, per region, the mean of (R+G+B)/3 in each image and slowlight / Cycles; with a second
# Cycles image (another seed), also Cycles' own seed-to-seed ratio, the noise floor of the
# comparison.
import json
import sys

import bpy


def load(path):
    img = bpy.data.images.load(path)
    w, h = img.size
    px = list(img.pixels[:])  # RGBA floats, rows bottom-up
    grey = [[0.0] * w for _ in range(h)]
    for y in range(h):
        row = (h - 1 - y) * w * 4  # rows from the top, as the regions count them
        for x in range(w):
            i = row + x * 4
            grey[y][x] = (px[i] + px[i + 1] + px[i + 2]) / 3
    return w, h, grey


def mean(img, rect):
    x0, x1, y0, y1 = rect
    vals = [img[y][x] for y in range(y0, y1) for x in range(x0, x1)]
    return sum(vals) / len(vals)


argv = sys.argv[sys.argv.index("--") + 1:]
regions = json.load(open(argv[0]))["regions"]
images = [load(p) for p in argv[1:]]
for w, h, _ in images[1:]:
    if (w, h) != images[0][:2]:
        sys.exit("error: the images differ in size")
print("%-18s %12s %12s %10s%s" % ("region", "slowlight", "cycles", "sl/cycles", "  cycles seed/seed" if len(images) > 2 else ""))
for name, rect in regions.items():
    s, c = mean(images[0][2], rect), mean(images[1][2], rect)
    line = "%-18s %12.6f %12.6f %10.4f" % (name, s, c, s / c if c else float("nan"))
    if len(images) > 2:
        c2 = mean(images[2][2], rect)
        line += "  %10.4f" % (c2 / c if c else float("nan"))
        # Against the mean of both seeds as well: the better reference.
        line += "  sl/(mean of seeds) %.4f" % (s / ((c + c2) / 2))
    print(line)

"""One render through the Python module, for bench/python/run.sh: `render` (every frame in one
array) or `frames` (the streaming loop, each frame looked at and dropped), with the command
line's flags as keyword arguments. Prints the frames' total light, so the work cannot be skipped."""
import sys

import numpy as np

import slowlight


def main():
    mode, scene, *flags = sys.argv[1:]
    options = {}
    for name, value in zip(flags[::2], flags[1::2]):
        options[name.lstrip("-").replace("-", "_")] = value
    total = 0.0
    if mode == "render":
        r = slowlight.render(scene, **options)
        total = float(r.frames.sum(dtype=np.float64))
    else:
        for frame in slowlight.frames(scene, **options):
            total += float(frame.image.sum(dtype=np.float64))
    print(f"{mode}: light {total:.6g}")


if __name__ == "__main__":
    main()

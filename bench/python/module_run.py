"""One render through the Python module, for bench/python/run.sh: `render` (every frame in one
array) or `frames` (the streaming loop, each frame looked at and dropped), with the command
line's flags as keyword arguments. The loop reads one value of each frame and keeps nothing:
what is measured is what the module adds, not what a user then computes."""
import sys

import numpy as np

import slowlight


def main():
    mode, scene, *flags = sys.argv[1:]
    options = {}
    for name, value in zip(flags[::2], flags[1::2]):
        options[name.lstrip("-").replace("-", "_")] = value
    seen = 0.0
    if mode == "render":
        r = slowlight.render(scene, **options)
        seen = float(r.frames[:, -1, -1, 0].sum(dtype=np.float64))
    else:
        for frame in slowlight.frames(scene, **options):
            seen += float(frame.image[-1, -1, 0])
    print(f"{mode}: {seen:.6g}")


if __name__ == "__main__":
    main()

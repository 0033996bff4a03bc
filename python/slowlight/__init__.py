"""slowlight from Python: time-resolved renders straight into NumPy arrays.

    import slowlight
    r = slowlight.render("samples/cornell_box.json", frames=24, passes=8, width=128)
    r.frames        # float32 (frames, height, width, 3), linear radiance, row 0 at the top
    for frame in slowlight.frames("scene.json", sections=4):   # each frame as its section finishes
        ...

The scene and the options are read and checked by the command line's own code: a keyword
argument is the `slowlight render` flag of the same name (max_memory= is --max-memory), and
bad input raises ValueError with the text of the command line's `error:` line. docs/python.md
says more.
"""
import json as _json
import os as _os
import warnings as _warnings

import numpy as _np

from . import _slowlight

__all__ = ["render", "frames", "info", "Result", "Frame", "FrameStream", "SlowlightWarning",
           "SPEED_OF_LIGHT_M_PER_NS", "__version__"]

__version__ = _slowlight.VERSION
SPEED_OF_LIGHT_M_PER_NS = _slowlight.SPEED_OF_LIGHT_M_PER_NS  # optical path length (m) per ns


class SlowlightWarning(UserWarning):
    """What the command line prints as a `warning:` line (the scene is valid but suspicious)."""


# keyword -> (flag, kind): "value" flags take str(value); "switch" flags are given when True;
# camera_tof chooses between --camera-tof and --no-camera-tof.
_OPTIONS = {
    "frames": "--frames", "passes": "--passes", "photons": "--photons", "width": "--width",
    "height": "--height", "seed": "--seed", "emission": "--emission", "sections": "--sections",
    "max_memory": "--max-memory", "max_bucket_memory": "--max-bucket-memory", "threads": "--threads",
    "max_depth": "--max-depth", "strategy": "--strategy", "exposure": "--exposure",
    "exposure_percentile": "--exposure-percentile", "gltf_light_units": "--gltf-light-units",
    "gltf_principled": "--gltf-principled",
}
_SWITCHES = {"exposure_follow": "--exposure-follow"}


def _nearest(name, names):
    import difflib
    close = difflib.get_close_matches(name, names, n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


def _command_line(scene, options, call):
    """The flags `slowlight render` would get, and the scene as JSON text when it is a dict."""
    args, text = [], None
    if isinstance(scene, dict):
        text = _json.dumps(scene)
    elif scene is not None:
        args.append(_os.fspath(scene))
    for key, value in options.items():
        if value is None:
            continue
        if key in _OPTIONS:
            args += [_OPTIONS[key], str(value)]
        elif key in _SWITCHES:
            if value:
                args.append(_SWITCHES[key])
        elif key == "camera_tof":
            args.append("--camera-tof" if value else "--no-camera-tof")
        else:
            known = sorted(set(_OPTIONS) | set(_SWITCHES) | {"camera_tof"})
            raise TypeError(f"{call}() got an unexpected keyword argument '{key}'{_nearest(key, known)}")
    return args, text


def _warn(lines, seen):
    for line in lines:
        if line not in seen:
            seen.add(line)
            _warnings.warn(line.removeprefix("warning: "), SlowlightWarning, stacklevel=4)


class Frame:
    """One time-resolved frame: `image` float32 (height, width, 3), covering arrival times
    [start_ns, end_ns), i.e. optical path lengths [start_m, end_m). np.asarray(frame) is the image."""
    __slots__ = ("index", "image", "start_ns", "end_ns", "start_m", "end_m")

    def __init__(self, index, image, start_ns, end_ns):
        self.index, self.image = index, image
        self.start_ns, self.end_ns = start_ns, end_ns
        self.start_m = start_ns * SPEED_OF_LIGHT_M_PER_NS
        self.end_m = end_ns * SPEED_OF_LIGHT_M_PER_NS

    def __array__(self, dtype=None):
        return self.image if dtype is None else self.image.astype(dtype)

    def __repr__(self):
        return f"Frame({self.index}, {self.start_ns:g}..{self.end_ns:g} ns)"


class Result:
    """What render() returns.

    frames      float32 (frames, height, width, 3): linear radiance, row 0 at the top (the EXRs' pixels)
    steady      float32 (height, width, 3): the image once the light has filled the scene (None if
                the render was interrupted before its last section)
    edges_ns    float64 (frames + 1,): frame k covers arrival times [edges_ns[k], edges_ns[k+1])
    edges_m     the same edges as optical path length in metres (c * t)
    exposure    the video's exposure (the multiplier the command line's video and PNGs use)
    per_frame_exposure  with exposure_follow=True, each frame's; else empty
    stats       the --stats file's numbers (times, photons, passes, peak memory, ...)
    warnings    the warning lines of the run (also issued through the warnings module)
    interrupted True when Ctrl-C stopped it: `frames` holds the frames written (as the command line
                keeps them: the finished sections and the section in progress)
    """

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def keys(self):
        return list(self.__dict__)

    def __getitem__(self, key):
        return self.__dict__[key]

    def __repr__(self):
        f = self.frames
        return f"Result(frames={f.shape}, exposure={self.exposure}, interrupted={self.interrupted})"


def _result(r, frames, warnings):
    edges = _np.asarray(r.edges_ns, dtype=_np.float64)
    return Result(frames=frames, steady=r.steady, edges_ns=edges, edges_m=edges * SPEED_OF_LIGHT_M_PER_NS,
                  exposure=r.exposure, per_frame_exposure=list(r.per_frame_exposure),
                  stats=_json.loads(r.stats_json()), warnings=list(r.warnings), interrupted=r.interrupted)


def _open(scene, options, call, base_dir):
    args, text = _command_line(scene, options, call)
    r = _slowlight.Render(args, text, _os.fspath(base_dir) if base_dir is not None else "")
    seen = set()
    _warn(r.warnings, seen)
    return r, seen


def _events(r, progress):
    """The render's events until it ends, calling `progress` as they come (the GIL is free
    while waiting; Python's Ctrl-C lands here within a tenth of a second)."""
    while True:
        event = r.next_event(0.1)
        if event is None:
            continue
        if event[0] == "progress":
            if progress is not None:
                progress(event[1], event[2], r.sections, r.passes)
            continue
        yield event
        if event[0] == "done":
            return


def render(scene=None, *, progress=None, base_dir=None, **options):
    """Render `scene` (a scene file, a .gltf/.glb/.obj model, a dict of the scene JSON, or None
    for the built-in Cornell box) and return a Result with every frame.

    options: frames, passes, photons, width, height, seed, emission ("constant", "pulse",
    "pulse:WIDTH_NS"), camera_tof (bool), sections, max_memory (bytes or "2G"), max_bucket_memory,
    threads, max_depth, strategy, exposure, exposure_percentile, exposure_follow, gltf_light_units,
    gltf_principled: the command line's flags of the same names. progress(section, passes_done, sections, passes)
    is called after every pass. base_dir resolves a dict scene's file paths (default: the
    working directory). Ctrl-C ends the pass in flight and raises KeyboardInterrupt with
    `.result` (a Result, interrupted=True) and `.frames` (its frames) on the exception.
    """
    r, seen = _open(scene, options, "render", base_dir)
    frames = _slowlight.frames_array(r.frames, r.height, r.width)
    r.start(frames, 1, progress is not None)
    try:
        for _ in _events(r, progress):
            pass
    except KeyboardInterrupt as interrupt:
        r.cancel()  # the pass in flight ends; the section in progress is written from what it had
        for _ in _events(r, None):
            pass
        result = _result(r, frames[: r.frames_written], list(r.warnings))
        interrupt.result, interrupt.frames = result, result.frames
        raise
    _warn(r.warnings, seen)
    return _result(r, frames, list(r.warnings))


class FrameStream:
    """Iterates over a render's frames in order, each as soon as its section is assembled; at
    most `queue_frames` finished frames wait for the loop (the render waits when they do).
    After the loop: `steady`, `exposure`, `stats`, `edges_ns`, `edges_m`, `warnings`.
    Leaving the loop early (break, an exception) stops the render."""

    def __init__(self, scene, progress, base_dir, queue_frames, options):
        self._r, self._seen = _open(scene, options, "frames", base_dir)
        self._progress = progress
        r = self._r
        self.frames, self.height, self.width, self.sections = r.frames, r.height, r.width, r.sections
        self.edges_ns = _np.asarray(r.edges_ns, dtype=_np.float64)
        self.edges_m = self.edges_ns * SPEED_OF_LIGHT_M_PER_NS
        self.steady = self.exposure = self.stats = None
        self.per_frame_exposure = []
        self.interrupted = False
        self.warnings = list(r.warnings)
        r.start(None, queue_frames, progress is not None)
        self._events = _events(r, progress)
        self._done = False

    def _frame(self, event):
        k = event[1]
        return Frame(k, event[2], float(self.edges_ns[k]), float(self.edges_ns[k + 1]))

    def _finish(self):
        r = self._r
        self._done = True
        self.steady, self.exposure = r.steady, r.exposure
        self.per_frame_exposure = list(r.per_frame_exposure)
        self.stats = _json.loads(r.stats_json())
        self.interrupted = r.interrupted
        self.warnings = list(r.warnings)

    def __iter__(self):
        return self

    def __next__(self):
        if self._done:
            raise StopIteration
        try:
            event = next(self._events)
        except KeyboardInterrupt as interrupt:
            interrupt.frames, interrupt.stream = self.stop(), self
            raise
        if event[0] == "frame":
            return self._frame(event)
        self._finish()
        _warn(self.warnings, self._seen)
        raise StopIteration

    def stop(self):
        """What Ctrl-C does: the pass in flight ends, the section in progress is written from the
        passes it completed; returns the frames written that the loop has not had yet. (Ctrl-C
        while the loop waits for a frame calls it; landing in the loop's own body, it is yours
        to call.)"""
        if self._done:
            return []
        self._r.cancel()
        rest = [self._frame(e) for e in _events(self._r, None) if e[0] == "frame"]
        self._finish()
        return rest

    def close(self):
        """Stop the render (frames not yet read are dropped)."""
        if not self._done:
            self._r.abandon()
            for _ in _events(self._r, None):
                pass
            self._finish()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass


def frames(scene=None, *, progress=None, base_dir=None, queue_frames=2, **options):
    """Like render(), but yields each frame (a Frame) in order as its section finishes, so that
    no more than the sections the command line would hold are in memory. Ctrl-C ends the pass in
    flight and raises KeyboardInterrupt with `.frames`, the frames written after it (the rest of
    the section in progress), and `.stream`, this FrameStream."""
    return FrameStream(scene, progress, base_dir, queue_frames, options)


def info(scene=None, *, base_dir=None, **options):
    """What `slowlight info` prints, as a dict (sizes in bytes, times in ns, lengths in m,
    powers in W); its warnings are issued through the warnings module too."""
    args, text = _command_line(scene, options, "info")
    result = _json.loads(_slowlight.info_json(args, text, _os.fspath(base_dir) if base_dir is not None else ""))
    _warn(result.get("warnings", []), set())
    return result

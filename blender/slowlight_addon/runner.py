# Runs the slowlight program as a child process: builds its command line from the panel's
# settings, reads its progress line (drawn only on a terminal, so the child's stderr is a pty),
# reports progress and its warning:/error: lines, and stops it on request with SIGINT, as Ctrl-C
# does (the program keeps the frames so far, closes the video and exits 130).
import os
import pty
import re
import select
import shutil
import signal
import subprocess
import termios

import bpy

PROGRESS = re.compile(r"section (\d+)/(\d+), pass (\d+)/(\d+)")
ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")
INTERRUPTED = 130


def program_path(settings):
    p = bpy.path.abspath(settings.program) if settings.program else "slowlight"
    if os.sep in p:
        return p if os.access(p, os.X_OK) else None
    return shutil.which(p)


def command(settings, program, scene_json, exr_dir, video=None, still=False):
    cmd = [program, "render", scene_json, "--exr-dir", exr_dir]
    if still:
        # The steady image (everything that ever arrives) needs no time buckets: one frame.
        cmd += ["--frames", "1", "--emission", "constant"]
    else:
        if video:
            cmd += ["-o", video]
        if settings.label_time:
            cmd += ["--label", "time"]
    if settings.use_time_limit:
        cmd += ["--time-limit", "%ds" % max(1, round(settings.time_limit_min * 60))]
    if not still and settings.split == 'SECTIONS':
        cmd += ["--sections", str(settings.sections)]
    elif settings.split == 'MEMORY':
        cmd += ["--max-memory", settings.max_memory.strip()]
    return cmd


def kind(line):
    """The Blender report type of one line the program printed."""
    if line.startswith("error:") or ": error:" in line:
        return 'ERROR'
    if line.startswith("warning:") or ": warning:" in line:
        return 'WARNING'
    return 'INFO'


def run(cmd, on_progress=None, should_stop=None, on_line=None, poll_seconds=0.1):
    """Runs cmd to its end; returns its exit status. on_progress(fraction), on_line(text) for every
    line it prints (progress redraws excluded); should_stop() -> True sends SIGINT once."""
    master, slave = pty.openpty()
    attrs = termios.tcgetattr(slave)
    attrs[1] &= ~termios.ONLCR  # keep "\n" as it is
    termios.tcsetattr(slave, termios.TCSANOW, attrs)
    try:
        child = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=slave, stderr=slave, close_fds=True)
    finally:
        os.close(slave)
    pending = ""
    stopped = False

    def report(m):
        s, ns, p, np_ = (int(x) for x in m.groups())
        on_progress(min(1.0, ((s - 1) * np_ + p) / max(1, ns * np_)))

    def consume(piece, final=False):
        nonlocal pending
        pending += ANSI.sub("", piece)
        parts = re.split(r"(\r|\n)", pending)
        pending = "" if final else parts.pop()  # an unfinished segment waits for more
        segment = ""
        for part in parts:
            if part == "\r":  # the progress line is redrawn after a carriage return
                m = PROGRESS.search(segment)
                if m and on_progress:
                    report(m)
                if m or not segment.strip():
                    segment = ""
            elif part == "\n":
                text = segment.strip()
                if text and not PROGRESS.search(text) and on_line:
                    on_line(text)
                segment = ""
            else:
                segment += part
        m = PROGRESS.search(pending)  # the line drawn last, not yet redrawn
        if m and on_progress:
            report(m)
        if final and segment.strip() and not PROGRESS.search(segment) and on_line:
            on_line(segment.strip())

    try:
        while True:
            if should_stop and not stopped and should_stop():
                child.send_signal(signal.SIGINT)
                stopped = True
            ready, _, _ = select.select([master], [], [], poll_seconds)
            if ready:
                try:
                    data = os.read(master, 65536)
                except OSError:  # EIO: the child closed its side
                    data = b""
                if data:
                    consume(data.decode("utf-8", "replace"))
                    continue
                if child.poll() is not None:
                    break
            elif child.poll() is not None:
                # drain what is left
                while select.select([master], [], [], 0)[0]:
                    try:
                        data = os.read(master, 65536)
                    except OSError:
                        break
                    if not data:
                        break
                    consume(data.decode("utf-8", "replace"))
                break
        consume("", final=True)
        return child.wait()
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
        os.close(master)

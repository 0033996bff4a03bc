#!/usr/bin/env python3
# How right the progress line's "time left" is: runs a render under a pseudo-terminal (so that
# the progress line is drawn), notes when each pass is reported and the time left it shows, and
# prints, for a few passes, the estimate against the time the passes really took from there.
# One section only (pass numbers restart in each section).
#
#   python3 bench/progress/time_left.py build/slowlight render --width 512 --height 512 \
#       --passes 48 --photons 400000 -o /tmp/eta.mp4
import os, pty, re, sys, time, subprocess
cmd = sys.argv[1:]
master, slave = pty.openpty()
p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=slave)
os.close(slave)
buf = b""; rows = []
while True:
    try:
        data = os.read(master, 4096)
    except OSError:
        break
    if not data: break
    now = time.time()
    for seg in re.split(rb"[\r\n]", data):
        m = re.search(rb"pass (\d+)/(\d+).*?(?:(\d+):)?(\d+):(\d\d) left", seg)
        if m:
            h = int(m.group(3) or 0); mm = int(m.group(4)); ss = int(m.group(5))
            rows.append((now, int(m.group(1)), int(m.group(2)), h*3600+mm*60+ss))
p.wait(); end = time.time()
# The render ends before the writing: take the last pass's report time as the render's end.
last = {}
for t, k, n, left in rows: last.setdefault(k, (t, left))
t_end = max(t for t, k, n, l in rows)
print("pass  estimate_s  actual_s  error")
for k in sorted(last):
    t, left = last[k]
    actual = t_end - t
    if actual > 1 and k in (1, 2, 3, 5, 8, 16, 32, 48):
        print(f"{k:4d} {left:10d} {actual:9.1f} {100*(left-actual)/actual:+6.0f}%")

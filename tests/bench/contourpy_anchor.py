#!/usr/bin/python3
"""contourpy_anchor.py: the contourpy anchor for bench_contour (same grid, same levels, serial).

usage: contourpy_anchor.py [-n RUNS] [--help] [--version]

Workload (identical to tests/bench/bench_contour.c):
  grid   1024 x 1024 samples over [-3, 3] x [-3, 3]
  field  z = |P - (-1, 0)| + |P - (1, 0)| + |P - (0, 1.2)|, float32 like Locus
  levels 3.0, 3.5, ..., 12.0 (19 levels)
Only contour generation is timed (contour_generator + lines() for every
level, serial algorithm), median of RUNS runs (default 7). Segments are
counted as points - 1 per line (contourpy repeats the first point of a closed
loop, so this equals Locus' count). Needs Debian python3-contourpy.
Prints one human line and one "BENCH contour-contourpy SECONDS s ..." line.
"""
import os
import sys
import time

try:
    import numpy as np
    import contourpy
except ImportError:
    # a python3 first on PATH (pyenv, venv) may lack Debian's packages: use the system one
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and \
            os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.stderr.write("contourpy_anchor.py: numpy/contourpy missing (apt-get install python3-contourpy)\n")
    sys.exit(69)

N = 1024
LEVELS = [3.0 + 0.5 * k for k in range(19)]


def main():
    runs = 7
    args = sys.argv[1:]
    if args[:1] in (["--help"], ["-h"]):
        print(__doc__.strip())
        return 0
    if args[:1] == ["--version"]:
        print("contourpy_anchor.py (contourpy %s, numpy %s)" % (contourpy.__version__, np.__version__))
        return 0
    if len(args) == 2 and args[0] == "-n":
        runs = int(args[1])
    elif args:
        sys.stderr.write("contourpy_anchor.py: usage: contourpy_anchor.py [-n RUNS]\n")
        return 64
    x = -3 + 6.0 * np.arange(N) / (N - 1)
    X, Y = np.meshgrid(x, x)
    z = np.zeros_like(X)
    for px, py in ((-1.0, 0.0), (1.0, 0.0), (0.0, 1.2)):
        z += np.hypot(X - px, Y - py)
    z = z.astype(np.float32).astype(np.float64)  # the same samples Locus sees
    times = []
    segments = lines_total = 0
    for _ in range(runs):
        t0 = time.perf_counter()
        gen = contourpy.contour_generator(x, x, z, name="serial",
                                          line_type=contourpy.LineType.Separate)
        result = [gen.lines(level) for level in LEVELS]
        times.append(time.perf_counter() - t0)
        segments = sum(len(line) - 1 for lines in result for line in lines)
        lines_total = sum(len(lines) for lines in result)
    times.sort()
    med = times[len(times) // 2]
    print("contourpy %s serial 1024x1024, 19 levels: %.4f s (median of %d, best %.4f), "
          "%d segments, %d lines" % (contourpy.__version__, med, runs, times[0], segments, lines_total))
    print("BENCH contour-contourpy %.6f s segments=%d polylines=%d" % (med, segments, lines_total))
    return 0


if __name__ == "__main__":
    sys.exit(main())

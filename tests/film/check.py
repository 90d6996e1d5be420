#!/usr/bin/env python3
"""check.py: read a film frame back through ImageMagick or OpenImageIO and compare it with the
locus-raster picture it came from (tests/t_film.sh).

usage: check.py REF.ppm FILE KIND READER [CHANNELS]
  KIND     log (10-bit printing density, docs/film.md defaults) or lin16 (16-bit linear)
  READER   oiio (oiiotool -a --dumpdata) or im (ImageMagick convert to a 16-bit PPM)
  CHANNELS the channels the file holds, in order: rgb (default), r, g, b, or planar (r, g, b
           as three image elements)
Checks that every code value is exactly the documented encoding of the reference's 8-bit value
(sRGB-decoded to linear light, then log-encoded or scaled to 16 bits), and that decoding it back
(to linear light, then sRGB-encoded) lands within one 8-bit code value. Prints one line; exits
0 when both hold, 1 otherwise, 2 on a reader failure.
"""
import math
import re
import subprocess
import sys

WHITE, BLACK, DENSITY, FILM_GAMMA, DISPLAY_GAMMA = 685.0, 95.0, 0.002, 0.6, 1.7
K = DENSITY / FILM_GAMMA * (DISPLAY_GAMMA / 1.7)
OFF = 10 ** ((BLACK - WHITE) * K)


def srgb_decode(v):
    c = v / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def srgb_encode(x):
    x = max(0.0, x)
    return 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1 / 2.4) - 0.055


def encode(v, kind):
    lin = srgb_decode(v)
    if kind == "lin16":
        return int(math.floor(lin * 65535 + 0.5))
    c = WHITE + math.log10(lin * (1 - OFF) + OFF) / K
    return max(0, min(1023, int(math.floor(c + 0.5))))


def decode(code, kind):
    """the code back to the picture's 8-bit scale: log (or linear) to linear light to sRGB"""
    if kind == "lin16":
        return srgb_encode(code / 65535.0) * 255
    return srgb_encode((10 ** ((code - WHITE) * K) - OFF) / (1 - OFF)) * 255


def read_ppm(data):
    parts = []
    pos = 0
    while len(parts) < 4:
        m = re.compile(rb"\s*(#[^\n]*\n\s*)*(\S+)").match(data, pos)
        parts.append(m.group(2))
        pos = m.end()
    w, h, mx = int(parts[1]), int(parts[2]), int(parts[3])
    pos += 1
    n = 2 if mx > 255 else 1
    vals = [int.from_bytes(data[pos + n * k:pos + n * k + n], "big") for k in range(w * h * 3)]
    return w, h, vals


def planes_oiio(path, nplanes):
    out = subprocess.run(["oiiotool", "-a", "--dumpdata", path], capture_output=True, text=True)
    if out.returncode:
        raise RuntimeError(out.stderr.strip())
    planes, cur = [], None
    for line in out.stdout.splitlines():
        m = re.match(r"\s*Pixel \((\d+), (\d+)\): ([\d ]+)\(", line)
        if not m:
            continue
        if m.group(1) == "0" and m.group(2) == "0":
            cur = []
            planes.append(cur)
        cur.append([int(x) for x in m.group(3).split()])
    return planes[:nplanes]


def planes_im(path, nplanes):
    planes = []
    for i in range(nplanes):
        out = subprocess.run(["convert", "%s[%d]" % (path, i), "-set", "colorspace", "sRGB", "-depth",
                              "16", "ppm:-"], capture_output=True)
        if out.returncode:
            raise RuntimeError(out.stderr.decode().strip())
        w, h, vals = read_ppm(out.stdout)
        planes.append([vals[3 * k:3 * k + 3] for k in range(w * h)])
    return planes


def main():
    ref_path, path, kind, reader = sys.argv[1:5]
    chans = sys.argv[5] if len(sys.argv) > 5 else "rgb"
    w, h, ref = read_ppm(open(ref_path, "rb").read())
    nplanes = 3 if chans == "planar" else 1
    try:
        planes = (planes_oiio if reader == "oiio" else planes_im)(path, nplanes)
    except (RuntimeError, OSError) as e:
        print("%s: %s could not read it: %s" % (path, reader, e))
        return 2
    # which reference channel each value of each plane holds
    layout = {"rgb": [[0, 1, 2]], "r": [[0]], "g": [[1]], "b": [[2]], "planar": [[0], [1], [2]]}[chans]
    bad_code = bad_lin = 0
    worst = 0.0
    for p, chs in enumerate(layout):
        if p >= len(planes) or len(planes[p]) != w * h:
            print("%s: %s gave %s pixels in image element %d, expected %d" %
                  (path, reader, len(planes[p]) if p < len(planes) else 0, p, w * h))
            return 1
        for i, px in enumerate(planes[p]):
            for j, c in enumerate(chs):
                v = px[j] if len(px) > j else px[0]
                if kind == "lin16":
                    code = v
                elif reader == "oiio":
                    code = v >> 6                  # OIIO widens 10 bits to 16 by replication
                else:
                    code = int(round(v * 1023 / 65535.0))
                want = ref[3 * i + c]
                if code != encode(want, kind):
                    bad_code += 1
                d = abs(decode(code, kind) - want)
                worst = max(worst, d)
                if round(decode(code, kind)) - want not in (-1, 0, 1):
                    bad_lin += 1
    verdict = "ok" if bad_code == 0 and bad_lin == 0 else "differs"
    print("%s: %s: %d values with a wrong code, %d decoded off by more than one; worst %.3f (%s)" %
          (path, reader, bad_code, bad_lin, worst, verdict))
    return 0 if verdict == "ok" else 1


if __name__ == "__main__":
    sys.exit(main())

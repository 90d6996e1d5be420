#!/usr/bin/env python3
# fbcheck.py: read framebuffer dumps (docs/framebuffer.md) for tests/t_fb.sh: the F picture's
# geometry and colours, the expected RGB of a dump, and the headers of PNG, PCX and BMP files.
# Prints "ok - ..." / "not ok - ..." lines; exits 1 on a malformed dump.
import struct
import sys
import zlib

MODES = {  # name: (width, height, layout)
    "13h": (320, 200, "linear8"), "12h": (640, 480, "planar4"),
    "1024x768x256": (1024, 768, "linear8"), "640x480x565": (640, 480, "direct565"),
}


def dac8(v):
    return (v << 2) | (v >> 4)


def decode(path, mode):
    """(width, height, per-pixel RGB tuples, DAC palette of 6-bit triples or None, indices)."""
    w, h, layout = MODES[mode]
    data = open(path, "rb").read()
    px = w * h
    if layout == "linear8":
        if len(data) != px + 768:
            sys.exit(f"{path}: {len(data)} bytes, a {mode} dump has {px + 768}")
        idx = data[:px]
        pal = [tuple(data[px + 3 * k: px + 3 * k + 3]) for k in range(256)]
    elif layout == "planar4":
        bpl = w // 8
        if len(data) != 4 * bpl * h + 48:
            sys.exit(f"{path}: {len(data)} bytes, a {mode} dump has {4 * bpl * h + 48}")
        planes = [data[p * bpl * h:(p + 1) * bpl * h] for p in range(4)]
        idx = bytearray(px)
        for y in range(h):
            for x in range(w):
                b = y * bpl + x // 8
                bit = 0x80 >> (x & 7)
                idx[y * w + x] = sum(1 << p for p in range(4) if planes[p][b] & bit)
        base = 4 * bpl * h
        pal = [tuple(data[base + 3 * k: base + 3 * k + 3]) for k in range(16)]
    else:
        if len(data) != 2 * px:
            sys.exit(f"{path}: {len(data)} bytes, a {mode} dump has {2 * px}")
        idx = None
        pal = None
        rgb = []
        for k in range(px):
            v = data[2 * k] | data[2 * k + 1] << 8
            r, g, b = v >> 11, (v >> 5) & 63, v & 31
            rgb.append(((r << 3) | (r >> 2), (g << 2) | (g >> 4), (b << 3) | (b >> 2)))
        return w, h, rgb, None, None, data
    rgb = [tuple(dac8(c) for c in pal[i]) for i in idx]
    return w, h, rgb, pal, idx, data


def report(good, what):
    print(("ok - " if good else "not ok - ") + what)


def centroid(rgb, w, colour):
    xs = ys = n = 0
    for k, c in enumerate(rgb):
        if c == colour:
            xs += k % w
            ys += k // w
            n += 1
    return (xs / n, ys / n, n) if n else (0, 0, 0)


def fcheck(path, mode):
    """The F of fixtures/meta/f-test.meta: red stem left, green bar at the top right of it,
    blue bar in the middle; DAC bytes R, G, B in that order and 6-bit."""
    w, h, rgb, pal, idx, data = decode(path, mode)
    red, green, blue = (255, 0, 0), (0, dac8(47), 0), (0, 0, 255)
    rx, ry, rn = centroid(rgb, w, red)
    gx, gy, gn = centroid(rgb, w, green)
    bx, by, bn = centroid(rgb, w, blue)
    report(rn and gn and bn, f"{mode}: F has red, green and blue pixels ({rn}, {gn}, {bn})")
    report(rx < gx and rx < bx, f"{mode}: F not flipped left-right (red stem x {rx:.0f} left of bars {gx:.0f}, {bx:.0f})")
    report(gy < by, f"{mode}: F not flipped upside down (green bar y {gy:.0f} above blue {by:.0f})")
    report(gx > bx, f"{mode}: top bar longer than the middle bar (not transposed)")
    if pal is not None:
        ri = idx[int(ry) * w + int(rx)]
        gi = idx[int(gy) * w + int(gx)]
        report(pal[ri] == (63, 0, 0), f"{mode}: red stem's DAC entry is R=63 G=0 B=0 (channel order, 6-bit): {pal[ri]}")
        report(pal[gi] == (0, 47, 0), f"{mode}: green bar's DAC entry is 0,47,0 (#00c000 at 6 bits): {pal[gi]}")
        report(max(max(p) for p in pal) <= 63, f"{mode}: every DAC byte is 6-bit")
    else:
        k = int(ry) * w + int(rx)
        report(data[2 * k: 2 * k + 2] == b"\x00\xf8", f"{mode}: red is 0xF800 little-endian (5-6-5 channel order)")


def expect(path, mode, out):
    w, h, rgb, *_ = decode(path, mode)
    with open(out, "wb") as f:
        f.write(bytes(c for p in rgb for c in p))


def png_chunks(data):
    pos = 8
    while pos < len(data):
        n, = struct.unpack(">I", data[pos:pos + 4])
        yield data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n


def header(path, fmt, mode):
    w, h, layout = MODES[mode]
    d = open(path, "rb").read()
    if fmt == "png":
        ch = dict(png_chunks(d))
        ihdr = ch.get(b"IHDR", b"")
        if layout == "direct565":
            report(ihdr[8:10] == b"\x08\x02", f"{mode} png: 8-bit RGB (direct colour)")
        else:
            depth = 4 if layout == "planar4" else 8
            report(ihdr[8] == depth and ihdr[9] == 3, f"{mode} png: colour type 3, {depth}-bit indices")
            report(b"PLTE" in ch and len(ch[b"PLTE"]) % 3 == 0, f"{mode} png: has PLTE")
        phys = ch.get(b"pHYs", b"")
        x, y = struct.unpack(">II", phys[:8]) if len(phys) == 9 else (0, 0)
        want = 1.2 if mode == "13h" else 1.0
        report(y and abs(x / y - want) < 1e-3, f"{mode} png: pHYs records the pixel shape ({x}:{y})")
    elif fmt == "pcx":
        report(d[0] == 10 and d[1] == 5 and d[2] == 1, f"{mode} pcx: version 5, RLE")
        xmax, ymax = struct.unpack("<HH", d[8:12])
        report((xmax + 1, ymax + 1) == (w, h), f"{mode} pcx: {xmax + 1}x{ymax + 1}")
        bits, planes, bpl = d[3], d[65], struct.unpack("<H", d[66:68])[0]
        if layout == "planar4":
            # a PCX 16-colour file: 4 planes of 1 bit, the EGA palette in the header, no 0x0C
            report((bits, planes, bpl) == (1, 4, (w + 15) // 16 * 2),
                   f"{mode} pcx: 4 planes of 1 bit, {bpl} bytes a plane line")
            report(d[-769] != 12 or len(d) < 769, f"{mode} pcx: no 256-colour palette at the end")
        elif layout == "linear8":
            report((bits, planes) == (8, 1), f"{mode} pcx: one plane of 8 bits")
            report(d[-769] == 12, f"{mode} pcx: 0x0C then the 256-colour palette")
        else:
            report((bits, planes) == (8, 3), f"{mode} pcx: three planes of 8 bits")
    elif fmt == "bmp":
        off, = struct.unpack("<I", d[10:14])
        bw, bh, planes, bits, comp = struct.unpack("<iiHHI", d[18:34])
        want_bits = {"linear8": 8, "planar4": 4, "direct565": 24}[layout]
        want_off = {8: 1078, 4: 118, 24: 54}[want_bits]
        report(bits == want_bits and comp == 0 and off == want_off,
               f"{mode} bmp: {bits}-bit BI_RGB, pixels at {off}")
        report(bw == w and bh == h, f"{mode} bmp: bottom-up rows (height {bh} > 0)")


def fbmem(mem, bpp, xres, yres, ll, dump, mode, cmap, what):
    """The fake framebuffer's memory (tests/fbdev/fbharness.c) against a dump of the same
    picture: pixels through the harness's bit fields, padding and tail untouched, and for 8 bits
    the indices and the colour map. dump "-" means: everything restored (marker bytes only,
    the grey colour map back)."""
    m = open(mem, "rb").read()
    bpp, xres, yres, ll = int(bpp), int(xres), int(yres), int(ll)
    bytes_pp = bpp // 8
    marker_ok = all(b == 0x5A for b in m[ll * yres:]) and all(
        b == 0x5A for y in range(yres) for b in m[y * ll + xres * bytes_pp:(y + 1) * ll])
    report(marker_ok, f"{what}: row padding and the memory after the screen untouched")
    cm = [tuple(int(v) for v in line.split()) for line in open(cmap)] if cmap != "-" else []
    if dump == "-":
        report(all(b == 0x5A for b in m), f"{what}: the screen's old contents restored")
        if bpp == 8:
            report(len(cm) == 256 and all(c == (k, k * 257, k * 257, k * 257) for k, c in enumerate(cm)),
                   f"{what}: the old colour map restored")
        return
    w, h, rgb, pal, idx, _ = decode(dump, mode)
    if (w, h) != (xres, yres):
        sys.exit(f"{dump}: {w}x{h}, the screen is {xres}x{yres}")
    bad = 0
    for y in range(yres):
        row = m[y * ll: y * ll + xres * bytes_pp]
        for x in range(xres):
            px = row[x * bytes_pp:(x + 1) * bytes_pp]
            k = y * w + x
            if bpp == 32:
                got = (px[0], px[1], px[2])        # red at bit 0, green 8, blue 16
                bad += got != rgb[k] or px[3] != 0
            elif bpp == 24:
                got = (px[2], px[1], px[0])        # red at bit 16: bytes B, G, R
                bad += got != rgb[k]
            elif bpp == 16:
                v = px[0] | px[1] << 8
                r, g, b = rgb[k]
                bad += v != ((r >> 3) << 11 | (g >> 2) << 5 | (b >> 3))
            else:
                bad += px[0] != idx[k]
    report(bad == 0, f"{what}: every pixel is the dump's ({bad} differ)")
    if bpp == 8:
        want = [(k, *(pal[k][c] * 65535 // 63 for c in range(3))) for k in range(len(cm))]
        report(len(cm) >= 2 and cm == want, f"{what}: FBIOPUTCMAP holds the dump's DAC palette scaled to 16 bits")


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "f":
        fcheck(sys.argv[2], sys.argv[3])
    elif cmd == "expect":
        expect(sys.argv[2], sys.argv[3], sys.argv[4])
    elif cmd == "fbmem":
        fbmem(*sys.argv[2:11])
    elif cmd == "header":
        header(sys.argv[2], sys.argv[3], sys.argv[4])
    else:
        sys.exit("usage: fbcheck.py f|expect|header ...")

#!/bin/sh
# t_raster_spec.sh: an independent, brute-force implementation of spec §5 (written from
# docs/meta-language.md, per pixel, exact integers in Python) must draw the same pixels as
# locus-raster on the stroke, fill, image, coverage and text fixtures (the font is read from the
# glyph listing in docs/stroke-font.md, not from drivers/geom/font.c).
. tests/lib.sh
command -v python3 >/dev/null 2>&1 || { ok "python3 missing # SKIP"; done_tests; }
cat > "$T/spec.py" <<'EOF'
import math, sys

def R(v):                       # nearest integer, ties away from zero
    t = math.trunc(v); f = v - t
    if f >= 0.5: t += 1
    elif f <= -0.5: t -= 1
    return int(t)

def fix(s):                     # text number -> thousandths (fixtures are canonical)
    neg = s.startswith('-'); s = s.lstrip('+-')
    a, _, b = s.partition('.')
    v = int(a or '0') * 1000 + int((b + '000')[:3] or '0')
    return -v if neg else v

def chords(r):                  # M of 5.4 for a radius in thousandths
    rp = r / 1000.0
    if not rp > 0.25: return 8
    return max(8, math.ceil(2.0 * math.pi / math.acos(1.0 - 0.25 / rp)))

def arc_points(cx, cy, r, start, sweep):
    m = chords(r); n = max(1, -(-abs(sweep) * m // 360000))
    out = []
    for k in range(n + 1):
        th = (start * n + sweep * k) / (n * 180000.0) * math.pi
        out.append((cx + R(r * math.cos(th)), cy + R(r * math.sin(th))))
    return out

class Page:
    def __init__(s, w, h):
        s.w, s.h = w, h
        s.pix = [[(255, 255, 255)] * w for _ in range(h)]   # pix[j][i], j from the bottom
    def paint_poly(s, contours, rule, rgb):
        pts = [p for c in contours for p in c]
        if not pts: return
        ylo = max(0, (min(p[1] for p in pts) - 500) // 1000 - 1); yhi = min(s.h, max(p[1] for p in pts) // 1000 + 2)
        xlo = max(0, (min(p[0] for p in pts) - 500) // 1000 - 1); xhi = min(s.w, max(p[0] for p in pts) // 1000 + 2)
        for j in range(ylo, yhi):
            yc = 1000 * j + 500
            for i in range(xlo, xhi):
                xc = 1000 * i + 500; w = 0
                for c in contours:
                    for k in range(len(c)):
                        (x0, y0), (x1, y1) = c[k], c[(k + 1) % len(c)]
                        if y0 == y1 or not (min(y0, y1) <= yc < max(y0, y1)): continue
                        # X <= xc, cross-multiplied with a positive denominator
                        if y1 > y0: le = x0 * (y1 - y0) + (yc - y0) * (x1 - x0) <= xc * (y1 - y0)
                        else: le = x1 * (y0 - y1) + (yc - y1) * (x0 - x1) <= xc * (y0 - y1)
                        if le: w += 1 if y1 > y0 else -1
                if (w % 2 == 1) if rule == 'even-odd' else (w != 0):
                    s.pix[j][i] = rgb

class Stroker:
    def __init__(s, page, st, rgb):
        s.p, s.rgb = page, rgb
        s.h = max(st['width'], 1000) / 2.0
        s.cap, s.join, s.lim = st['cap'], st['join'], st['miter'] / 1000.0
    def piece(s, q): s.p.paint_poly([q], 'non-zero', s.rgb)
    def disc(s, v):
        m = chords(s.h)
        s.piece([(v[0] + R(s.h * math.cos((360000.0 * k) / (m * 180000.0) * math.pi)),
                  v[1] + R(s.h * math.sin((360000.0 * k) / (m * 180000.0) * math.pi))) for k in range(m)])
    def seg(s, p, q):
        dx, dy = q[0] - p[0], q[1] - p[1]; L = math.sqrt(float(dx * dx + dy * dy))
        u = (-dy / L, dx / L); o = (R(s.h * u[0]), R(s.h * u[1]))
        return (dx, dy), u, o
    def dot(s, v):
        if s.cap == 'round': s.disc(v)
        elif s.cap == 'square':
            r = R(s.h); s.piece([(v[0] - r, v[1] - r), (v[0] + r, v[1] - r), (v[0] + r, v[1] + r), (v[0] - r, v[1] + r)])
    def do_join(s, v, a, b):
        (d1, u1, o1), (d2, u2, o2) = a, b
        z = d1[0] * d2[1] - d1[1] * d2[0]
        if z == 0:
            if d1[0] * d2[0] + d1[1] * d2[1] < 0 and s.join == 'round': s.disc(v)
            return
        if s.join == 'round': s.disc(v); return
        g = -1 if z > 0 else 1
        A = (v[0] + g * o1[0], v[1] + g * o1[1]); B = (v[0] + g * o2[0], v[1] + g * o2[1])
        if s.join == 'miter':
            v1 = (g * u1[0], g * u1[1]); v2 = (g * u2[0], g * u2[1]); c = v1[0] * v2[0] + v1[1] * v2[1]
            if (1 + c) * (s.lim * s.lim) >= 2:
                M = (v[0] + R(s.h * (v1[0] + v2[0]) / (1 + c)), v[1] + R(s.h * (v1[1] + v2[1]) / (1 + c)))
                s.piece([v, A, M, B]); return
        s.piece([v, A, B])
    def solid(s, pts, closed):
        q = [pts[0]]
        for p in pts[1:]:
            if p != q[-1]: q.append(p)
        if closed and len(q) > 1 and q[-1] == q[0]: q.pop()
        if len(q) == 1: s.dot(q[0]); return
        segs = [(q[k], q[k + 1]) for k in range(len(q) - 1)] + ([(q[-1], q[0])] if closed else [])
        info = [s.seg(a, b) for a, b in segs]
        for (a, b), (d, u, o) in zip(segs, info):
            s.piece([(a[0] - o[0], a[1] - o[1]), (b[0] - o[0], b[1] - o[1]), (b[0] + o[0], b[1] + o[1]), (a[0] + o[0], a[1] + o[1])])
        for k in range(1, len(segs)): s.do_join(segs[k][0], info[k - 1], info[k])
        if closed: s.do_join(segs[0][0], info[-1], info[0])
        else:
            for (P, (d, u, o), sign) in ((segs[0][0], info[0], -1), (segs[-1][1], info[-1], 1)):
                if s.cap == 'round': s.disc(P)
                elif s.cap == 'square':
                    e = (sign * o[1], sign * -o[0])
                    s.piece([(P[0] + o[0], P[1] + o[1]), (P[0] - o[0], P[1] - o[1]),
                             (P[0] - o[0] + e[0], P[1] - o[1] + e[1]), (P[0] + o[0] + e[0], P[1] + o[1] + e[1])])
    def dashed(s, pts, closed, dash):
        if all(p == pts[0] for p in pts): s.solid(pts, closed); return
        k, rest, on = 0, float(dash[0]), True
        pieces, cur = [], [pts[0]]
        segs = [(pts[i], pts[i + 1]) for i in range(len(pts) - 1)] + ([(pts[-1], pts[0])] if closed else [])
        for P, Q in segs:
            if P == Q: continue
            dx, dy = Q[0] - P[0], Q[1] - P[1]; L = math.sqrt(float(dx * dx + dy * dy)); t = 0.0
            while rest < L - t:
                t = t + rest; f = t / L; B = (P[0] + R(dx * f), P[1] + R(dy * f))
                if on: cur.append(B); pieces.append(cur); cur = None
                else: cur = [B]
                on = not on; k = (k + 1) % len(dash); rest = float(dash[k])
            rest = rest - (L - t)
            if on: cur.append(Q)
        if on and cur: pieces.append(cur)
        for pc in pieces:
            if len(pc) >= 2: s.solid(pc, False)

def run(path, out):
    page = None; st = None; subs = []; cur = None; img = None
    for raw in open(path, 'rb'):
        line = raw.decode('latin-1')
        w = line.split()
        if not w or w[0].startswith('#') or w[0] == 'LOCUS-META': continue
        op, a = w[0], w[1:]
        if op == 'page':
            page = Page(int(a[0]), int(a[1]))
            st = dict(colour=(0, 0, 0), width=1000, dash=[], cap='butt', join='miter', miter=10000, rule='non-zero')
        elif op == 'clear': page.paint_poly([[(0, 0), (page.w * 1000, 0), (page.w * 1000, page.h * 1000), (0, page.h * 1000)]], 'non-zero', hexc(a[0]))
        elif op == 'colour': st['colour'] = hexc(a[0])
        elif op == 'width': st['width'] = fix(a[0])
        elif op == 'dash': d = [fix(x) for x in a]; st['dash'] = d + d if len(d) % 2 else d
        elif op == 'cap': st['cap'] = a[0]
        elif op == 'join': st['join'] = a[0]
        elif op == 'fill-rule': st['rule'] = a[0]
        elif op == 'miter-limit': st['miter'] = fix(a[0])
        elif op in ('stroke', 'fill'): kind = op; subs = []; cur = None
        elif op == 'move': cur = {'pts': [(fix(a[0]), fix(a[1]))], 'closed': False}; subs.append(cur)
        elif op == 'draw':
            if cur['closed']: st0 = cur['pts'][0]; cur = {'pts': [st0], 'closed': False}; subs.append(cur)
            cur['pts'].append((fix(a[0]), fix(a[1])))
        elif op == 'arc':
            pts = arc_points(*[fix(x) for x in a])
            if cur is None: cur = {'pts': [pts[0]], 'closed': False}; subs.append(cur)
            elif cur['closed']: st0 = cur['pts'][0]; cur = {'pts': [st0], 'closed': False}; subs.append(cur)
            else: cur['pts'].append(pts[0])
            cur['pts'] += pts[1:]
        elif op == 'circle':
            cx, cy, r = [fix(x) for x in a]; m = chords(r)
            pts = arc_points(cx, cy, r, 0, 360000)[:m]
            # the arc from 0 through 360 has N = M chords; keep k = 0 .. M-1
            subs.append({'pts': pts, 'closed': True}); cur = None
        elif op == 'close': cur['closed'] = True
        elif op == 'end':
            if kind == 'fill': page.paint_poly([sp['pts'] for sp in subs], st['rule'], st['colour'])
            else:
                sk = Stroker(page, st, st['colour'])
                for sp in subs:
                    if len(sp['pts']) < 2 and not sp['closed']: continue
                    if st['dash']: sk.dashed(sp['pts'], sp['closed'], st['dash'])
                    else: sk.solid(sp['pts'], sp['closed'])
        elif op == 'text': draw_text(page, st, a, raw)
        elif op == 'span':
            x, y, n = int(a[0]), int(a[1]), int(a[2])
            for i in range(x, min(x + n, page.w)):
                if y < page.h: page.pix[y][i] = hexc(a[3])
        elif op == 'image': img = [int(a[0]), int(a[1]), int(a[3]), 0]
        elif op == 'row':
            y = img[1] + img[2] - 1 - img[3]; img[3] += 1; x = img[0]
            for c, col in zip(a[0::2], a[1::2]):
                for i in range(x, x + int(c)):
                    if i < page.w and y < page.h: page.pix[y][i] = hexc(col)
                x += int(c)
        elif op == 'end-page':
            with open(out, 'wb') as f:
                f.write(b'P6\n%d %d\n255\n' % (page.w, page.h))
                for j in range(page.h - 1, -1, -1):
                    f.write(bytes(v for px in page.pix[j] for v in px))
            return

FONT = {}
def load_font(doc):             # the glyph listing of docs/stroke-font.md
    for line in open(doc, encoding='utf-8'):
        cells = [c.strip() for c in line.split(' | ')]
        if len(cells) == 4 and cells[0].startswith('| ') and len(cells[0]) == 4 and cells[3].endswith('` |'):
            key = 'rep' if cells[1] == 'replacement' else int(cells[0][2:], 16)
            src = cells[3][1:-3].strip()
            FONT[key] = (float(cells[2]), [[tuple(float(v) for v in pt.split(',')) for pt in pl.split()] for pl in src.split(';') if pl.strip()])

def text_chars(b):              # 5.5: bytes -> glyph keys
    out, i = [], 0
    while i < len(b):
        c = b[i]
        if 0x20 <= c <= 0x7e: out.append(c); i += 1; continue
        n = 2 if 0xc2 <= c <= 0xdf else 3 if 0xe0 <= c <= 0xef else 4 if 0xf0 <= c <= 0xf4 else 1
        if n > 1 and i + n <= len(b) and all(0x80 <= x <= 0xbf for x in b[i + 1:i + n]): i += n
        else: i += 1
        out.append('rep')
    return out

def meta_string(line):          # the quoted operand with its escapes, as bytes
    i = line.index(b'"') + 1; out = bytearray()
    while line[i:i + 1] != b'"':
        if line[i:i + 1] == b'\\':
            if line[i + 1:i + 2] == b'x': out.append(int(line[i + 2:i + 4], 16)); i += 4
            else: out.append(line[i + 1]); i += 2
        else: out.append(line[i]); i += 1
    return bytes(out)

def draw_text(page, st, a, raw):
    X, Y, size, ang = [fix(x) for x in a[:4]]
    u = size / 6.0; an = ang / 180000.0 * math.pi; pen = 0.0
    sk = Stroker(page, dict(st, cap='round', join='round'), st['colour'])
    for ch in text_chars(meta_string(raw)):
        adv, pls = FONT[ch]
        for pl in pls:
            pts = []
            for gx, gy in pl:
                U = (pen + gx) * u; V = gy * u
                pts.append((X + R(U * math.cos(an) - V * math.sin(an)), Y + R(U * math.sin(an) + V * math.cos(an))))
            sk.solid(pts, False)
        pen += adv

def hexc(c): return (int(c[1:3], 16), int(c[3:5], 16), int(c[5:7], 16))

load_font(sys.argv[3])
run(sys.argv[1], sys.argv[2])
EOF
for f in fixtures/meta/f-test.meta fixtures/meta/strokes.meta fixtures/meta/fills.meta fixtures/meta/image.meta fixtures/raster/inputs/coverage.meta fixtures/raster/inputs/joins.meta \
		fixtures/meta/text.meta fixtures/raster/inputs/font.meta; do
	[ -f "$f" ] || continue
	c=$(basename "$f" .meta)
	if ! python3 "$T/spec.py" "$f" "$T/$c.spec.ppm" docs/stroke-font.md 2> "$T/err"; then notok "$c: the Python implementation failed: $(tail -1 "$T/err")"; continue; fi
	"$BIN/locus-raster" "$f" -o "$T/$c.ppm"
	if "$BIN/locus-diff" "$T/$c.spec.ppm" "$T/$c.ppm" > "$T/d"; then ok "$c: the spec implemented independently draws the same pixels"
	else notok "$c: independent implementation differs: $(cat "$T/d")"; fi
done
done_tests

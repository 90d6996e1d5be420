#!/bin/sh
# t_mesh.sh: polygonisation end to end: admesh (Debian) finds the STL closed and consistently
# oriented with the analytic volume, the PLY and OBJ hold the same mesh, the wireframe page lies
# on the ray-traced silhouette, and bad mesh scenes fail with one located line and no output.
. tests/lib.sh
R="$BIN/locus-render"
PY=python3

# admesh_field FILE LABEL: the number after "LABEL :" in admesh's report
admesh_field() { sed -n "s/^$2 *: *\([-0-9.]*\).*/\1/p" "$1" | head -1; }
# admesh_defects FILE: " NAME=N" for each defect count of admesh's report that is not 0
admesh_defects() {
	for f in "Facets with 1 disconnected edge" "Facets with 2 disconnected edges" "Facets with 3 disconnected edges" \
		"Degenerate facets" "Edges fixed" "Facets reversed" "Backwards edges" "Normals fixed"; do
		v=$(admesh_field "$1" "$f")
		[ "$v" = 0 ] || printf ' %s=%s' "$f" "$v"
	done
}
# within A B PCT: |A - B| <= PCT% of B
within() { awk -v a="$1" -v b="$2" -v p="$3" 'BEGIN {d = a - b; if (d < 0) d = -d; exit !(a != "" && d <= p / 100 * b)}'; }
stat() { grep -o -E "(^| )$1=[^ ]+" "$2" | head -1 | sed 's/.*=//'; }

# 1. sphere and ellipsoid through admesh: closed, no wrongly oriented facet, the analytic volume
# (the capsule coarsened within 0.001: `tolerance`, the adaptive mesh)
for c in "sphere 4.18879020 12.5663706" "ellipsoid 4.02123859 12.4082835" "capsule 2.56563400 11.3097336"; do
	set -- $c
	n=$1 vol=$2 area=$3
	if ! "$R" "fixtures/mesh/$n.scene" -o "$T/$n.stl" --stats 2> "$T/$n.stats"; then
		notok "$n: locus-render -o $n.stl: $(tail -1 "$T/$n.stats")"; continue
	fi
	if ! command -v admesh > /dev/null; then notok "admesh missing (Debian admesh)"; continue; fi
	admesh "$T/$n.stl" > "$T/$n.admesh" 2>&1
	tri=$(stat triangles "$T/$n.stats")
	facets=$(sed -n 's/^Number of facets *: *\([0-9]*\).*/\1/p' "$T/$n.admesh")
	grep -q "Binary STL" "$T/$n.admesh" && [ "$facets" = "$tri" ] && ok "$n: admesh reads $tri facets of binary STL" \
		|| notok "$n: admesh facets '$facets', locus-render says $tri"
	bad=$(admesh_defects "$T/$n.admesh")
	grep -q "No holes need to be filled" "$T/$n.admesh" || bad="$bad holes"
	[ -z "$bad" ] && [ "$(admesh_field "$T/$n.admesh" "Number of parts")" = 1 ] \
		&& ok "$n: admesh: one part, no open edge, no wrongly oriented facet, no degenerate facet" \
		|| notok "$n: admesh:$bad parts=$(admesh_field "$T/$n.admesh" "Number of parts")"
	v=$(sed -n 's/.*Volume *: *\([0-9.]*\).*/\1/p' "$T/$n.admesh")
	within "$v" "$vol" 0.5 && ok "$n: admesh volume $v within 0.5% of $vol" || notok "$n: admesh volume '$v', exact $vol"
	a=$(stat area "$T/$n.stats")
	within "$a" "$area" 0.5 && ok "$n: area $a within 0.5% of $area" || notok "$n: area '$a', exact $area"
done

# 1b. coarsening keeps the capsule's round caps fine and makes its cylinder coarse: far fewer
# triangles than the same depth without a tolerance (marching cubes: under 2/5 of them;
# marching tetrahedra, three times the triangles with slivers among them: under a quarter)
sed '/tolerance/d' fixtures/mesh/capsule.scene > "$T/cap0.scene"
"$R" "$T/cap0.scene" -o "$T/cap0.stl" --stats 2> "$T/cap0.stats"
t0=$(stat triangles "$T/cap0.stats") t1=$(stat triangles "$T/capsule.stats")
[ -n "$t0" ] && [ -n "$t1" ] && [ $((t1 * 5)) -lt $((t0 * 2)) ] && ok "tolerance 0.001 coarsens the capsule from $t0 to $t1 triangles" \
	|| notok "capsule coarsening: $t0 -> $t1 triangles"
sed 's/^render mesh$/render mesh\n  method tetrahedra/' fixtures/mesh/capsule.scene > "$T/capt.scene"
sed '/tolerance/d' "$T/capt.scene" > "$T/capt0.scene"
"$R" "$T/capt.scene" -o "$T/capt.stl" --stats 2> "$T/capt.stats"
"$R" "$T/capt0.scene" -o "$T/capt0.stl" --stats 2> "$T/capt0.stats"
t0=$(stat triangles "$T/capt0.stats") t1=$(stat triangles "$T/capt.stats")
[ -n "$t0" ] && [ -n "$t1" ] && [ $((t1 * 4)) -lt "$t0" ] && ok "method tetrahedra: tolerance 0.001 coarsens the capsule from $t0 to $t1 triangles" \
	|| notok "capsule coarsening (tetrahedra): $t0 -> $t1 triangles"

# 2. the same mesh as PLY and OBJ: their headers, counts and indices, and the STL's facets
"$R" fixtures/mesh/ellipsoid.scene -o "$T/e.ply" && "$R" fixtures/mesh/ellipsoid.scene -o "$T/E.OBJ" \
	&& ok "PLY and OBJ (any case of suffix) written" || notok "PLY/OBJ"
if $PY - "$T/ellipsoid.stl" "$T/e.ply" "$T/E.OBJ" > "$T/fmt.out" 2>&1 <<'PYEOF'
import struct, sys
stl, ply, obj = (open(p, 'rb').read() for p in sys.argv[1:4])
n = struct.unpack_from('<I', stl, 80)[0]
assert len(stl) == 84 + 50 * n, 'STL size'
tri_stl = [struct.unpack_from('<9f', stl, 84 + 50 * i + 12) for i in range(n)]
end = ply.index(b'end_header\n') + 11
head = ply[:end].decode().split('\n')
assert head[0] == 'ply' and head[1] == 'format binary_little_endian 1.0', head[:2]
nv = int([l for l in head if l.startswith('element vertex')][0].split()[2])
nf = int([l for l in head if l.startswith('element face')][0].split()[2])
assert nf == n, 'PLY faces %d, STL %d' % (nf, n)
v = struct.unpack_from('<%df' % (3 * nv), ply, end)
off = end + 12 * nv
assert len(ply) == off + 13 * nf, 'PLY size'
tri_ply = []
for i in range(nf):
    k, a, b, c = struct.unpack_from('<B3i', ply, off + 13 * i)
    assert k == 3 and 0 <= min(a, b, c) and max(a, b, c) < nv
    tri_ply.append(tuple(v[3 * a:3 * a + 3] + v[3 * b:3 * b + 3] + v[3 * c:3 * c + 3]))
assert tri_ply == tri_stl, 'PLY and STL triangles differ'
ov, of = [], []
for line in obj.decode().split('\n'):
    w = line.split()
    if w and w[0] == 'v': ov.append(tuple(struct.unpack('<f', struct.pack('<f', float(x)))[0] for x in w[1:4]))
    elif w and w[0] == 'f': of.append(tuple(int(x) - 1 for x in w[1:4]))
assert len(ov) == nv and len(of) == nf, 'OBJ counts'
tri_obj = [ov[a] + ov[b] + ov[c] for a, b, c in of]
assert tri_obj == tri_stl, 'OBJ and STL triangles differ'
print('same %d triangles, %d vertices' % (n, nv))
PYEOF
then ok "PLY and OBJ hold the STL's triangles in the same order and winding ($(cat "$T/fmt.out"))"
else notok "PLY/OBJ against STL: $(tail -1 "$T/fmt.out")"; fi

# 2b. the bench's Hausdorff measure (tests/bench/skimage_mc.py) on a mesh worked out by hand: the
# octahedron of the unit points on the axes, inscribed in the unit sphere, is 1 - 1/sqrt(3) =
# 0.42265 from it both ways (at the face centres, and the sphere points above them)
$PY - "$T/octa.ply" <<'PYEOF'
import struct, sys
v = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
f = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
h = ("ply\nformat binary_little_endian 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
     "property float z\nelement face 8\nproperty list uchar int vertex_indices\nend_header\n").encode()
open(sys.argv[1], "wb").write(h + b"".join(struct.pack("<3f", *p) for p in v) + b"".join(struct.pack("<B3i", 3, *t) for t in f))
PYEOF
$PY tests/bench/skimage_mc.py hausdorff sphere "$T/octa.ply" > "$T/octa.h" 2>&1
hd=$(stat hausdorff "$T/octa.h") hm=$(stat h_mesh_to_surface "$T/octa.h") hs=$(stat h_surface_to_mesh "$T/octa.h")
within "$hd" 0.422650 0.1 && within "$hm" 0.422650 0.1 && within "$hs" 0.422650 0.1 \
	&& ok "Hausdorff measure of the inscribed octahedron: $hd ($hm, $hs; exact 0.42265)" || notok "octahedron Hausdorff: $(cat "$T/octa.h")"

# 3. the wireframe page: valid meta, its ink on the ray-traced silhouette of the same object
S=fixtures/mesh/mesh-trifocal.scene
if "$R" "$S" -o "$T/w.meta" --quiet && "$BIN/locus-meta" check "$T/w.meta" > /dev/null 2>&1 \
	&& "$BIN/locus-raster" "$T/w.meta" -o "$T/w.ppm"; then
	ok "mesh wireframe renders and passes locus-meta check"
	$PY - "$T/w-001.ppm" "$T/w-002.ppm" > "$T/sil.out" 2>&1 <<'PYEOF'
import sys
def ppm(p):
    d = open(p, 'rb').read().split(b'\n', 3)
    w, h = map(int, d[1].split())
    return w, h, d[3]
w, h, wire = ppm(sys.argv[1])
_, _, rt = ppm(sys.argv[2])
ink = {(i % w, i // w) for i in range(w * h) if wire[3 * i:3 * i + 3] != b'\xff\xff\xff'}
sil = {(i % w, i // w) for i in range(w * h) if rt[3 * i:3 * i + 3] != b'\xff\xff\xff'}
near = {(x + dx, y + dy) for x, y in sil for dx in (-2, -1, 0, 1, 2) for dy in (-2, -1, 0, 1, 2)}
outside = len(ink - near)
box = lambda s: (min(p[0] for p in s), min(p[1] for p in s), max(p[0] for p in s), max(p[1] for p in s))
bi, bs = box(ink), box(sil)
d = max(abs(a - b) for a, b in zip(bi, bs))
print('ink %d px, %d outside the silhouette, bounding boxes %s %s' % (len(ink), outside, bi, bs))
sys.exit(0 if outside == 0 and d <= 2 and len(ink) > 5000 else 1)
PYEOF
	[ $? = 0 ] && ok "wireframe lies on the ray-traced silhouette: $(cat "$T/sil.out")" || notok "wireframe vs silhouette: $(cat "$T/sil.out")"
else
	notok "mesh wireframe scene"
fi

# 4. bad input: one located line, exit 65 (74 for I/O), no output file
bad() {   # bad DESC EXIT PATTERN SCENE-TEXT
	printf '%s\n' "$4" > "$T/bad.scene"
	rm -f "$T/bad.stl"
	"$R" "$T/bad.scene" -o "$T/bad.stl" --quiet 2> "$T/bad.err"
	r=$?
	if [ "$r" = "$2" ] && [ "$(wc -l < "$T/bad.err")" = 1 ] && grep -q "$3" "$T/bad.err" && [ ! -e "$T/bad.stl" ]; then
		ok "$1: $(cat "$T/bad.err")"
	else
		notok "$1: exit $r, $(cat "$T/bad.err"), output $(ls "$T/bad.stl" 2>/dev/null)"
	fi
}
OBJ='object b
  point 0 0 0
  c 1
end'
bad "mesh depth 11" 65 "bad.scene:5:1: expected a mesh depth from 1 to 10" "$OBJ
render mesh
  depth 11
end"
# a scene of shape blocks only is refused by the scene language itself (issue 13's "an empty
# scene is an error"), before the mesh is tried
bad "nothing drawn" 65 "bad.scene:1:1: expected an 'object' block or a 'render' block" 'shape b
  point 0 0 0
  c 1
end'
bad "empty shape" 65 "bad.scene:6:1: the mesh is empty: no drawn object" 'object b
  point 1 0 0
  point -1 0 0
  c 1.5
end
render mesh
end'
bad "hidden takes yes or no" 65 "bad.scene:6:10: expected yes or no" "$OBJ
render mesh
  hidden maybe
end"
bad "negative tolerance" 65 "bad.scene:6:3: expected a tolerance of 0" "$OBJ
render mesh
  tolerance -1
end"
bad "hidden only in a mesh block" 65 "bad.scene:6:3: expected a render option" "$OBJ
render wireframe
  hidden no
end"
"$R" fixtures/mesh/sphere.scene -o "$T/no/such/dir/x.stl" 2> "$T/io.err"
[ $? = 74 ] && [ "$(wc -l < "$T/io.err")" = 1 ] && ok "unwritable mesh output: exit 74, $(cat "$T/io.err")" \
	|| notok "unwritable mesh output: $(cat "$T/io.err")"
"$R" fixtures/mesh/sphere.scene -o /dev/full 2> "$T/full.err"
[ $? = 74 ] && ok "mesh to /dev/full: exit 74" || notok "mesh to /dev/full: $(cat "$T/full.err")"
# 4. a distance-estimated shape (the Mandelbrot solid, no Lipschitz bound): admesh finds its
# mesh closed, consistently oriented, one part; coarsening it is refused at the tolerance line
if "$R" fixtures/mesh/mandelbrot.scene -o "$T/mandel.stl" --stats 2> "$T/mandel.stats" && command -v admesh > /dev/null; then
	admesh "$T/mandel.stl" > "$T/mandel.admesh" 2>&1
	bad=$(admesh_defects "$T/mandel.admesh")
	[ -z "$bad" ] && [ "$(admesh_field "$T/mandel.admesh" "Number of parts")" = 1 ] \
		&& ok "mandelbrot (distance estimate): admesh: $(stat triangles "$T/mandel.stats") triangles, one part, closed, consistently oriented" \
		|| notok "mandelbrot: admesh:$bad"
else
	notok "mandelbrot mesh: $(tail -1 "$T/mandel.stats")"
fi
sed '$d' fixtures/mesh/mandelbrot.scene > "$T/mtol.scene"   # the mesh block without its end
printf '  tolerance 1e-3\nend\n' >> "$T/mtol.scene"
rm -f "$T/mtol.stl"
"$R" "$T/mtol.scene" -o "$T/mtol.stl" 2> "$T/mtol.err"
rc=$?
[ "$rc" = 65 ] && grep -q "mtol.scene:8:1: expected tolerance 0 for a distance-estimated shape" "$T/mtol.err" && [ ! -e "$T/mtol.stl" ] \
	&& ok "coarsening a distance-estimated shape is refused at its render block: $(cat "$T/mtol.err")" \
	|| notok "mandelbrot tolerance: exit $rc: $(cat "$T/mtol.err")"
# 5. the solid as tetrahedra (-o X.msh, Gmsh MSH 2.2 ASCII), read back by awk from the format
# alone: every tetrahedron positively oriented, every face shared by exactly two tetrahedra or
# on the boundary, the boundary closed (each of its edges in two boundary faces), the volume
# within 0.5% of the analytic sphere's and ellipsoid's
msh_check() {   # FILE: prints "tets= neg= flat= volume= inner= boundary= over= open_edges="
	awk '
	/^\$Nodes/ { mode = 1; getline; next }
	/^\$EndNodes/ { mode = 0; next }
	/^\$Elements/ { mode = 2; getline; next }
	/^\$EndElements/ { mode = 0; next }
	mode == 1 { x[$1] = $2; y[$1] = $3; z[$1] = $4; next }
	mode == 2 && $2 == 4 {
		a = $6; b = $7; c = $8; d = $9; n++
		ux = x[b] - x[a]; uy = y[b] - y[a]; uz = z[b] - z[a]
		vx = x[c] - x[a]; vy = y[c] - y[a]; vz = z[c] - z[a]
		wx = x[d] - x[a]; wy = y[d] - y[a]; wz = z[d] - z[a]
		v = (ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx)) / 6
		vol += v; neg += v < 0; flat += v == 0
		f[1] = b " " c " " d; f[2] = a " " c " " d; f[3] = a " " b " " d; f[4] = a " " b " " c
		for (k = 1; k <= 4; k++) print f[k] > "/dev/stderr"
	}
	END { printf "tets=%d neg=%d flat=%d volume=%.9g\n", n, neg, flat, vol }' "$1" 2> "$1.faces" |
		tr '\n' ' '
	# faces sorted by their vertex numbers, counted; boundary faces' edges counted
	awk '{ if ($1 > $2) { t = $1; $1 = $2; $2 = t } if ($2 > $3) { t = $2; $2 = $3; $3 = t } if ($1 > $2) { t = $1; $1 = $2; $2 = t } print }' "$1.faces" |
		sort | uniq -c | awk '
		{ c[$1 > 2 ? 3 : $1]++ } $1 == 1 { print $2, $3 > "/dev/stderr"; print $2, $4 > "/dev/stderr"; print $3, $4 > "/dev/stderr" }
		END { printf "inner=%d boundary=%d over=%d ", c[2], c[1], c[3] }' 2> "$1.bedges"
	sort "$1.bedges" | uniq -c | awk '$1 != 2 { o++ } END { printf "open_edges=%d\n", o }'
}
# same_volume NAME STATS: the solid's volume is the surface's, to rounding (1e-9 relative)
same_volume() {
	sv=$(stat solid_volume "$2") v=$(stat volume "$2")
	awk -v a="$sv" -v b="$v" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && d <= 1e-9 * b) }' &&
		ok "$1: solid volume $sv = surface volume $v" || notok "$1: solid volume $sv, surface volume $v"
}
# msh_gamma FILE: prints "worst W below FRACTION%": the tetrahedra's shape quality 3 r_in / r_circ
# (1 for the regular tetrahedron, 0 for a flat one; Gmsh's gamma)
msh_gamma() {
	awk '
	function cr(ax, ay, az, bx, by, bz) { X = ay * bz - az * by; Y = az * bx - ax * bz; Z = ax * by - ay * bx }
	function area(ax, ay, az, bx, by, bz) { cr(ax, ay, az, bx, by, bz); return sqrt(X * X + Y * Y + Z * Z) / 2 }
	/^\$Nodes/ { mode = 1; getline; next }
	/^\$EndNodes/ { mode = 0; next }
	/^\$Elements/ { mode = 2; getline; next }
	/^\$EndElements/ { mode = 0; next }
	mode == 1 { x[$1] = $2; y[$1] = $3; z[$1] = $4; next }
	mode == 2 && $2 == 4 {
		p = $6; q = $7; r = $8; s = $9
		ax = x[q] - x[p]; ay = y[q] - y[p]; az = z[q] - z[p]
		bx = x[r] - x[p]; by = y[r] - y[p]; bz = z[r] - z[p]
		cx = x[s] - x[p]; cy = y[s] - y[p]; cz = z[s] - z[p]
		cr(bx, by, bz, cx, cy, cz); det = ax * X + ay * Y + az * Z
		a2 = ax * ax + ay * ay + az * az; b2 = bx * bx + by * by + bz * bz; c2 = cx * cx + cy * cy + cz * cz
		nx = a2 * X; ny = a2 * Y; nz = a2 * Z
		cr(cx, cy, cz, ax, ay, az); nx += b2 * X; ny += b2 * Y; nz += b2 * Z
		cr(ax, ay, az, bx, by, bz); nx += c2 * X; ny += c2 * Y; nz += c2 * Z
		A = area(ax, ay, az, bx, by, bz) + area(ax, ay, az, cx, cy, cz) + area(bx, by, bz, cx, cy, cz) + \
			area(bx - ax, by - ay, bz - az, cx - ax, cy - ay, cz - az)
		g = det <= 0 ? 0 : 3 * (det / (2 * A)) / (sqrt(nx * nx + ny * ny + nz * nz) / (2 * det))
		n++; lo += g < 0.01; if (n == 1 || g < w) w = g
	}
	END { printf "worst %.3g below %.2f\n", w, n ? 100 * lo / n : 100 }' "$1"
}
for c in "sphere 4.18879020" "ellipsoid 4.02123859"; do
	set -- $c
	n=$1 vol=$2
	sed 's/^  depth .*/  depth 5/' "fixtures/mesh/$n.scene" > "$T/$n-solid.scene"
	if ! "$R" "$T/$n-solid.scene" -o "$T/$n.msh" --stats 2> "$T/$n-solid.stats"; then
		notok "$n: -o $n.msh: $(tail -1 "$T/$n-solid.stats")"; continue
	fi
	head -2 "$T/$n.msh" | tail -1 | grep -q '^2.2 0 8$' && ok "$n.msh: Gmsh MSH 2.2 ASCII" || notok "$n.msh: header $(head -2 "$T/$n.msh")"
	r=$(msh_check "$T/$n.msh")
	v=$(echo "$r" | sed -n 's/.*volume=\([^ ]*\).*/\1/p')
	case "$r" in
	*" neg=0 flat=0 "*" over=0 open_edges=0"*) ok "$n.msh read back: $r" ;;
	*) notok "$n.msh read back: $r" ;;
	esac
	within "$v" "$vol" 0.5 && ok "$n.msh: volume $v within 0.5% of $vol" || notok "$n.msh: volume '$v', exact $vol"
	[ "$(echo "$r" | sed -n 's/.*boundary=\([0-9]*\).*/\1/p')" = "$(stat triangles "$T/$n-solid.stats")" ] &&
		ok "$n.msh: as many boundary faces as the surface has triangles" || notok "$n.msh: boundary faces against $(stat triangles "$T/$n-solid.stats") triangles"
	same_volume "$n.msh" "$T/$n-solid.stats"
	msh_gamma "$T/$n.msh" > "$T/$n.gamma"
	set -- $(cat "$T/$n.gamma")
	# what holds (docs/mesh.md): no tetrahedron flatter than gamma 1e-4 (measured worst at depth
	# 5: 7.6e-4 sphere, 6.6e-4 ellipsoid), at most 2% below 0.01 (measured 0.14%, 1.10%); the
	# slivers are cut pieces of Kuhn tetrahedra whose crossings lie near a grid corner
	awk -v w="$2" -v f="$4" 'BEGIN { exit !(w >= 1e-4 && f <= 2) }' &&
		ok "$n.msh: shape quality (3 r_in / r_circ) worst $2, $4% below 0.01" ||
		notok "$n.msh: shape quality worst $2, $4% below 0.01 (bounds 1e-4, 2%)"
	if command -v gmsh >/dev/null 2>&1; then
		bounded 120 "gmsh -check $n.msh" gmsh "$T/$n.msh" -check > "$T/$n.gmsh" 2>&1
		grep -q "Done checking mesh coherence" "$T/$n.gmsh" && ! grep -q -E "^(Error|Warning)" "$T/$n.gmsh" &&
			ok "$n.msh: gmsh $(gmsh --version 2>&1 | tail -1) reads it and finds it coherent" ||
			notok "$n.msh: gmsh -check: $(grep -E '^(Error|Warning)' "$T/$n.gmsh" | head -1)"
	else
		skip "gmsh not installed (Debian gmsh): $n.msh not read by Gmsh itself"
	fi
done
# the solid's boundary is the surface mesh itself (the surface's quadrilaterals cut along the
# same diagonal): the two volumes agree to rounding, also on the coarse trifocal ellipsoid of
# the gallery (depth 4), where they differed by 0.067% before
"$R" fixtures/mesh/mesh-trifocal.scene -o "$T/tri.msh" --stats 2> "$T/tri.stats" || notok "mesh-trifocal -o tri.msh: $(tail -1 "$T/tri.stats")"
same_volume "mesh-trifocal.msh (depth 4)" "$T/tri.stats"
sed '$d' fixtures/mesh/sphere.scene > "$T/stol.scene"
printf '  tolerance 1e-3\nend\n' >> "$T/stol.scene"
rm -f "$T/stol.msh"
"$R" "$T/stol.scene" -o "$T/stol.msh" 2> "$T/stol.err"
[ $? = 65 ] && grep -q "expected tolerance 0 for a solid" "$T/stol.err" && [ ! -e "$T/stol.msh" ] \
	&& ok "a coarsened solid is refused: $(cat "$T/stol.err")" || notok "solid with tolerance: $(cat "$T/stol.err")"
# 6. adaptive extraction: the rounded box's flat faces in coarse cells, its rounded edges fine;
# admesh finds it closed across every change of cell size, with the analytic volume and area,
# and with fewer triangles than the uniform marching tetrahedra of the same depth (it cuts its
# cells into tetrahedra too; uniform marching cubes make fewer triangles than either)
S=fixtures/mesh/rbox-adaptive.scene
if "$R" "$S" -o "$T/rbox.stl" --stats 2> "$T/rbox.stats" &&
	sed -e '/adaptive/d' -e 's/^render mesh$/render mesh\n  method tetrahedra/' "$S" > "$T/rbox-u.scene" &&
	"$R" "$T/rbox-u.scene" -o "$T/rbox-u.stl" --stats 2> "$T/rbox-u.stats" && command -v admesh > /dev/null; then
	admesh "$T/rbox.stl" > "$T/rbox.admesh" 2>&1
	bad=$(admesh_defects "$T/rbox.admesh")
	[ -z "$bad" ] && [ "$(admesh_field "$T/rbox.admesh" "Number of parts")" = 1 ] \
		&& ok "adaptive rounded box: admesh: one part, closed, consistently oriented" || notok "adaptive rounded box: admesh:$bad"
	v=$(sed -n 's/.*Volume *: *\([0-9.]*\).*/\1/p' "$T/rbox.admesh")
	within "$v" 7.26164 0.5 && ok "adaptive rounded box: admesh volume $v within 0.5% of 7.26164" || notok "adaptive rounded box: volume '$v'"
	a=$(stat area "$T/rbox.stats")
	within "$a" 19.69841 0.5 && ok "adaptive rounded box: area $a within 0.5% of 19.69841" || notok "adaptive rounded box: area '$a'"
	ta=$(stat triangles "$T/rbox.stats") tu=$(stat triangles "$T/rbox-u.stats")
	[ $((ta * 10)) -lt $((tu * 8)) ] && ok "adaptive rounded box: $ta triangles, uniform depth 7: $tu" \
		|| notok "adaptive rounded box: $ta triangles against $tu uniform"
else
	notok "adaptive rounded box: $(tail -1 "$T/rbox.stats")"
fi
done_tests

# mesh.sh: bench group "mesh" (sourced by scripts/bench.sh): locus-render polygonising a sphere and
# the two-focus ellipsoid at depth 7 (129^3 grid points over [-1.25, 1.25]^3), as extracted and
# coarsened within 1e-4, against
# scikit-image's marching_cubes on the same grid (tests/bench/skimage_mc.py, Debian
# python3-skimage run by /usr/bin/python3). One BENCH line per shape and tolerance: the in-process times of both
# (field evaluation plus extraction; Locus' from --stats mesh_ms; medians of rounds of one anchor
# run and one run of each Locus variant), the whole commands'
# wall times (locus-render writing the PLY; python3 starting, importing, evaluating, extracting),
# triangle counts and the
# Hausdorff distance of each mesh to the exact surface, measured by the same script
# (docs/benchmarks.md, docs/mesh.md). Targets (issue 26): as extracted, at least 2x the anchor's
# in-process time with no more triangles and no worse a Hausdorff distance; within 1e-4, at
# least 1x with no more triangles (pass=, fails= names the ones missed). Then the adaptive
# extraction of a rounded box against the uniform one of the same depth (mesh_adaptive below).

bench_mesh() {
	if ! have_bin locus-render; then skip mesh "$BIN/locus-render not built yet"; return; fi
	MESH_PY=/usr/bin/python3
	[ -x "$MESH_PY" ] || MESH_PY=python3
	if ! "$MESH_PY" -c "import skimage.measure, scipy.spatial" 2> /dev/null; then
		fail mesh "scikit-image or scipy missing (Debian python3-skimage python3-scipy)"; return
	fi
	for shape in sphere ellipsoid; do
		n=mesh-$shape-d7
		if [ "$shape" = sphere ]; then els="  point 0 0 0
  c 1"; else els="  point 0.8 0 0
  point -0.8 0 0
  c 2.4"; fi
		# Locus as extracted, and coarsened within 1e-4 (about the chord error of this grid)
		for tol in 0 1e-4; do
			ln=$n
			[ "$tol" = 0 ] || ln=$n-tol$tol
			printf 'object %s\n%s\n  bound -1.25 -1.25 -1.25 1.25 1.25 1.25\nend\nrender mesh\n  depth 7\n  tolerance %s\nend\n' \
				"$shape" "$els" "$tol" > "$W/$ln.scene"
			: > "$W/$ln.errs"
			: > "$W/$ln.walls"
			: > "$W/$ln.mibs"
		done
		# rounds of one anchor run (its in-process time) and one run of each Locus variant, so
		# that a change of load on the shared machine hits both sides alike
		: > "$W/$n.as"
		: > "$W/$n.amibs"
		ERR="" i=0
		while [ "$i" -lt "$SLOW_RUNS" ] && [ -z "$ERR" ]; do
			if ! measure 1 "$W/$n.anchor" "$MESH_PY" tests/bench/skimage_mc.py anchor "$shape" 7 -n 1 ||
				! own_line "$W/$n.anchor" "mesh-skimage-$shape"; then
				ERR="skimage_mc.py anchor: ${M_ERR:-no BENCH line}"; break
			fi
			echo "$O_S" >> "$W/$n.as"
			echo "$M_MIB" >> "$W/$n.amibs"
			for tol in 0 1e-4; do
				ln=$n
				[ "$tol" = 0 ] || ln=$n-tol$tol
				if ! measure 1 /dev/null "$BIN/locus-render" "$W/$ln.scene" -o "$W/$ln.ply" --stats; then
					ERR="$ln: $M_ERR"; break
				fi
				cat "$W/err" >> "$W/$ln.errs"
				echo "$M_S" >> "$W/$ln.walls"
				echo "$M_MIB" >> "$W/$ln.mibs"
			done
			i=$((i + 1))
		done
		if [ -n "$ERR" ]; then fail "$n" "$ERR"; continue; fi
		a_s=$(awk -v s="$(median "$W/$n.as")" 'BEGIN {printf "%.4f", s}')
		a_kv=$(echo "$O_KV" | sed 's/\([a-z_]*\)=/anchor_\1=/g')
		a_tri=$(echo "$O_KV" | sed -n 's/.*triangles=\([0-9]*\).*/\1/p')
		a_h=$(echo "$O_KV" | sed -n 's/.*hausdorff=\([0-9.e+-]*\).*/\1/p')
		a_mib=$(median "$W/$n.amibs")
		# the whole command, as a user runs it: interpreter start-up, imports, field, extraction
		if ! SKIMAGE_MC_ONCE=1 measure "$SLOW_RUNS" /dev/null "$MESH_PY" tests/bench/skimage_mc.py anchor "$shape" 7; then
			fail "$n" "skimage_mc.py once: $M_ERR"; continue
		fi
		a_wall=$M_S
		for tol in 0 1e-4; do
			ln=$n
			[ "$tol" = 0 ] || ln=$n-tol$tol
			l_wall=$(median "$W/$ln.walls") l_mib=$(median "$W/$ln.mibs")
			l_ms=$(stat_med mesh_ms "$W/$ln.errs")
			l_s=$(awk -v m="${l_ms:-0}" 'BEGIN {printf "%.4f", m / 1000}')
			l_tri=$(stat triangles "$W/$ln.errs")
			l_evals=$(stat evals "$W/$ln.errs")
			if ! "$MESH_PY" tests/bench/skimage_mc.py hausdorff "$shape" "$W/$ln.ply" > "$W/$ln.h" 2>&1; then
				fail "$ln" "skimage_mc.py hausdorff: $(tail -1 "$W/$ln.h")"; continue
			fi
			l_h=$(stat hausdorff "$W/$ln.h")
			# issue 26: 2x the anchor as extracted, 1x coarsened within 1e-4, never more
			# triangles; as extracted also a Hausdorff distance no worse than the anchor's
			tgt=2
			[ "$tol" = 0 ] || tgt=1
			mesh_fails=$(awk -v r="$(ratio "$a_s" "$l_s")" -v t="$tgt" -v lt="${l_tri:-x}" -v at="${a_tri:-0}" \
				-v lh="${l_h:-x}" -v ah="${a_h:-0}" -v tol="$tol" 'BEGIN {
				f = ""
				if (r == "inf" ? 0 : r + 0 < t) f = f ",ratio"
				if (lt !~ /^[0-9]+$/ || lt + 0 > at + 0) f = f ",triangles"
				if (tol == 0 && (lh !~ /^[0-9.e+-]+$/ || lh + 0 > ah + 0)) f = f ",hausdorff"
				print f == "" ? "pass=yes" : "pass=no fails=" substr(f, 2) }')
			line "$ln" "$l_s" skimage-marching_cubes "$a_s" "$l_mib" "$a_mib" \
				"grid=129 tolerance=$tol locus_wall_s=$l_wall anchor_wall_s=$a_wall ratio_wall=$(ratio "$a_wall" "$l_wall")" \
				"locus_triangles=$l_tri locus_evals=$l_evals" \
				"locus_hausdorff=$l_h locus_h_mesh_to_surface=$(stat h_mesh_to_surface "$W/$ln.h")" \
				"locus_h_surface_to_mesh=$(stat h_surface_to_mesh "$W/$ln.h") $a_kv" \
				"target_ratio=$tgt target_triangles=${a_tri:-na}$([ "$tol" = 0 ] && echo " target_hausdorff=${a_h:-na}") $mesh_fails" \
				"rss_note=whole_process time_note=in_process_field_and_extraction"
		done
	done
	mesh_adaptive
}

# The rounded box (fixtures/mesh/rbox-adaptive.scene: flat faces, rounded edges and corners) at
# depth 7, adaptive within 3e-4 against the uniform extraction of the same depth: both Hausdorff
# distances to the exact surface (skimage_mc.py's measure, its shape functions replaced by the
# rounded box's exact distance |d_box(P) - 0.4| and points spread over its faces, edges and
# corners), triangle counts, in-process times (medians of mesh_ms). One BENCH line: Locus
# adaptive against Locus uniform marching tetrahedra (anchor=locus-uniform), with the uniform
# marching cubes' triangle count beside them.
mesh_adaptive() {
	n=mesh-rbox-adaptive-d7
	S=fixtures/mesh/rbox-adaptive.scene
	# like for like: the adaptive extraction cuts its cells into tetrahedra, so the uniform one
	# it is measured against does too (method tetrahedra); uniform cubes' count is beside it
	sed -e '/adaptive/d' -e 's/^render mesh$/render mesh\n  method tetrahedra/' "$S" > "$W/$n-u.scene"
	sed '/adaptive/d' "$S" > "$W/$n-c.scene"
	"$BIN/locus-render" "$W/$n-c.scene" -o "$W/$n-c.ply" --stats 2> "$W/$n-c.err"
	tri_c=$(stat triangles "$W/$n-c.err")
	cat > "$W/rbox_h.py" <<'PY'
import sys
sys.path.insert(0, "tests/bench")
import numpy as np
import skimage_mc as sk
B, R = 0.6, 0.4
def dist_surface(shape, p):
    q = np.abs(p) - B
    return np.abs(np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0) - R)
def surface_points(shape, n=200000):
    rng = np.random.default_rng(1)
    af, ae, ac = 6 * (2 * B) ** 2, 12 * 2 * B * np.pi * R / 2, 4 * np.pi * R * R
    nf, ne = int(n * af / (af + ae + ac)), int(n * ae / (af + ae + ac))
    nc = n - nf - ne
    u, a, s = rng.uniform(-B, B, (nf, 2)), rng.integers(0, 3, nf), rng.choice([-1.0, 1.0], nf)
    F = np.zeros((nf, 3))
    F[np.arange(nf), a] = s * (B + R)
    F[np.arange(nf), (a + 1) % 3], F[np.arange(nf), (a + 2) % 3] = u[:, 0], u[:, 1]
    a, t, th = rng.integers(0, 3, ne), rng.uniform(-B, B, ne), rng.uniform(0, np.pi / 2, ne)
    s1, s2 = rng.choice([-1.0, 1.0], ne), rng.choice([-1.0, 1.0], ne)
    E = np.zeros((ne, 3))
    E[np.arange(ne), a] = t
    E[np.arange(ne), (a + 1) % 3] = s1 * (B + R * np.cos(th))
    E[np.arange(ne), (a + 2) % 3] = s2 * (B + R * np.sin(th))
    v = rng.normal(size=(nc, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    return np.concatenate([F, E, np.sign(v) * B + v * R])
sk.dist_surface, sk.surface_points = dist_surface, surface_points
h, hms, hsm = sk.hausdorff("rbox", *sk.read_ply(sys.argv[1]))
print("HAUSDORFF hausdorff=%.4g h_mesh_to_surface=%.4g h_surface_to_mesh=%.4g" % (h, hms, hsm))
PY
	for v in u a; do
		sc=$S
		[ "$v" = u ] && sc=$W/$n-u.scene
		if ! measure "$SLOW_RUNS" /dev/null "$BIN/locus-render" "$sc" -o "$W/$n-$v.ply" --stats; then
			fail "$n" "$M_ERR"; return
		fi
		if [ "$v" = u ]; then
			ms_u=$(stat_med mesh_ms "$W/errs") tri_u=$(stat triangles "$W/err") mib_u=$M_MIB
		else
			ms_a=$(stat_med mesh_ms "$W/errs") tri_a=$(stat triangles "$W/err") mib_a=$M_MIB
		fi
		if ! "$MESH_PY" "$W/rbox_h.py" "$W/$n-$v.ply" > "$W/$n-$v.h" 2>&1; then
			fail "$n" "hausdorff: $(tail -1 "$W/$n-$v.h")"; return
		fi
	done
	l_s=$(awk -v m="${ms_a:-0}" 'BEGIN {printf "%.4f", m / 1000}')
	a_s=$(awk -v m="${ms_u:-0}" 'BEGIN {printf "%.4f", m / 1000}')
	line "$n" "$l_s" locus-uniform "$a_s" "$mib_a" "$mib_u" "depth=7 adaptive=3e-4" \
		"locus_triangles=$tri_a anchor_triangles=$tri_u ratio_triangles=$(ratio "$tri_u" "$tri_a")" \
		"locus_hausdorff=$(stat hausdorff "$W/$n-a.h") anchor_hausdorff=$(stat hausdorff "$W/$n-u.h")" \
		"anchor_method=tetrahedra uniform_cubes_triangles=${tri_c:-na}" \
		"time_note=in_process_field_and_extraction"
}

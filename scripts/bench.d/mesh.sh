# mesh.sh: bench group "mesh" (sourced by scripts/bench.sh): locus-render polygonising a sphere and
# the two-focus ellipsoid at depth 7 (129^3 grid points over [-1.25, 1.25]^3), as extracted and
# coarsened within 1e-4, against
# scikit-image's marching_cubes on the same grid (tests/bench/skimage_mc.py, Debian
# python3-skimage run by /usr/bin/python3). One BENCH line per shape and tolerance: the in-process times of both
# (field evaluation plus extraction; Locus' from --stats mesh_ms, medians), the whole commands'
# wall times (locus-render writing the PLY; python3 starting, importing, evaluating, extracting),
# triangle counts and the
# Hausdorff distance of each mesh to the exact surface, measured by the same script
# (docs/benchmarks.md, docs/mesh.md).

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
		# the anchor once (its own median of SLOW_RUNS runs), for both Locus lines
		if ! measure 1 "$W/$n.anchor" "$MESH_PY" tests/bench/skimage_mc.py anchor "$shape" 7 -n "$SLOW_RUNS" ||
			! own_line "$W/$n.anchor" "mesh-skimage-$shape"; then
			fail "$n" "skimage_mc.py anchor: ${M_ERR:-no BENCH line}"; continue
		fi
		a_s=$(awk -v s="$O_S" 'BEGIN {printf "%.4f", s}')
		a_kv=$(echo "$O_KV" | sed 's/\([a-z_]*\)=/anchor_\1=/g')
		a_mib=$M_MIB
		# the whole command, as a user runs it: interpreter start-up, imports, field, extraction
		if ! SKIMAGE_MC_ONCE=1 measure "$SLOW_RUNS" /dev/null "$MESH_PY" tests/bench/skimage_mc.py anchor "$shape" 7; then
			fail "$n" "skimage_mc.py once: $M_ERR"; continue
		fi
		a_wall=$M_S
		# Locus as extracted, and coarsened within 1e-4 (about the chord error of this grid)
		for tol in 0 1e-4; do
			ln=$n
			[ "$tol" = 0 ] || ln=$n-tol$tol
			printf 'object %s\n%s\n  bound -1.25 -1.25 -1.25 1.25 1.25 1.25\nend\nrender mesh\n  depth 7\n  tolerance %s\nend\n' \
				"$shape" "$els" "$tol" > "$W/$ln.scene"
			if ! measure "$SLOW_RUNS" /dev/null "$BIN/locus-render" "$W/$ln.scene" -o "$W/$ln.ply" --stats; then
				fail "$ln" "$M_ERR"; continue
			fi
			l_wall=$M_S l_mib=$M_MIB
			l_ms=$(stat_med mesh_ms "$W/errs")
			l_s=$(awk -v m="${l_ms:-0}" 'BEGIN {printf "%.4f", m / 1000}')
			l_tri=$(stat triangles "$W/err")
			l_evals=$(stat evals "$W/err")
			if ! "$MESH_PY" tests/bench/skimage_mc.py hausdorff "$shape" "$W/$ln.ply" > "$W/$ln.h" 2>&1; then
				fail "$ln" "skimage_mc.py hausdorff: $(tail -1 "$W/$ln.h")"; continue
			fi
			line "$ln" "$l_s" skimage-marching_cubes "$a_s" "$l_mib" "$a_mib" \
				"grid=129 tolerance=$tol locus_wall_s=$l_wall anchor_wall_s=$a_wall ratio_wall=$(ratio "$a_wall" "$l_wall")" \
				"locus_triangles=$l_tri locus_evals=$l_evals" \
				"locus_hausdorff=$(stat hausdorff "$W/$ln.h") locus_h_mesh_to_surface=$(stat h_mesh_to_surface "$W/$ln.h")" \
				"locus_h_surface_to_mesh=$(stat h_surface_to_mesh "$W/$ln.h") $a_kv" \
				"rss_note=whole_process time_note=in_process_field_and_extraction"
		done
	done
}

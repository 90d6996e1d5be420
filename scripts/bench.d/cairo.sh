# cairo.sh: bench group "cairo" (sourced by scripts/bench.sh): locus-raster against cairo's image
# surface (tests/bench/cairo_anchor.c) on workloads a, b and c (text input, PPM output,
# 1024x768), exact mode against CAIRO_ANTIALIAS_NONE and --antialias (4 x 4, linear light)
# against cairo's default anti-aliasing, in alternating rounds of the same run.
# Lines: cairo-W (exact; target 2: at least twice as fast) and cairo-aa-W (target 1: faster).
# Extra keys: the percentage of pixels where the two pictures differ, their PSNR (dB), and the
# one-minute load average when the line was written (load1).

# cairo_img: build the anchor into $W/cairo_anchor unless the ps group already did
cairo_img() {
	[ -x "$W/cairo_anchor" ] && return 0
	pkg-config --exists cairo 2> /dev/null || { B_ERR="cairo missing (Debian libcairo2-dev)"; return 1; }
	# shellcheck disable=SC2046,SC2086
	$CC $BCFLAGS $(pkg-config --cflags cairo) "-DLOCUS_VERSION=\"$VERSION\"" tests/bench/cairo_anchor.c \
		$BLIBS $(pkg-config --libs cairo) $BLDLIBS -o "$W/cairo_anchor" 2> "$W/cairo_anchor.log" && return 0
	B_ERR="$(grep -m1 -E 'error|undefined' "$W/cairo_anchor.log" | cut -c1-160)"
	return 1
}

# bench_load: the one-minute load average (other work on the machine: wall-time ratios of a
# two-thread replay shrink when the cores are shared)
bench_load() { cut -d' ' -f1 /proc/loadavg 2> /dev/null || echo na; }

# cairo_psnr A B: ImageMagick's PSNR of two pictures (inf when equal, na when it cannot tell)
cairo_psnr() {
	compare -metric PSNR "$1" "$2" null: 2>&1 | awk '{v = $1} END {print (v ~ /^[0-9.]+$|^inf$/) ? v : "na"}'
}

bench_cairo() {
	if ! have_bin locus-raster; then
		skip cairo-a "$BIN/locus-raster not built yet"; return
	fi
	if ! cairo_img; then
		for wl in a b c; do skip "cairo-$wl" "no cairo anchor: $B_ERR"; done; return
	fi
	if [ ! -x "$W/gen_workloads" ] && ! build gen_workloads tests/bench/gen_workloads.c; then
		for wl in a b c; do skip "cairo-$wl" "gen_workloads does not build: $B_ERR"; done; return
	fi
	for wl in a b c; do
		if [ ! -f "$W/$wl.meta" ] && ! "$W/gen_workloads" "$wl" text -o "$W/$wl.meta" 2> "$W/gen.log"; then
			fail "cairo-$wl" "gen_workloads $wl text: $(tail -1 "$W/gen.log")"; continue
		fi
		# rounds of: locus exact, cairo NONE, locus --antialias, cairo default, so that a change
		# of load on the machine hits both sides alike
		for v in le cn la cd; do : > "$W/r.$v"; done
		ERR="" i=0
		while [ "$i" -lt "$BENCH_RUNS" ] && [ -z "$ERR" ]; do
			once le /dev/null "$BIN/locus-raster" "$W/$wl.meta" -o "$W/cairo-$wl-le.ppm"
			once cn /dev/null "$W/cairo_anchor" -s image -a none "$W/$wl.meta" -o "$W/cairo-$wl-cn.ppm"
			once la /dev/null "$BIN/locus-raster" --antialias "$W/$wl.meta" -o "$W/cairo-$wl-la.ppm"
			once cd /dev/null "$W/cairo_anchor" -s image -a default "$W/$wl.meta" -o "$W/cairo-$wl-cd.ppm"
			i=$((i + 1))
		done
		if [ -n "$ERR" ]; then fail "cairo-$wl" "$ERR"; continue; fi
		med "$W/r.cn"
		cn_s=$M_S cn_mib=$M_MIB cn_cpu=$M_CPU
		med "$W/r.le"
		r=$(ratio "$cn_s" "$M_S")
		line "cairo-$wl" "$M_S" cairo-antialias-none "$cn_s" "$M_MIB" "$cn_mib" "target=2 pass=$(pass "$r" 2)" \
			"runs=$BENCH_RUNS diff_pct=$(diffpct "$W/cairo-$wl-le.ppm" "$W/cairo-$wl-cn.ppm")" \
			"psnr_db=$(cairo_psnr "$W/cairo-$wl-le.ppm" "$W/cairo-$wl-cn.ppm") $(cpu "$M_CPU" "$cn_cpu") load1=$(bench_load)"
		med "$W/r.cd"
		cd_s=$M_S cd_mib=$M_MIB cd_cpu=$M_CPU
		med "$W/r.la"
		r=$(ratio "$cd_s" "$M_S")
		line "cairo-aa-$wl" "$M_S" cairo-antialias-default "$cd_s" "$M_MIB" "$cd_mib" "target=1 pass=$(pass "$r" 1)" \
			"runs=$BENCH_RUNS antialias=4 diff_pct=$(diffpct "$W/cairo-$wl-la.ppm" "$W/cairo-$wl-cd.ppm")" \
			"psnr_db=$(cairo_psnr "$W/cairo-$wl-la.ppm" "$W/cairo-$wl-cd.ppm") $(cpu "$M_CPU" "$cd_cpu") load1=$(bench_load)"
		rm -f "$W/cairo-$wl-"*.ppm
	done
}

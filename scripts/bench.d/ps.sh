# ps.sh: bench group "ps" (sourced by scripts/bench.sh): locus-ps against plot -T ps and cairo's
# PostScript and PDF surfaces on workloads a, b and c: replay time, peak memory, output size,
# and Ghostscript's time to interpret each output (and, with valgrind, its instruction counts on
# b and c: ratio_instr, which other load does not move); the sizes of a ray-traced picture.
#
# Lines: ps-W (locus-ps PS against plot -T ps and against cairo PS), pdf-W (locus-ps PDF against
# cairo PDF), gs-ps-W / gs-pdf-W (Ghostscript interpreting Locus' output against the anchor's:
# locus_s is gs on ours), ps-a-x4 (memory with 4x the input), ps-gallery (a ray-traced
# picture: locus-ps PDF against locus-raster PNG, and the sizes of PNG, EPS per level, PDF).
# Size keys: bytes (Locus), anchor_bytes, size_ratio = bytes / anchor_bytes (target <= 0.5).

# ps_cairo: build tests/bench/cairo_anchor.c against cairo into $W/cairo_anchor
ps_cairo() {
	pkg-config --exists cairo 2> /dev/null || { B_ERR="cairo missing (Debian libcairo2-dev)"; return 1; }
	# shellcheck disable=SC2086,SC2046
	$CC $BCFLAGS $(pkg-config --cflags cairo) "-DLOCUS_VERSION=\"$VERSION\"" tests/bench/cairo_anchor.c \
		$BLIBS $(pkg-config --libs cairo) $BLDLIBS -o "$W/cairo_anchor" 2> "$W/cairo_anchor.log" && return 0
	B_ERR="$(grep -m1 -E 'error|undefined' "$W/cairo_anchor.log" | cut -c1-160)"
	return 1
}

# ps_gs FILE: Ghostscript interprets and renders FILE at 96 dpi into nothing (medians in M_*)
ps_gs() {
	measure "$SLOW_RUNS" /dev/null gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=ppmraw -r96 -sOutputFile=/dev/null "$1"
}

# ps_gsi FILE: the instructions (millions) Ghostscript executes on FILE, counted by valgrind
# (cachegrind without its cache model): unlike times, not moved by other load on a shared
# machine. Sets G_I; empty when valgrind is missing or BENCH_PS_INSTR=0.
ps_gsi() {
	G_I=""
	[ "${BENCH_PS_INSTR:-1}" = 0 ] && return 0
	have valgrind || return 0
	G_I=$(valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file=/dev/null gs -q -dSAFER -dBATCH \
		-dNOPAUSE -sDEVICE=ppmraw -r96 -sOutputFile=/dev/null "$1" 2>&1 > /dev/null |
		sed -n 's/.*I *refs: *//p' | tr -d , | awk '{printf "%d", $1 / 1e6}')
}

# ps_instr LOCUS_FILE ANCHOR_FILE: key=values of Ghostscript's instructions on both (workloads b
# and c only: a takes minutes under valgrind); nothing when not counted
ps_instr() {
	[ "$wl" = a ] && return 0
	ps_gsi "$1"; p_li=$G_I
	ps_gsi "$2"; p_ai=$G_I
	[ -n "$p_li" ] && [ -n "$p_ai" ] && echo "locus_instr_m=$p_li anchor_instr_m=$p_ai ratio_instr=$(ratio "$p_ai" "$p_li")"
}

# ps_size_line NAME LOCUS_S ANCHOR ANCHOR_S LOCUS_MIB ANCHOR_MIB BYTES ANCHOR_BYTES [extra]
ps_size_line() {
	p_sr=$(awk -v a="$7" -v b="$8" 'BEGIN {printf "%.3f", a / b}')
	p_sp=$(awk -v r="$p_sr" 'BEGIN {print (r <= 0.5) ? "yes" : "no"}')
	p_r=$(ratio "$4" "$2")
	p_n=$1 p_ls=$2 p_an=$3 p_as=$4 p_lm=$5 p_am=$6 p_b=$7 p_ab=$8
	shift 8
	line "$p_n" "$p_ls" "$p_an" "$p_as" "$p_lm" "$p_am" "target=2 pass=$(pass "$p_r" 2)" \
		"bytes=$p_b anchor_bytes=$p_ab size_ratio=$p_sr size_pass=$p_sp${*:+ $*}"
}

bench_ps() {
	if ! have_bin locus-ps; then
		for wl in a b c; do skip "ps-$wl" "$BIN/locus-ps not built"; done
		return
	fi
	if ! have plot || ! have gs; then
		fail ps "plot (plotutils) or gs (ghostscript) missing"
		return
	fi
	if ! build gen_workloads tests/bench/gen_workloads.c; then
		skip ps "gen_workloads does not build: $B_ERR"
		return
	fi
	cai=1
	ps_cairo || { cai=0; echo "bench: ps: no cairo anchor: $B_ERR" >&2; }
	for wl in a b c; do
		"$W/gen_workloads" "$wl" binary -o "$W/ps-$wl.lmb" 2> "$W/gen.log" &&
			"$W/gen_workloads" "$wl" plot -o "$W/ps-$wl.plot" 2>> "$W/gen.log" ||
			{ fail "ps-$wl" "gen_workloads: $(tail -1 "$W/gen.log")"; continue; }
		ERR=""
		for v in lps lpdf plot cps cpdf; do : > "$W/r.$v"; done
		# rounds of every program in turn, so that a change of load hits all alike
		i=0
		while [ "$i" -lt "$SLOW_RUNS" ] && [ -z "$ERR" ]; do
			once lps /dev/null "$BIN/locus-ps" "$W/ps-$wl.lmb" -o "$W/ps-$wl.ps"
			once lpdf /dev/null "$BIN/locus-ps" "$W/ps-$wl.lmb" -o "$W/ps-$wl.pdf"
			once plot "$W/ps-$wl.plot.ps" plot -T ps "$W/ps-$wl.plot"
			if [ $cai = 1 ]; then
				once cps /dev/null "$W/cairo_anchor" -s ps "$W/ps-$wl.lmb" -o "$W/ps-$wl.cairo.ps"
				once cpdf /dev/null "$W/cairo_anchor" -s pdf "$W/ps-$wl.lmb" -o "$W/ps-$wl.cairo.pdf"
			fi
			i=$((i + 1))
		done
		if [ -n "$ERR" ]; then fail "ps-$wl" "$ERR"; continue; fi
		med "$W/r.lps"; lps_s=$M_S lps_mib=$M_MIB lps_cpu=$M_CPU
		[ "$wl" = a ] && lps_a_mib=$lps_mib
		med "$W/r.lpdf"; lpdf_s=$M_S lpdf_mib=$M_MIB lpdf_cpu=$M_CPU
		med "$W/r.plot"; plot_s=$M_S plot_mib=$M_MIB plot_cpu=$M_CPU
		b_lps=$(wc -c < "$W/ps-$wl.ps") b_lpdf=$(wc -c < "$W/ps-$wl.pdf") b_plot=$(wc -c < "$W/ps-$wl.plot.ps")
		ps_size_line "ps-$wl" "$lps_s" plot-Tps "$plot_s" "$lps_mib" "$plot_mib" "$b_lps" "$b_plot" "$(cpu "$lps_cpu" "$plot_cpu")"
		if [ $cai = 1 ]; then
			med "$W/r.cps"; cps_s=$M_S cps_mib=$M_MIB cps_cpu=$M_CPU
			med "$W/r.cpdf"; cpdf_s=$M_S cpdf_mib=$M_MIB cpdf_cpu=$M_CPU
			b_cps=$(wc -c < "$W/ps-$wl.cairo.ps") b_cpdf=$(wc -c < "$W/ps-$wl.cairo.pdf")
			ps_size_line "ps-$wl" "$lps_s" cairo-ps "$cps_s" "$lps_mib" "$cps_mib" "$b_lps" "$b_cps" "$(cpu "$lps_cpu" "$cps_cpu")"
			ps_size_line "pdf-$wl" "$lpdf_s" cairo-pdf "$cpdf_s" "$lpdf_mib" "$cpdf_mib" "$b_lpdf" "$b_cpdf" "$(cpu "$lpdf_cpu" "$cpdf_cpu")"
		else
			skip "pdf-$wl" "no cairo anchor: $B_ERR"
		fi
		# Ghostscript interpreting each output (rendering at 96 dpi into nothing)
		ps_gs "$W/ps-$wl.ps" || { fail "gs-ps-$wl" "$M_ERR"; continue; }
		g_l=$M_S g_lm=$M_MIB g_lc=$M_CPU
		ps_gs "$W/ps-$wl.plot.ps" || { fail "gs-ps-$wl" "$M_ERR"; continue; }
		line "gs-ps-$wl" "$g_l" gs-on-plot-Tps "$M_S" "$g_lm" "$M_MIB" "target=1 pass=$(pass "$(ratio "$M_S" "$g_l")" 1) $(cpu "$g_lc" "$M_CPU")"
		if [ $cai = 1 ]; then
			ps_gs "$W/ps-$wl.cairo.ps" || { fail "gs-ps-$wl" "$M_ERR"; continue; }
			line "gs-ps-$wl" "$g_l" gs-on-cairo-ps "$M_S" "$g_lm" "$M_MIB" "target=1 pass=$(pass "$(ratio "$M_S" "$g_l")" 1) $(cpu "$g_lc" "$M_CPU")" \
				"$(ps_instr "$W/ps-$wl.ps" "$W/ps-$wl.cairo.ps")"
			ps_gs "$W/ps-$wl.pdf" || { fail "gs-pdf-$wl" "$M_ERR"; continue; }
			g_l=$M_S g_lm=$M_MIB g_lc=$M_CPU
			ps_gs "$W/ps-$wl.cairo.pdf" || { fail "gs-pdf-$wl" "$M_ERR"; continue; }
			line "gs-pdf-$wl" "$g_l" gs-on-cairo-pdf "$M_S" "$g_lm" "$M_MIB" "target=1 pass=$(pass "$(ratio "$M_S" "$g_l")" 1) $(cpu "$g_lc" "$M_CPU")" \
				"$(ps_instr "$W/ps-$wl.pdf" "$W/ps-$wl.cairo.pdf")"
		fi
	done
	# memory with four times the input: Locus streams, plotutils holds the page
	if "$W/gen_workloads" a binary -s 4 -o "$W/ps-a4.lmb" 2> "$W/gen.log" &&
			"$W/gen_workloads" a plot -s 4 -o "$W/ps-a4.plot" 2>> "$W/gen.log"; then
		measure 1 /dev/null "$BIN/locus-ps" "$W/ps-a4.lmb" -o "$W/ps-a4.ps" && l4_s=$M_S l4_mib=$M_MIB &&
			measure 1 "$W/ps-a4.plot.ps" plot -T ps "$W/ps-a4.plot" &&
			line ps-a-x4 "$l4_s" plot-Tps "$M_S" "$l4_mib" "$M_MIB" "locus_rss_x1_mib=${lps_a_mib:-na}"
	fi
	# a 1024x768 ray-traced picture: PNG against EPS at each level and PDF
	if have_bin locus-render && have_bin locus-raster && [ -f fixtures/scenes/bench-trifocal.scene ] &&
			"$BIN/locus-render" --quiet fixtures/scenes/bench-trifocal.scene -o "$W/ps-rt.meta" 2> /dev/null; then
		measure 1 /dev/null "$BIN/locus-raster" "$W/ps-rt.meta" -o "$W/ps-rt.png" && r_s=$M_S r_mib=$M_MIB
		sz=""
		for lv in 1 2 3; do
			"$BIN/locus-ps" --level $lv "$W/ps-rt.meta" -o "$W/ps-rt$lv.eps" && sz="$sz eps_level${lv}_bytes=$(wc -c < "$W/ps-rt$lv.eps")"
		done
		measure 1 /dev/null "$BIN/locus-ps" "$W/ps-rt.meta" -o "$W/ps-rt.pdf" &&
			line ps-gallery "$M_S" locus-raster-png "$r_s" "$M_MIB" "$r_mib" \
				"png_bytes=$(wc -c < "$W/ps-rt.png")$sz pdf_bytes=$(wc -c < "$W/ps-rt.pdf")"
	else
		skip ps-gallery "locus-render or the bench scene missing"
	fi
}

# hpgl.sh (sourced by scripts/bench.sh): locus-hpgl against GNU plotutils' plot -T hpgl.
#  hpgl-WL-v1 / -v2   replay of workload WL (a, b, c) to HP-GL (7475a profile, against
#                     HPGL_VERSION=1) and HP-GL/2 (hpgl2 profile, against HPGL_VERSION=2); target 2x
#  hpgl-travel-c      the plot-time estimate of locus-hpgl's order against plot's order of workload c,
#                     both read back by locus-hpgl --analyse at the same pen-down length; target 5x on
#                     the pen-up travel
#  hpgl-travel-plate  the same on a rendered contour-map plate (fixtures/scenes/contour-sum.scene),
#                     against the file's own order (plot does not reorder: --no-optimize gives its order)
#  hpgl-2opt-WL       the optimiser with 2-opt against plain greedy nearest-end ordering (budget=0)

# hpgl_stat KEY FILE: a figure from the --stats line ("pen-up travel B mm -> A mm (greedy G mm")
hpgl_stat() {
	case $1 in
	before) sed -n 's/.*pen-up travel \([0-9.]*\) mm -> .*/\1/p' "$2" | head -1 ;;
	after) sed -n 's/.*pen-up travel [0-9.]* mm -> \([0-9.]*\) mm.*/\1/p' "$2" | head -1 ;;
	greedy) sed -n 's/.*(greedy \([0-9.]*\) mm.*/\1/p' "$2" | head -1 ;;
	opt) sed -n 's/.*optimiser \([0-9.]*\) s.*/\1/p' "$2" | head -1 ;;
	esac
}

# hpgl_an FILE [LENGTH]: --analyse figures: sets AN_DOWN AN_UP AN_LIFTS AN_EST AN_CH
hpgl_an() {
	if [ -n "${2:-}" ]; then
		a=$("$BIN/locus-hpgl" --analyse --length "$2" "$1") || return 1
	else
		a=$("$BIN/locus-hpgl" --analyse "$1") || return 1
	fi
	AN_DOWN=$(echo "$a" | sed 's/.*pen-down \([0-9.]*\) mm.*/\1/')
	AN_UP=$(echo "$a" | sed 's/.*pen-up \([0-9.]*\) mm.*/\1/')
	AN_LIFTS=$(echo "$a" | sed 's/.* \([0-9]*\) lifts.*/\1/')
	AN_EST=$(echo "$a" | sed 's/.*estimate \([0-9.]*\) s.*/\1/')
	AN_CH=$(echo "$a" | sed 's/.* \([0-9]*\) pen changes.*/\1/')
}

bench_hpgl() {
	if ! have plot; then fail hpgl "plot (Debian plotutils) missing"; return; fi
	if ! have_bin locus-hpgl; then skip hpgl "$BIN/locus-hpgl not built"; return; fi
	if ! build gen_workloads tests/bench/gen_workloads.c; then skip hpgl "gen_workloads does not build: $B_ERR"; return; fi
	for wl in a b c; do
		"$W/gen_workloads" "$wl" text -o "$W/h$wl.meta" 2> /dev/null &&
			"$W/gen_workloads" "$wl" plot -o "$W/h$wl.plot" 2> /dev/null || { fail "hpgl-$wl" "gen_workloads $wl failed"; continue; }
		# b: plot fills with FP only in HP-GL/2; in HP-GL it draws no fills at all, locus-hpgl hatches
		l2opt=""
		[ "$wl" = b ] && l2opt="--fill native"
		for v in p1 l1 p2 l2; do : > "$W/r.$v"; done
		ERR="" i=0
		while [ "$i" -lt "$BENCH_RUNS" ] && [ -z "$ERR" ]; do
			once p1 "$W/h$wl.p1.hpgl" env HPGL_VERSION=1 plot -T hpgl "$W/h$wl.plot"
			once l1 /dev/null "$BIN/locus-hpgl" "$W/h$wl.meta" -o "$W/h$wl.l1.hpgl"
			once p2 "$W/h$wl.p2.hpgl" env HPGL_VERSION=2 plot -T hpgl "$W/h$wl.plot"
			# shellcheck disable=SC2086
			once l2 /dev/null "$BIN/locus-hpgl" --profile hpgl2 $l2opt "$W/h$wl.meta" -o "$W/h$wl.l2.hpgl"
			i=$((i + 1))
		done
		if [ -n "$ERR" ]; then fail "hpgl-$wl" "$ERR"; continue; fi
		note=""
		[ "$wl" = b ] && note=" note=plot_draws_no_fills_in_HP-GL_locus_hatches"
		med "$W/r.p1"; p_s=$M_S p_mib=$M_MIB p_cpu=$M_CPU
		med "$W/r.l1"
		r=$(ratio "$p_s" "$M_S")
		line "hpgl-$wl-v1" "$M_S" plot-Thpgl-v1 "$p_s" "$M_MIB" "$p_mib" "target=2 pass=$(pass "$r" 2) $(cpu "$M_CPU" "$p_cpu")" \
			"bytes=$(wc -c < "$W/h$wl.l1.hpgl") anchor_bytes=$(wc -c < "$W/h$wl.p1.hpgl") mem_bound=page_paths$note"
		med "$W/r.p2"; p_s=$M_S p_mib=$M_MIB p_cpu=$M_CPU
		med "$W/r.l2"
		r=$(ratio "$p_s" "$M_S")
		line "hpgl-$wl-v2" "$M_S" plot-Thpgl-v2 "$p_s" "$M_MIB" "$p_mib" "target=2 pass=$(pass "$r" 2) $(cpu "$M_CPU" "$p_cpu")" \
			"bytes=$(wc -c < "$W/h$wl.l2.hpgl") anchor_bytes=$(wc -c < "$W/h$wl.p2.hpgl") mem_bound=page_paths"
	done

	# pen-up travel and plot time: workload c against plot's order
	if [ -f "$W/hc.l1.hpgl" ] && [ -f "$W/hc.p1.hpgl" ] && hpgl_an "$W/hc.l1.hpgl"; then
		l_up=$AN_UP l_est=$AN_EST l_down=$AN_DOWN l_lifts=$AN_LIFTS l_ch=$AN_CH
		if hpgl_an "$W/hc.p1.hpgl" "$l_down"; then
			"$BIN/locus-hpgl" --stats "$W/hc.meta" -o /dev/null 2> "$W/hc.stats"
			tr=$(ratio "$AN_UP" "$l_up")
			line hpgl-travel-c "$l_est" plot-Thpgl-order "$AN_EST" 0 0 "target=5 pass=$(pass "$tr" 5)" \
				"travel_locus_mm=$l_up travel_anchor_mm=$AN_UP travel_ratio=$tr lifts_locus=$l_lifts lifts_anchor=$AN_LIFTS" \
				"pen_changes_locus=$l_ch pen_changes_anchor=$AN_CH" \
				"optimiser_s=$(hpgl_stat opt "$W/hc.stats") units=estimated_plot_seconds_7475a"
		else fail hpgl-travel-c "locus-hpgl --analyse of plot's HP-GL failed"; fi
	fi
	# the same on a rendered contour-map plate, against the file's own order
	if have_bin locus-render && "$BIN/locus-render" --quiet fixtures/scenes/contour-sum.scene -o "$W/plate.meta" 2> /dev/null; then
		"$BIN/locus-hpgl" --stats "$W/plate.meta" -o "$W/plate.hpgl" 2> "$W/plate.stats"
		"$BIN/locus-hpgl" --no-optimize "$W/plate.meta" -o "$W/plate.keep.hpgl" 2> /dev/null
		if hpgl_an "$W/plate.hpgl"; then
			l_up=$AN_UP l_est=$AN_EST l_lifts=$AN_LIFTS l_ch=$AN_CH
			hpgl_an "$W/plate.keep.hpgl"
			tr=$(ratio "$AN_UP" "$l_up")
			line hpgl-travel-plate "$l_est" file-order "$AN_EST" 0 0 "target=5 pass=$(pass "$tr" 5)" \
				"travel_locus_mm=$l_up travel_anchor_mm=$AN_UP travel_ratio=$tr lifts_locus=$l_lifts lifts_anchor=$AN_LIFTS" \
				"pen_changes_locus=$l_ch pen_changes_anchor=$AN_CH" \
				"optimiser_s=$(hpgl_stat opt "$W/plate.stats") units=estimated_plot_seconds_7475a"
		else fail hpgl-travel-plate "locus-hpgl --analyse failed"; fi
	else
		skip hpgl-travel-plate "locus-render cannot render fixtures/scenes/contour-sum.scene"
	fi
	# 2-opt against plain greedy nearest-end ordering
	for wl in a c; do
		[ -f "$W/h$wl.meta" ] || continue
		"$BIN/locus-hpgl" --stats "$W/h$wl.meta" -o /dev/null 2> "$W/h$wl.2opt" &&
			"$BIN/locus-hpgl" --stats -O budget=0 "$W/h$wl.meta" -o /dev/null 2> "$W/h$wl.greedy" || { fail "hpgl-2opt-$wl" "locus-hpgl failed"; continue; }
		g=$(hpgl_stat after "$W/h$wl.greedy") t=$(hpgl_stat after "$W/h$wl.2opt")
		pct=$(awk -v g="$g" -v t="$t" 'BEGIN { printf "%.1f", (g > 0 ? 100 * (g - t) / g : 0) }')
		line "hpgl-2opt-$wl" "$(hpgl_stat opt "$W/h$wl.2opt")" greedy-nearest-end "$(hpgl_stat opt "$W/h$wl.greedy")" 0 0 \
			"travel_2opt_mm=$t travel_greedy_mm=$g gain_2opt_pct=$pct travel_file_order_mm=$(hpgl_stat before "$W/h$wl.2opt")" \
			"units=optimiser_seconds"
	done
}

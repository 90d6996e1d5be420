# svgimport.sh: bench group "svgimport" (sourced by scripts/bench.sh), issue 23 item 5: SVG to
# HP-GL for a pen plotter, `locus-meta import X.svg` then `locus-hpgl` (7475a profile, its
# defaults: fitted to the paper, strokes ordered), against Inkscape's own HP-GL export
# (`inkscape --export-type=hpgl`, its extension's default settings) of the same file, on vpype's
# benchmark drawings in ../shared/corpus/svg/vpype/benchmark (read there, not copied):
#  svgimport-FILE  time of the two Locus programs against Inkscape's export; beside it the
#                  pen-up travel and pen changes of both HP-GL files, read back by the same
#                  code (`locus-hpgl --analyse`, the anchor's file first scaled to Locus's
#                  pen-down length with --length, since locus-hpgl shrinks a page the 7475a's
#                  paper cannot hold), and rsvg-convert to PNG at the page's size as a second
#                  time anchor. Goals: 5x Inkscape's time, at most half its pen-up travel.
# No CPU comparison: Inkscape's export runs in a python3 child whose CPU time the rusage of
# the inkscape process does not hold (0.9 s of CPU for 24 s of wall time on 7k_lines; the
# extension alone, python3 hpgl_output.py, takes most of that wall time), so wall time it is.
# Inkscape takes 15-45 s a file, so it runs once a file (SVGIMPORT_INK_RUNS, default 1); the
# Locus pipeline and rsvg-convert run BENCH_RUNS times and give medians.
# Inkscape runs its extensions with the first python3 on PATH: /usr/bin goes first so Debian's
# python3-lxml, python3-cssselect and python3-numpy are seen (a python3 of its own on PATH,
# without them, makes the export abort with "unhandled exception in signal handler").

# hpgl_an FILE [LENGTH] (scripts/bench.d/hpgl.sh: `locus-hpgl --analyse` into AN_DOWN AN_UP
# AN_LIFTS AN_CH) reads both HP-GL files; that group's file is sourced for it when not run.
command -v hpgl_an > /dev/null 2>&1 || . ./scripts/bench.d/hpgl.sh

bench_svgimport() {
	sv_dir=../shared/corpus/svg/vpype/benchmark
	if ! [ -d "$sv_dir" ]; then skip svgimport "$sv_dir absent (vpype's drawings: CI lays ../shared beside the clone)"; return; fi
	if ! have_bin locus-meta || ! have_bin locus-hpgl; then skip svgimport "$BIN/locus-meta or $BIN/locus-hpgl not built"; return; fi
	if ! have inkscape; then fail svgimport "inkscape missing (Debian package inkscape, scripts/deps.d/svgimport.txt)"; return; fi
	if ! /usr/bin/python3 -c 'import lxml, cssselect, numpy' 2> /dev/null; then
		fail svgimport "Inkscape's HP-GL extension needs python3-lxml python3-cssselect python3-numpy"; return
	fi
	have rsvg-convert || { fail svgimport "rsvg-convert missing (librsvg2-bin)"; return; }
	ink_runs=${SVGIMPORT_INK_RUNS:-1}
	for f in 7k_lines 500_circles 900_quad_beziers multi_skull; do
		n=svgimport-$f
		src=$sv_dir/$f.svg
		if ! [ -f "$src" ]; then skip "$n" "$src absent"; continue; fi
		# Inkscape writes beside nothing of ours: the drawing is read where it is
		if ! measure "$ink_runs" /dev/null env PATH="/usr/bin:$PATH" inkscape --export-type=hpgl \
				--export-filename="$W/sv_$f.ink.hpgl" "$src" || ! [ -s "$W/sv_$f.ink.hpgl" ]; then
			fail "$n" "inkscape --export-type=hpgl: ${M_ERR:-no output} $(grep -m1 ERROR "$W/err" | cut -c1-80)"
			continue
		fi
		i_s=$M_S i_mib=$M_MIB
		if ! measure "$BENCH_RUNS" /dev/null sh -c '"$1/locus-meta" import "$2" -o "$3.meta" && "$1/locus-hpgl" "$3.meta" -o "$3.hpgl"' \
				sh "$BIN" "$src" "$W/sv_$f.loc"; then
			fail "$n" "$M_ERR"; continue
		fi
		l_s=$M_S l_mib=$M_MIB l_cpu=$M_CPU
		# rsvg-convert at the drawing's own size (its width and height in px at 96 dpi)
		if ! measure "$BENCH_RUNS" "$W/sv_$f.png" rsvg-convert -f png "$src"; then fail "$n" "rsvg-convert: $M_ERR"; continue; fi
		r_s=$M_S
		if ! hpgl_an "$W/sv_$f.loc.hpgl"; then fail "$n" "locus-hpgl --analyse of Locus's HP-GL failed"; continue; fi
		l_up=$AN_UP l_down=$AN_DOWN l_ch=$AN_CH l_lifts=$AN_LIFTS
		if ! hpgl_an "$W/sv_$f.ink.hpgl" "$l_down"; then fail "$n" "locus-hpgl --analyse of Inkscape's HP-GL failed"; continue; fi
		tr=$(ratio "$AN_UP" "$l_up")
		line "$n" "$l_s" inkscape-export-hpgl "$i_s" "$l_mib" "$i_mib" "target=5 pass=$(pass "$(ratio "$i_s" "$l_s")" 5) locus_cpu_s=$l_cpu" \
			"travel_locus_mm=$l_up travel_anchor_mm=$AN_UP travel_ratio=$tr travel_target=2 travel_pass=$(pass "$tr" 2)" \
			"lifts_locus=$l_lifts lifts_anchor=$AN_LIFTS pen_changes_locus=$l_ch pen_changes_anchor=$AN_CH" \
			"rsvg_png_s=$r_s ratio_rsvg=$(ratio "$r_s" "$l_s") inkscape_runs=$ink_runs units=mm_at_locus_pen_down_length"
	done
}

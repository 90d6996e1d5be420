# film.sh: bench group "film" (sourced by scripts/bench.sh): locus-film writing a slide frame
# (4096x2730, and 8192x5460) of a ray-traced gallery plate and of workload a, against
# ImageMagick converting locus-raster's PNG of the same picture, upscaled to the frame, to DPX.
# One BENCH line per picture and frame: time, peak RSS, MB/s written (docs/benchmarks.md), and
# the one-minute load average (load1: locus-film paints with two threads, so shared cores show).

# film_one NAME META W H PRESET RUNS
film_one() {
	f_n=$1 f_m=$2 f_w=$3 f_h=$4 f_p=$5 f_r=$6
	if ! measure "$f_r" /dev/null "$BIN/locus-film" --preset "$f_p" "$f_m" -o "$W/film.dpx"; then
		fail "$f_n" "$M_ERR"; return
	fi
	ls=$M_S lm=$M_MIB lc=$M_CPU
	bytes=$(wc -c < "$W/film.dpx")
	# the anchor: the same letterboxed frame, box-filtered up, log-encoded to 10 bits
	if ! measure "$f_r" /dev/null "$FILM_IM" "$W/film-in.png" -filter box -resize "${f_w}x$f_h" \
		-background black -gravity center -extent "${f_w}x$f_h" -colorspace Log -depth 10 "$W/film-im.dpx"; then
		fail "$f_n" "$M_ERR"; return
	fi
	abytes=$(wc -c < "$W/film-im.dpx")
	r=$(ratio "$M_S" "$ls")
	mem=$(awk -v l="$lm" -v a="$M_MIB" 'BEGIN {print (l * 10 <= a) ? "yes" : "no"}')
	line "$f_n" "$ls" imagemagick-convert "$M_S" "$lm" "$M_MIB" "target=3 pass=$(pass "$r" 3)" \
		"mem_target=0.1 mem_pass=$mem runs=$f_r frame=${f_w}x$f_h" \
		"mb_per_s=$(awk -v b="$bytes" -v s="$ls" 'BEGIN {printf "%.1f", b / 1e6 / s}')" \
		"anchor_mb_per_s=$(awk -v b="$abytes" -v s="$M_S" 'BEGIN {printf "%.1f", b / 1e6 / s}')" \
		"bytes=$bytes $(cpu "$lc" "$M_CPU") load1=$(cut -d' ' -f1 /proc/loadavg 2> /dev/null || echo na)"
	rm -f "$W/film.dpx" "$W/film-im.dpx"
}

bench_film() {
	if ! have_bin locus-film || ! have_bin locus-raster || ! have_bin locus-render; then
		skip film-plate "$BIN/locus-film, locus-raster or locus-render not built yet"; return
	fi
	# ImageMagick's own binary (Debian's convert-im6.q16), not a wrapper script that may stand
	# in front of `convert` on the PATH and add its start-up to the anchor's time
	FILM_IM=$(command -v convert-im6.q16 || command -v convert) ||
		{ fail film-plate "ImageMagick convert missing (Debian imagemagick)"; return; }
	# the ray-traced gallery plate (docs/gallery/default.png) and workload a of the plot group
	if ! "$BIN/locus-render" fixtures/scenes/default.scene -o "$W/film-plate.meta" 2> "$W/film.log"; then
		fail film-plate "locus-render: $(tail -1 "$W/film.log")"; return
	fi
	if [ ! -f "$W/a.meta" ]; then
		if [ ! -x "$W/gen_workloads" ] && ! build gen_workloads tests/bench/gen_workloads.c; then
			skip film-a "gen_workloads does not build: $B_ERR"
		elif ! "$W/gen_workloads" a text -o "$W/a.meta" 2> "$W/gen.log"; then
			fail film-a "gen_workloads: $(tail -1 "$W/gen.log")"
		fi
	fi
	for pic in plate:film-plate.meta a:a.meta; do
		m=$W/${pic#*:}
		[ -f "$m" ] || continue
		if ! "$BIN/locus-raster" "$m" -o "$W/film-in.png" 2> "$W/film.log"; then
			fail "film-${pic%%:*}" "locus-raster: $(tail -1 "$W/film.log")"; continue
		fi
		film_one "film-${pic%%:*}" "$m" 4096 2730 slide4k "$SLOW_RUNS"
		film_one "film-${pic%%:*}-8k" "$m" 8192 5460 slide8k 1
	done
	rm -f "$W/film-in.png"
}

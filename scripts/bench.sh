#!/bin/sh
# bench.sh: run Locus and its anchors in the same run; print BENCH lines (also to out/bench.txt).
#
# Every comparison prints one line
#   BENCH name=WORKLOAD locus_s=S anchor=TOOL anchor_s=S ratio=R locus_rss_mib=M anchor_rss_mib=M [key=value...]
# with medians of several runs; ratio = anchor_s / locus_s, so ratio > 1 means Locus is faster.
# A comparison whose Locus program (or scene, or bench source) is not there yet prints
#   BENCH-SKIP name=WORKLOAD reason=...
# and one that could not run (a crash, a missing anchor tool) prints BENCH-FAIL and makes the
# script exit 1. A low ratio never fails: this is a measurement, not a test.
# docs/benchmarks.md explains each workload. Environment: BIN (programs, default bin),
# CC, BENCH_RUNS (runs per fast measurement, default 5), BENCH_ONLY (space-separated groups
# to run: plot check pov octree contour voronoi; default all), BENCH_KEEP=1 keeps the
# run directory build/bench/run.PID (inputs and pictures) for looking at.
set -u
: "${BIN:=bin}" "${CC:=cc}" "${BENCH_RUNS:=5}"
# groups: the built-in ones, then one per scripts/bench.d/GROUP.sh
BENCH_GROUPS="plot check pov octree contour voronoi"
for f in scripts/bench.d/*.sh; do
	[ -f "$f" ] && BENCH_GROUPS="$BENCH_GROUPS $(basename "$f" .sh)"
done
: "${BENCH_ONLY:=$BENCH_GROUPS}"
LIBDIR=build/native
BB=build/bench
# one directory per run, so that two runs at once do not overwrite each other's files
# (their timings still disturb each other); removed at the end unless BENCH_KEEP=1
W=$BB/run.$$
RESULTS=out/bench.txt
RTMP=out/bench.txt.$$.tmp
mkdir -p "$BB" "$W" out || exit 74
: > "$RTMP" || exit 74
trap 'rm -f "$RTMP"; [ "${BENCH_KEEP:-0}" = 1 ] || rm -rf "$W"' EXIT
trap 'exit 130' INT TERM
FAILED=0
SLOW_RUNS=3
[ "$BENCH_RUNS" -lt "$SLOW_RUNS" ] && SLOW_RUNS=$BENCH_RUNS

# ---- helpers -------------------------------------------------------------

emit() { echo "$*"; echo "$*" >> "$RTMP"; }
words() { echo "$*" | tr ' =' '-:'; }
skip() { s_n=$1; shift; emit "BENCH-SKIP name=$s_n reason=$(words "$*" | cut -c1-160)"; }
fail() { f_n=$1; shift; emit "BENCH-FAIL name=$f_n reason=$(words "$*" | cut -c1-200)"; FAILED=1; }
want() { case " $BENCH_ONLY " in *" $1 "*) return 0 ;; esac; return 1; }

# measure N OUT CMD...: run CMD N times with stdout to OUT (stderr of the last run in $W/err,
# of all N runs one after the other in $W/errs, for medians of figures the programs print).
# Sets M_S (median wall seconds, from the clock around /usr/bin/time), M_CPU (median user +
# system CPU seconds: less disturbed by other load on a shared machine) and M_MIB (median
# peak RSS in MiB, from /usr/bin/time %M). Returns 1 (M_ERR set) if any run fails.
measure() {
	m_n=$1 m_out=$2
	shift 2
	: > "$W/times"
	: > "$W/errs"
	m_i=0
	while [ "$m_i" -lt "$m_n" ]; do
		t0=$(date +%s%N)
		if ! /usr/bin/time -f '%e %M %U %S' -o "$W/time1" "$@" > "$m_out" 2> "$W/err"; then
			M_ERR="$(basename "$1") failed: $(grep -v '^Command exited' "$W/err" | tail -1 | cut -c1-120)"
			return 1
		fi
		t1=$(date +%s%N)
		cat "$W/err" >> "$W/errs"
		echo "$(( (t1 - t0) / 1000 )) $(tail -1 "$W/time1" | awk '{print $2, $3 + $4}')" >> "$W/times"
		m_i=$((m_i + 1))
	done
	M_S=$(sort -n -k1,1 "$W/times" | awk '{a[NR] = $1} END {printf "%.4f", a[int((NR + 1) / 2)] / 1e6}')
	M_MIB=$(awk '{print $2}' "$W/times" | sort -n | awk '{a[NR] = $1} END {printf "%.1f", a[int((NR + 1) / 2)] / 1024}')
	M_CPU=$(awk '{print $3}' "$W/times" | sort -n | awk '{a[NR] = $1} END {printf "%.3f", a[int((NR + 1) / 2)]}')
	return 0
}

# cpu LOCUS_CPU ANCHOR_CPU: the key=values of the CPU-time comparison
cpu() { echo "locus_cpu_s=$1 anchor_cpu_s=$2 ratio_cpu=$(ratio "$2" "$1")"; }

# ratio A L: A / L with 2 decimals
ratio() { awk -v a="$1" -v l="$2" 'BEGIN {if (l > 0) printf "%.2f", a / l; else print "inf"}'; }
# pass RATIO TARGET: yes when RATIO >= TARGET
pass() { awk -v r="$1" -v t="$2" 'BEGIN {print (r != "inf" && r + 0 < t + 0) ? "no" : "yes"}'; }

# line NAME LOCUS_S ANCHOR ANCHOR_S LOCUS_MIB ANCHOR_MIB [key=value...]
line() {
	l_n=$1 l_ls=$2 l_an=$3 l_as=$4 l_lm=$5 l_am=$6
	shift 6
	emit "BENCH name=$l_n locus_s=$l_ls anchor=$l_an anchor_s=$l_as ratio=$(ratio "$l_as" "$l_ls")" \
		"locus_rss_mib=$l_lm anchor_rss_mib=$l_am${*:+ $*}"
}

# diffpct A B: percentage of pixels that differ between two same-size images (ImageMagick)
diffpct() {
	ae=$(compare -metric AE "$1" "$2" null: 2>&1 | awk '{print $1}')
	awk -v d="$ae" 'BEGIN {if (d ~ /^[0-9.e+]+$/) printf "%.2f", 100 * d / (1024 * 768); else print "na"}'
}

# ---- building the bench programs ------------------------------------------

VERSION=$(sed -n 's/^VERSION *:= *//p' Makefile)
BCFLAGS="-std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -O2 -march=native -fno-math-errno -Wall -Wextra -Imeta -Icore -Idrivers $(pkg-config --cflags libpng zlib 2>/dev/null)"
# `make all` builds only the libraries its programs need: make sure all three are there
# (a library that does not build yet just leaves its bench program skipped)
${MAKE:-make} -s -j2 "$LIBDIR/libcore.a" "$LIBDIR/libdrivers.a" "$LIBDIR/libmeta.a" > "$W/libs.log" 2>&1 ||
	echo "bench: some libraries do not build yet (see $W/libs.log)" >&2
BLIBS=""
for l in core drivers meta; do
	[ -f "$LIBDIR/lib$l.a" ] && BLIBS="$BLIBS $LIBDIR/lib$l.a"
done
BLDLIBS="$(pkg-config --libs libpng zlib 2>/dev/null) -lpthread -lm"

# build NAME SRC: compile SRC into the run directory as NAME; 1 when it does not build
build() {
	# shellcheck disable=SC2086
	$CC $BCFLAGS "-DLOCUS_VERSION=\"$VERSION\"" "$2" $BLIBS $BLDLIBS -o "$W/$1" 2> "$W/$1.log" && return 0
	B_ERR="$(grep -m1 -E 'error|undefined' "$W/$1.log" | cut -c1-160)"
	return 1
}

have() { command -v "$1" >/dev/null 2>&1; }
have_bin() { [ -x "$BIN/$1" ]; }

if ! [ -x /usr/bin/time ]; then
	fail setup "/usr/bin/time missing (Debian package time)"
	mv "$RTMP" "$RESULTS"
	exit 1
fi
echo "bench: $(date -u +%Y-%m-%dT%H:%M:%SZ) $(uname -m) $(nproc) cores, runs=$BENCH_RUNS (slow ones $SLOW_RUNS)" >&2

# ---- issue 2: metafile replay, Locus meta vs plotutils #PLOT 2 ----------------

# rec FILE: append the last measurement (M_S M_MIB M_CPU) to FILE
rec() { echo "$M_S $M_MIB $M_CPU" >> "$1"; }

# med FILE: set M_S, M_MIB and M_CPU to the medians of the runs recorded in FILE
med() {
	M_S=$(awk '{print $1}' "$1" | sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
	M_MIB=$(awk '{print $2}' "$1" | sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
	M_CPU=$(awk '{print $3}' "$1" | sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
}

# once TAG OUT CMD...: one timed run of CMD recorded in $W/r.TAG; after a failure (ERR set)
# it does nothing more
once() {
	o_t=$1 o_o=$2
	shift 2
	[ -n "$ERR" ] && return 1
	if measure 1 "$o_o" "$@"; then rec "$W/r.$o_t"; return 0; fi
	ERR="$o_t: $M_ERR"
	return 1
}

# pair_line NAME IN EXT PLOT_S PLOT_MIB PLOT_CPU LOCUS_OUT PLOT_OUT: the line of one
# locus-raster variant (its medians in M_*) against plot, and how much the pictures differ
pair_line() {
	r=$(ratio "$4" "$M_S")
	line "$1" "$M_S" "plot-T$3" "$4" "$M_MIB" "$5" "target=2 pass=$(pass "$r" 2) $(cpu "$M_CPU" "$6")" \
		"bytes=$(wc -c < "$2") diff_px_pct=$(diffpct "$7" "$8")"
}

bench_plot() {
	if ! have plot || ! have compare; then
		fail plot "plot (Debian plotutils) or compare (imagemagick) missing"
		return
	fi
	if ! build gen_workloads tests/bench/gen_workloads.c; then
		for wl in a b c; do skip "$wl" "gen_workloads does not build yet: $B_ERR"; done
		return
	fi
	lr=0
	have_bin locus-raster && lr=1
	for wl in a b c; do
		for f in text:meta binary:lmb plot:plot; do
			if ! "$W/gen_workloads" "$wl" "${f%%:*}" -o "$W/$wl.${f#*:}" 2> "$W/gen.log"; then
				fail "$wl" "gen_workloads $wl ${f%%:*}: $(tail -1 "$W/gen.log")"
				continue 2
			fi
		done
		echo "bench: $(tail -1 "$W/gen.log")" >&2
		# rounds of: plot to PNM, locus-raster text and binary to PPM, plot to PNG, locus-raster
		# to PNG, so that a change of load on the machine hits both sides alike
		for v in pnm png text bin lpng; do : > "$W/r.$v"; done
		ERR="" i=0
		while [ "$i" -lt "$BENCH_RUNS" ] && [ -z "$ERR" ]; do
			once pnm "$W/$wl.pnm" plot -T pnm --bitmap-size 1024x768 "$W/$wl.plot"
			[ "$lr" = 1 ] && once text /dev/null "$BIN/locus-raster" "$W/$wl.meta" -o "$W/$wl.ppm"
			[ "$lr" = 1 ] && once bin /dev/null "$BIN/locus-raster" "$W/$wl.lmb" -o "$W/$wl-binary.ppm"
			once png "$W/$wl.plot.png" plot -T png --bitmap-size 1024x768 "$W/$wl.plot"
			[ "$lr" = 1 ] && once lpng /dev/null "$BIN/locus-raster" "$W/$wl.meta" -o "$W/$wl-png.png"
			i=$((i + 1))
		done
		if [ -n "$ERR" ]; then fail "$wl" "$ERR"; continue; fi
		med "$W/r.pnm"
		pnm_s=$M_S pnm_mib=$M_MIB pnm_cpu=$M_CPU
		med "$W/r.png"
		png_s=$M_S png_mib=$M_MIB png_cpu=$M_CPU
		if [ "$lr" = 0 ]; then
			for n in "$wl" "$wl-binary" "$wl-png"; do
				skip "$n" "$BIN/locus-raster not built yet (plot -T pnm $pnm_s s)"
			done
			continue
		fi
		med "$W/r.text"
		pair_line "$wl" "$W/$wl.meta" ppm "$pnm_s" "$pnm_mib" "$pnm_cpu" "$W/$wl.ppm" "$W/$wl.pnm"
		[ "$wl" = a ] && RASTER_a_MIB=$M_MIB
		med "$W/r.bin"
		pair_line "$wl-binary" "$W/$wl.lmb" ppm "$pnm_s" "$pnm_mib" "$pnm_cpu" "$W/$wl-binary.ppm" "$W/$wl.pnm"
		med "$W/r.lpng"
		pair_line "$wl-png" "$W/$wl.meta" png "$png_s" "$png_mib" "$png_cpu" "$W/$wl-png.png" "$W/$wl.plot.png"
	done
	# peak memory against input size: workload a at 4 times the polylines
	if have_bin locus-raster && [ -n "${RASTER_a_MIB:-}" ]; then
		if "$W/gen_workloads" a text -s 4 -o "$W/a4.meta" 2> "$W/gen.log" &&
			"$W/gen_workloads" a plot -s 4 -o "$W/a4.plot" 2>> "$W/gen.log"; then
			# the anchor once: it is the slowest run of the bench and only gives the ratio here
			if measure 1 "$W/a4.pnm" plot -T pnm --bitmap-size 1024x768 "$W/a4.plot"; then
				ps=$M_S pm=$M_MIB pc=$M_CPU
				if measure "$SLOW_RUNS" /dev/null "$BIN/locus-raster" "$W/a4.meta" -o "$W/a4.ppm"; then
					r=$(ratio "$ps" "$M_S")
					line a-4x "$M_S" plot-Tppm "$ps" "$M_MIB" "$pm" "target=2 pass=$(pass "$r" 2) anchor_runs=1" \
						"$(cpu "$M_CPU" "$pc")" \
						"bytes=$(wc -c < "$W/a4.meta") locus_rss_mib_1x=$RASTER_a_MIB" \
						"rss_growth=$(ratio "$M_MIB" "$RASTER_a_MIB")"
				else
					fail a-4x "$M_ERR"
				fi
			else
				fail a-4x "$M_ERR"
			fi
		else
			fail a-4x "gen_workloads: $(tail -1 "$W/gen.log")"
		fi
	fi
}

# ---- issue 2: locus-meta check must take < 1/3 of the replay ----------------

bench_check() {
	if ! have_bin locus-meta || ! have_bin locus-raster; then
		skip a-check "$BIN/locus-meta or $BIN/locus-raster not built yet"; return
	fi
	# workload a from the plot group, or made here when that group did not run
	if [ ! -f "$W/a.meta" ] || [ ! -f "$W/a.lmb" ]; then
		if [ ! -x "$W/gen_workloads" ] && ! build gen_workloads tests/bench/gen_workloads.c; then
			skip a-check "gen_workloads does not build yet: $B_ERR"; return
		fi
		for f in text:meta binary:lmb; do
			if ! "$W/gen_workloads" a "${f%%:*}" -o "$W/a.${f#*:}" 2> "$W/gen.log"; then
				fail a-check "gen_workloads a ${f%%:*}: $(tail -1 "$W/gen.log")"; return
			fi
		done
	fi
	# rounds of check, replay, check, replay... of the same file, so that both see the same load
	for v in a:meta a-binary:lmb; do
		n=${v%%:*}-check ext=${v#*:}
		: > "$W/r.check"
		: > "$W/r.replay"
		ERR="" i=0
		while [ "$i" -lt "$BENCH_RUNS" ] && [ -z "$ERR" ]; do
			once check /dev/null "$BIN/locus-meta" check "$W/a.$ext"
			once replay /dev/null "$BIN/locus-raster" "$W/a.$ext" -o "$W/a-check.ppm"
			i=$((i + 1))
		done
		if [ -n "$ERR" ]; then fail "$n" "$ERR"; continue; fi
		med "$W/r.replay"
		rs=$M_S rm=$M_MIB rc=$M_CPU
		med "$W/r.check"
		r=$(ratio "$rs" "$M_S")
		# check_fraction = check time / replay time: the target is below 1/3 (ratio >= 3)
		line "$n" "$M_S" locus-raster "$rs" "$M_MIB" "$rm" "target=3 pass=$(pass "$r" 3)" \
			"check_fraction=$(awk -v c="$M_S" -v r="$rs" 'BEGIN {if (r > 0) printf "%.3f", c / r; else print "na"}')" \
			"$(cpu "$M_CPU" "$rc") bytes=$(wc -c < "$W/a.$ext")"
	done
}

# ---- issue 3: implicit surfaces, Locus vs POV-Ray isosurface ---------------------

# POV-Ray's options: 1024x768, no anti-aliasing, 2 threads, linear file gamma (the values Locus writes)
POVOPTS="-D -V +W1024 +H768 -A +WT2 File_Gamma=1.0"

# scene_with SCENE OUT LINES: copy SCENE with LINES (separated by \n, which awk -v turns
# into newlines) added to its `render raytrace` block
scene_with() {
	awk -v add="$3" '
		/^render raytrace *$/ { print; n = split(add, a, "\n")
			for (i = 1; i <= n; i++) print "  " a[i]; next }
		{ print }' "$1" > "$2"
}

# stat KEY FILE: value of KEY=VALUE in a locus-render --stats line
stat() { grep -o -m1 -E "(^| )$1=[^ ]+" "$2" | head -1 | sed 's/.*=//'; }

# median FILE: median of the numbers in FILE, one a line (empty when there are none)
median() { sort -n "$1" | awk '{a[NR] = $1} END {if (NR) print a[int((NR + 1) / 2)]}'; }

# stat_med KEY FILE: median of KEY=VALUE over all the --stats lines in FILE (one per run:
# the trace time of one run moves by 2x on a shared machine, the median much less)
stat_med() {
	grep -o -E "(^| )$1=[^ ]+" "$2" | sed 's/.*=//' > "$W/vals"
	median "$W/vals"
}

# pixcmp A.ppm B.ppm PREFIX: "PREFIX_psnr_db=P PREFIX_silhouette_px=S" from bench_pixcmp (raw
# values: PPM has no gamma chunk), "=na" when the comparison could not run
pixcmp() {
	if [ -x "$W/bench_pixcmp" ] && "$W/bench_pixcmp" "$1" "$2" > "$W/pixcmp.out" 2> "$W/pixcmp.err"; then
		echo "$3_psnr_db=$(stat psnr_db "$W/pixcmp.out") $3_silhouette_px=$(stat silhouette_px "$W/pixcmp.out")"
	else
		echo "$3_psnr_db=na $3_silhouette_px=na"
	fi
}

# surface_pass RATIO_TRACE PSNR SILHOUETTE EVALS: "pass=yes", or "pass=no fails=WHAT,..." against
# the targets: trace ratio >= SURFACE_TARGET (issue 3 asked 20, issue 26 asks 40), PSNR >= 60 dB
# and at most 5 silhouette pixels against the reference, at most 12 evaluations per pixel ("na"
# figures fail)
SURFACE_TARGET=40
surface_pass() {
	awk -v r="$1" -v p="$2" -v s="$3" -v e="$4" -v t="$SURFACE_TARGET" 'BEGIN {
		f = ""
		if (r != "inf" && (r !~ /^[0-9.]+$/ || r + 0 < t)) f = f ",ratio_trace"
		if (p != "inf" && (p !~ /^[0-9.]+$/ || p + 0 < 60)) f = f ",psnr"
		if (s !~ /^[0-9]+$/ || s + 0 > 5) f = f ",silhouette"
		if (e !~ /^[0-9.]+$/ || e + 0 > 12) f = f ",evals"
		print f == "" ? "pass=yes" : "pass=no fails=" substr(f, 2) }'
}

bench_pov() {
	# the raw-pixel comparer (without it the accuracy figures are "na", and pass=no)
	build bench_pixcmp tests/bench/bench_pixcmp.c || echo "bench: bench_pixcmp does not build: $B_ERR" >&2
	for s in trifocal segpoint; do
		pov=fixtures/bench/$s.pov
		if ! have povray; then fail "$s" "povray missing (Debian povray)"; continue; fi
		scene=fixtures/scenes/bench-$s.scene
		lok=1
		{ have_bin locus-render && have_bin locus-raster && [ -f "$scene" ]; } || lok=0
		# rounds of one POV-Ray run and 3 Locus runs (Locus is fast: more runs steady its
		# median), so that a change of load from other work on the machine hits both sides;
		# the stderr of every run is kept for the medians of the trace times
		: > "$W/r.pov"
		: > "$W/r.locus"
		: > "$W/$s.povlog"
		: > "$W/$s.stats"
		ERR="" i=0
		while [ "$i" -lt "$SLOW_RUNS" ] && [ -z "$ERR" ]; do
			# PPM output (+FP): raw values, no gAMA chunk to make readers convert them
			# shellcheck disable=SC2086
			once pov /dev/null povray $POVOPTS +FP +I"$pov" +O"$W/$s.pov.ppm" && cat "$W/err" >> "$W/$s.povlog"
			for _ in 1 2 3; do
				[ "$lok" = 1 ] && once locus /dev/null "$BIN/locus-render" "$scene" -o "$W/$s.meta" --stats &&
					grep '^stats:' "$W/err" >> "$W/$s.stats"
			done
			i=$((i + 1))
		done
		if [ -n "$ERR" ]; then fail "$s" "$ERR"; continue; fi
		med "$W/r.pov"
		pv_s=$M_S pv_mib=$M_MIB pv_cpu=$M_CPU
		# the trace time: median over the runs, like the wall time
		sed -n 's/.*Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' "$W/$s.povlog" > "$W/vals"
		pv_trace=$(median "$W/vals")
		pv_calls=$(awk '/Function VM calls/ {print $NF}' "$W/$s.povlog" | tail -1)
		pv_epp=$(awk -v c="${pv_calls:-0}" 'BEGIN {printf "%.1f", c / (1024 * 768)}')
		# POV-Ray's reference: accuracy 1e-6 (max_gradient 3, the exact bound, is in the .pov)
		# shellcheck disable=SC2086
		povray $POVOPTS +FP Declare=Accuracy=0.000001 +I"$pov" +O"$W/$s.povref.ppm" > /dev/null 2>&1
		pv_acc=$(pixcmp "$W/$s.pov.ppm" "$W/$s.povref.ppm" pov)
		if [ "$lok" = 0 ]; then
			emit "BENCH-SKIP name=$s reason=$(words "$BIN/locus-render, $BIN/locus-raster or $scene not there yet")" \
				"anchor=povray anchor_s=$pv_s anchor_trace_s=${pv_trace:-na} anchor_calls_per_px=$pv_epp" \
				"anchor_rss_mib=$pv_mib $pv_acc"
			continue
		fi
		med "$W/r.locus"
		lr_s=$M_S lr_mib=$M_MIB lr_cpu=$M_CPU
		l_epp=$(stat evals_per_pixel "$W/$s.stats")
		l_lanes=$(awk -v e="$(stat lane_evals "$W/$s.stats")" -v p="$(stat pixels "$W/$s.stats")" \
			'BEGIN {if (p > 0 && e != "") printf "%.3f", e / p; else print "na"}')
		# median of the runs' trace_ms, as locus_s is the median of their wall times
		l_ms=$(stat_med trace_ms "$W/$s.stats")
		l_trace=$(awk -v m="${l_ms:-0}" 'BEGIN {printf "%.4f", m / 1000}')
		r_trace=$(ratio "${pv_trace:-0}" "$(awk -v m="${l_ms:-0}" 'BEGIN {print m / 1000}')")
		"$BIN/locus-raster" "$W/$s.meta" -o "$W/$s.locus.ppm" 2> "$W/raster.err" ||
			{ fail "$s" "locus-raster: $(tail -1 "$W/raster.err")"; continue; }
		# Locus' reference: the same scene with `refine yes` (hits polished in double precision)
		l_acc="locus_psnr_db=na locus_silhouette_px=na" x_acc="refs_psnr_db=na refs_silhouette_px=na"
		scene_with "$scene" "$W/$s.ref.scene" "refine yes"
		if "$BIN/locus-render" "$W/$s.ref.scene" -o "$W/$s.ref.meta" --quiet 2> /dev/null &&
			"$BIN/locus-raster" "$W/$s.ref.meta" -o "$W/$s.ref.ppm" 2> /dev/null; then
			l_acc=$(pixcmp "$W/$s.locus.ppm" "$W/$s.ref.ppm" locus)
			# the two references against each other: do both renderers draw the same picture?
			x_acc=$(pixcmp "$W/$s.povref.ppm" "$W/$s.ref.ppm" refs)
		fi
		l_psnr=$(echo "$l_acc" | sed -n 's/.*locus_psnr_db=\([^ ]*\).*/\1/p')
		l_sil=$(echo "$l_acc" | sed -n 's/.*locus_silhouette_px=\([^ ]*\).*/\1/p')
		line "$s" "$lr_s" povray "$pv_s" "$lr_mib" "$pv_mib" \
			"anchor_trace_s=${pv_trace:-na} locus_trace_s=$l_trace ratio_trace=$r_trace" \
			"$(cpu "$lr_cpu" "$pv_cpu") evals_per_px=${l_epp:-na} lane_evals_per_px=$l_lanes" \
			"anchor_calls_per_px=$pv_epp $l_acc $pv_acc $x_acc" \
			"target_ratio_trace=$SURFACE_TARGET target_psnr_db=60 target_silhouette_px=5 target_evals_per_px=12" \
			"$(surface_pass "$r_trace" "$l_psnr" "$l_sil" "${l_epp:-na}")"
	done
}

# octree of the trifocal at depth 10 (1024 cells a side in the root cube [-3, 3]^3, nothing
# drawn), cubical vs spherical cell test: figures from locus-render --stats; there is no
# anchor program (anchors.md gives a prototype's figures for the same octree)
bench_octree() {
	scene=fixtures/scenes/bench-octree.scene
	if ! have_bin locus-render || [ ! -f "$scene" ]; then skip octree "$BIN/locus-render or $scene not there yet"; return; fi
	for t in cubical spherical; do
		sed "s/^\( *test \).*/\1$t/" "$scene" > "$W/oct-$t.scene"
		if ! measure "$SLOW_RUNS" /dev/null "$BIN/locus-render" "$W/oct-$t.scene" -o - --stats --quiet; then
			fail "octree-$t" "$M_ERR"; continue
		fi
		emit "BENCH-INFO name=octree-d10-$t locus_s=$M_S locus_rss_mib=$M_MIB locus_cpu_s=$M_CPU" \
			"cells_visited=$(stat oct_visited "$W/err") leaves=$(stat oct_leaves "$W/err")" \
			"octree_ms=$(stat_med trace_ms "$W/errs")"
	done
}

# ---- issue 3: contours and Voronoi (programs by the 2D engineer) ----------------

# own_line FILE TAG: from a program's "BENCH TAG SECONDS s k=v..." line, set O_S and O_KV
own_line() {
	O_S=$(awk -v t="$2" '$1 == "BENCH" && $2 == t {print $3; exit}' "$1")
	O_KV=$(awk -v t="$2" '$1 == "BENCH" && $2 == t {for (i = 5; i <= NF; i++) printf "%s%s", (i > 5 ? " " : ""), $i; exit}' "$1")
	[ -n "$O_S" ]
}

bench_contour() {
	if [ ! -f tests/bench/bench_contour.c ]; then skip contour "tests/bench/bench_contour.c not there yet"; return; fi
	if ! build bench_contour tests/bench/bench_contour.c; then
		skip contour "bench_contour does not build yet: $B_ERR"; return
	fi
	if ! measure 1 "$W/contour.out" "$W/bench_contour" -n 7 -o "$W/contour.meta" ||
		! own_line "$W/contour.out" contour-locus; then
		fail contour "bench_contour: ${M_ERR:-no BENCH contour-locus line}"; return
	fi
	l_s=$O_S l_kv=$O_KV l_mib=$M_MIB
	if ! have python3 || [ ! -f tests/bench/contourpy_anchor.py ]; then
		fail contour "python3 or tests/bench/contourpy_anchor.py missing"; return
	fi
	if ! measure 1 "$W/contourpy.out" python3 tests/bench/contourpy_anchor.py -n 7 ||
		! own_line "$W/contourpy.out" contour-contourpy; then
		fail contour "contourpy_anchor.py: ${M_ERR:-no BENCH contour-contourpy line}"; return
	fi
	# their lines give seconds with 6 decimals; keep 4 like the others
	l_s=$(awk -v s="$l_s" 'BEGIN {printf "%.4f", s}') a_s=$(awk -v s="$O_S" 'BEGIN {printf "%.4f", s}')
	line contour "$l_s" contourpy "$a_s" "$l_mib" "$M_MIB" \
		"$(echo "$l_kv" | sed 's/\([a-z_]*\)=/locus_\1=/g')" "$(echo "$O_KV" | sed 's/\([a-z_]*\)=/anchor_\1=/g')" \
		"rss_note=whole_process"
}

bench_voronoi() {
	# the anchor is context only (another task): without qhull-bin the line is a skip, not a failure
	q_s="" q_mib=""
	if have rbox && have qvoronoi; then
		rbox 100000 D2 t1 > "$W/voronoi.pts" 2> /dev/null || { fail voronoi "rbox failed"; return; }
		if ! measure "$SLOW_RUNS" /dev/null qvoronoi o TI "$W/voronoi.pts"; then fail voronoi "$M_ERR"; return; fi
		q_s=$M_S q_mib=$M_MIB
	fi
	if [ ! -f tests/bench/bench_voronoi.c ]; then
		emit "BENCH-SKIP name=voronoi reason=tests/bench/bench_voronoi.c-not-there-yet anchor=qvoronoi" \
			"anchor_s=${q_s:-na} anchor_rss_mib=${q_mib:-na}"; return
	fi
	if ! build bench_voronoi tests/bench/bench_voronoi.c; then
		skip voronoi "bench_voronoi does not build yet: $B_ERR"; return
	fi
	if ! measure 1 "$W/voronoi.out" "$W/bench_voronoi" || ! own_line "$W/voronoi.out" voronoi-locus; then
		fail voronoi "bench_voronoi: ${M_ERR:-no BENCH voronoi-locus line}"; return
	fi
	l_s=$(awk -v s="$O_S" 'BEGIN {printf "%.4f", s}')
	if [ -z "$q_s" ]; then
		emit "BENCH-SKIP name=voronoi reason=rbox/qvoronoi-missing-(Debian-qhull-bin) locus_s=$l_s" \
			"locus_rss_mib=$M_MIB $O_KV"
		return
	fi
	line voronoi "$l_s" qvoronoi "$q_s" "$M_MIB" "$q_mib" "$O_KV" "note=context_only_different_task"
}

# ---- main -------------------------------------------------------------------

RASTER_a_MIB=""
want plot && bench_plot
want check && bench_check
want pov && bench_pov
want octree && bench_octree
want contour && bench_contour
want voronoi && bench_voronoi
# Each scripts/bench.d/GROUP.sh is sourced here: it sees every helper above (emit, measure,
# line, skip, fail, build, $W, $BIN) and defines bench_GROUP, which is then run.
for f in scripts/bench.d/*.sh; do
	[ -f "$f" ] || continue
	g=$(basename "$f" .sh)
	want "$g" || continue
	. "./$f"
	"bench_$g"
done
mv "$RTMP" "$RESULTS"
echo "bench: $(grep -c '^BENCH ' "$RESULTS") comparisons, $(grep -c '^BENCH-SKIP' "$RESULTS") skipped," \
	"$(grep -c '^BENCH-FAIL' "$RESULTS") failed; lines in $RESULTS" >&2
exit "$FAILED"

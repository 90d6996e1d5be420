# render2.sh: bench group "render2" (sourced by scripts/bench.sh): the Mandelbrot gallery plate
# (fixtures/scenes/mandelbrot.scene) ray-traced on the Douady-Hubbard distance estimate against
# the same scene with 'stepping' on its process line, which forces the step-and-bisect path the
# renderer used before the estimate ("today" of issue 13), in the same run, one thread, at the
# plate's 480x360 and at 1024x768. Times are CPU seconds (user + system, medians): on this shared
# machine wall time moves with the other load; wall times are on the line too. The line also
# gives both evaluations per pixel and how far the two pictures are apart (locus-diff: PSNR and
# differing pixels). docs/benchmarks.md (issue 13 section) explains it.

render2_one() {
	r_n=$1 r_scene=$2 r_runs=$3
	sed 's/smooth revolve$/smooth revolve stepping/' "$r_scene" > "$W/$r_n-step.scene"
	if ! grep -q 'stepping$' "$W/$r_n-step.scene"; then fail "$r_n" "no process line to switch to stepping"; return; fi
	if ! measure "$r_runs" /dev/null "$BIN/locus-render" "$W/$r_n-step.scene" --threads 1 --stats -o "$W/$r_n-step.meta"; then
		fail "$r_n" "$M_ERR"; return
	fi
	a_s=$M_CPU a_wall=$M_S a_mib=$M_MIB
	a_epp=$(stat evals_per_pixel "$W/err")
	if ! measure "$BENCH_RUNS" /dev/null "$BIN/locus-render" "$r_scene" --threads 1 --stats -o "$W/$r_n.meta"; then
		fail "$r_n" "$M_ERR"; return
	fi
	l_s=$M_CPU l_wall=$M_S l_mib=$M_MIB
	l_epp=$(stat evals_per_pixel "$W/err")
	"$BIN/locus-diff" "$W/$r_n.meta" "$W/$r_n-step.meta" > "$W/$r_n.diff" 2>&1
	psnr=$(sed -n 's/.*PSNR \([^ ]*\) dB.*/\1/p' "$W/$r_n.diff")
	dpx=$(sed -n 's/.*: \([0-9]*\) of [0-9]* pixels differ.*/\1/p' "$W/$r_n.diff")
	r=$(ratio "$a_s" "$l_s")
	# issue 26: 20x the stepping at 15 evaluations a pixel or fewer (issue 13 asked 30)
	r_pass=$(awk -v r="$r" -v e="${l_epp:-x}" 'BEGIN {
		f = ""
		if (r != "inf" && r + 0 < 20) f = f ",ratio"
		if (e !~ /^[0-9.]+$/ || e + 0 > 15) f = f ",evals"
		print f == "" ? "pass=yes" : "pass=no fails=" substr(f, 2) }')
	line "$r_n" "$l_s" locus-stepping "$a_s" "$l_mib" "$a_mib" \
		"time=cpu locus_wall_s=$l_wall anchor_wall_s=$a_wall ratio_wall=$(ratio "$a_wall" "$l_wall")" \
		"locus_evals_per_pixel=$l_epp anchor_evals_per_pixel=$a_epp target_ratio=20 $r_pass" \
		"target_evals_per_pixel=15 psnr_vs_stepping_db=${psnr:-na} diff_px_vs_stepping=${dpx:-na}"
}

bench_render2() {
	if ! have_bin locus-render || ! have_bin locus-diff; then skip mandelbrot "$BIN/locus-render or locus-diff not built yet"; return; fi
	s=fixtures/scenes/mandelbrot.scene
	render2_one mandelbrot "$s" "$SLOW_RUNS"
	sed 's/^  size 480 360$/  size 1024 768/' "$s" > "$W/mandelbrot-1024.scene"
	# the stepping render at 1024x768 takes about 20 s: once
	render2_one mandelbrot-1024 "$W/mandelbrot-1024.scene" 1
}

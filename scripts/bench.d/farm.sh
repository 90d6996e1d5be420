# farm.sh: bench group "farm" (sourced by scripts/bench.sh; issue 25, docs/farm.md): the 16 frames
# of fixtures/scenes/anim-trifocal.scene, at 1280x852 with supersample 3 (about 0.4 s of CPU a
# frame, so that GNU parallel's own cost, about 0.7 s of CPU for 16 jobs, is not what is
# measured; a farm's frames take seconds), rendered by one process (--threads 1: the anchor, one
# machine's core) against two GNU parallel workers over local job slots, each frame its own
# process and file (--threads 1 each, as a farm node's slot runs it), joined by locus-meta cat;
# the joined file must equal the one process's byte for byte (same=yes). A second line runs the
# two workers on chunks of 8 (two processes). A third gives the cost of a process per frame:
# 16 single-frame processes one after the other against one process of 16 frames, the
# difference per frame (start-up, scene read, output open and rename) next to a frame's render
# time. Wall seconds are what the target (ratio >= 1.8 on 2 cores) is about; CPU seconds are on
# the lines too, since wall time on this shared machine moves with the others' load. The four
# commands run in rounds, one after the other in each round (SLOW_RUNS rounds), so that load
# that comes and goes falls on all of them alike; the figures are medians over the rounds, and
# pair_ratio the median of each round's own ratio. Every renderer process runs in a session of
# its own (setsid), as on a job slot of its own: the kernel's autogroup scheduling gives each
# session, not each process, a fair share of the CPUs, so under other sessions' load two workers
# of one session would share one session's time and no parallel speed-up could show. And
# ratio_cpu_2cores = 2 x anchor CPU / locus CPU is the speed-up two idle cores would give when the
# work splits evenly (an upper bound that load does not move).

bench_farm() {
	if ! have_bin locus-render || ! have_bin locus-meta; then skip farm "$BIN/locus-render or locus-meta not built yet"; return; fi
	if ! command -v parallel > /dev/null 2>&1; then skip farm "GNU parallel missing (Debian package parallel)"; return; fi
	f_scene=$W/farm-anim.scene
	sed 's/^  size 320 240$/  size 1280 852/; s/^  supersample 2$/  supersample 3/' fixtures/scenes/anim-trifocal.scene > "$f_scene"
	if ! grep -q '^  size 1280 852$' "$f_scene"; then fail farm "anim-trifocal.scene: no size line to enlarge"; return; fi
	f_r=$BIN/locus-render
	case $f_r in /*) ;; *) f_r=$(pwd)/$f_r ;; esac
	# one: the anchor, one process, 16 frames, one thread; pf: two GNU parallel workers, a process
	# per frame; ch: two workers on chunks of 8; se: 16 single-frame processes one after the other
	f_one="setsid -w '$f_r' '$f_scene' --frames 16 --threads 1 --quiet -o '$W/farm-one.meta'"
	f_pf="rm -rf '$W/farm-pf' && mkdir '$W/farm-pf' && seq 0 15 | parallel -j2 setsid -w '$f_r' '$f_scene' --frames {}-{} --threads 1 --quiet -o '$W/farm-pf/f-%04d.meta'"
	f_ch="rm -rf '$W/farm-ch' && mkdir '$W/farm-ch' && seq 0 1 | parallel -j2 setsid -w '$f_r' '$f_scene' --frames 16 --chunk 8 --task {} --threads 1 --quiet -o '$W/farm-ch/f-%04d.meta'"
	f_se="rm -rf '$W/farm-se' && mkdir '$W/farm-se' && for k in \$(seq 0 15); do setsid -w '$f_r' '$f_scene' --frames \$k-\$k --threads 1 --quiet -o '$W/farm-se/f-%04d.meta' || exit 1; done"
	for v in one pf ch se; do : > "$W/farm-$v.s"; : > "$W/farm-$v.cpu"; : > "$W/farm-$v.mib"; done
	f_i=0
	while [ "$f_i" -lt "$SLOW_RUNS" ]; do
		for v in one pf ch se; do
			eval "f_cmd=\$f_$v"
			if ! measure 1 /dev/null sh -c "$f_cmd"; then fail farm "$v: $M_ERR"; return; fi
			echo "$M_S" >> "$W/farm-$v.s"; echo "$M_CPU" >> "$W/farm-$v.cpu"; echo "$M_MIB" >> "$W/farm-$v.mib"
		done
		f_i=$((f_i + 1))
	done
	# pair ratios: anchor / variant within each round
	for v in pf ch se; do
		paste "$W/farm-one.s" "$W/farm-$v.s" | awk '{printf "%.4f\n", $1 / $2}' > "$W/farm-$v.pair"
	done
	a_s=$(median "$W/farm-one.s") a_cpu=$(median "$W/farm-one.cpu") a_mib=$(median "$W/farm-one.mib")
	if ! measure "$SLOW_RUNS" /dev/null "$BIN/locus-meta" cat "$W"/farm-pf/f-*.meta --frames 16 -o "$W/farm-joined.meta"; then
		fail farm "$M_ERR"; return
	fi
	j_s=$M_S
	f_same=no; cmp -s "$W/farm-joined.meta" "$W/farm-one.meta" && f_same=yes
	"$BIN/locus-meta" cat "$W"/farm-ch/f-*.meta --frames 16 -o "$W/farm-joined-ch.meta" 2> /dev/null
	c_same=no; cmp -s "$W/farm-joined-ch.meta" "$W/farm-one.meta" && c_same=yes
	for v in pf ch; do
		l_s=$(median "$W/farm-$v.s") l_cpu=$(median "$W/farm-$v.cpu") l_mib=$(median "$W/farm-$v.mib")
		r=$(ratio "$a_s" "$l_s")
		if [ $v = pf ]; then n=farm-16-frames-2-workers extra="join_s=$j_s same=$f_same"; else n=farm-16-frames-2-chunks extra="same=$c_same"; fi
		line "$n" "$l_s" one-process-1-thread "$a_s" "$l_mib" "$a_mib" \
			"time=wall pair_ratio=$(median "$W/farm-$v.pair") $(cpu "$l_cpu" "$a_cpu")" \
			"ratio_cpu_2cores=$(ratio "$(awk -v a="$a_cpu" 'BEGIN {print 2 * a}')" "$l_cpu") $extra target_ratio=1.8 pass=$(pass "$r" 1.8)"
	done
	s_s=$(median "$W/farm-se.s") s_cpu=$(median "$W/farm-se.cpu")
	# per frame: CPU figures (steady under load), wall ones beside them (not)
	frame_cpu_ms=$(awk -v a="$a_cpu" 'BEGIN {printf "%.1f", a * 1000 / 16}')
	over_cpu_ms=$(awk -v s="$s_cpu" -v a="$a_cpu" 'BEGIN {printf "%.1f", (s - a) * 1000 / 16}')
	frame_ms=$(awk -v a="$a_s" 'BEGIN {printf "%.1f", a * 1000 / 16}')
	over_ms=$(awk -v s="$s_s" -v a="$a_s" 'BEGIN {printf "%.1f", (s - a) * 1000 / 16}')
	# GNU parallel's own cost for 16 jobs that do nothing
	measure "$SLOW_RUNS" /dev/null sh -c "seq 0 15 | parallel -j2 true" || M_CPU=na
	emit "BENCH name=farm-process-per-frame locus_s=$s_s anchor=one-process-16-frames anchor_s=$a_s" \
		"ratio=$(ratio "$a_s" "$s_s") pair_ratio=$(median "$W/farm-se.pair") locus_cpu_s=$s_cpu anchor_cpu_s=$a_cpu" \
		"ratio_cpu=$(ratio "$a_cpu" "$s_cpu") frame_cpu_ms=$frame_cpu_ms overhead_per_process_cpu_ms=$over_cpu_ms" \
		"overhead_pct_cpu=$(awk -v o="$over_cpu_ms" -v f="$frame_cpu_ms" 'BEGIN {if (f > 0) printf "%.1f", 100 * o / f; else print "na"}')" \
		"frame_wall_ms=$frame_ms overhead_per_process_wall_ms=$over_ms parallel_16_empty_jobs_cpu_s=$M_CPU"
}

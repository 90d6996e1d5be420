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
# the lines too, since wall time on this shared machine moves with the others' load, and
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
	# the anchor: one process, 16 frames, one thread
	if ! measure "$SLOW_RUNS" /dev/null "$f_r" "$f_scene" --frames 16 --threads 1 --quiet -o "$W/farm-one.meta"; then
		fail farm "$M_ERR"; return
	fi
	a_s=$M_S a_cpu=$M_CPU a_mib=$M_MIB
	# two GNU parallel workers, a process per frame, then the join
	if ! measure "$SLOW_RUNS" /dev/null sh -c "rm -rf '$W/farm-pf' && mkdir '$W/farm-pf' && seq 0 15 |
		parallel -j2 '$f_r' '$f_scene' --frames {}-{} --threads 1 --quiet -o '$W/farm-pf/f-%04d.meta'"; then
		fail farm "$M_ERR"; return
	fi
	l_s=$M_S l_cpu=$M_CPU l_mib=$M_MIB
	if ! measure "$SLOW_RUNS" /dev/null "$BIN/locus-meta" cat "$W"/farm-pf/f-*.meta --frames 16 -o "$W/farm-joined.meta"; then
		fail farm "$M_ERR"; return
	fi
	j_s=$M_S
	f_same=no; cmp -s "$W/farm-joined.meta" "$W/farm-one.meta" && f_same=yes
	r=$(ratio "$a_s" "$l_s")
	line farm-16-frames-2-workers "$l_s" one-process-1-thread "$a_s" "$l_mib" "$a_mib" \
		"time=wall $(cpu "$l_cpu" "$a_cpu") ratio_cpu_2cores=$(ratio "$(awk -v a="$a_cpu" 'BEGIN {print 2 * a}')" "$l_cpu") join_s=$j_s ratio_with_join=$(ratio "$a_s" "$(awk -v a="$l_s" -v b="$j_s" 'BEGIN {print a + b}')")" \
		"same=$f_same target_ratio=1.8 pass=$(pass "$r" 1.8)"
	# two workers on chunks of 8 frames: two processes
	if ! measure "$SLOW_RUNS" /dev/null sh -c "rm -rf '$W/farm-ch' && mkdir '$W/farm-ch' && seq 0 1 |
		parallel -j2 '$f_r' '$f_scene' --frames 16 --chunk 8 --task {} --threads 1 --quiet -o '$W/farm-ch/f-%04d.meta'"; then
		fail farm "$M_ERR"; return
	fi
	c_s=$M_S c_cpu=$M_CPU c_mib=$M_MIB
	"$BIN/locus-meta" cat "$W"/farm-ch/f-*.meta --frames 16 -o "$W/farm-joined-ch.meta" 2> /dev/null
	f_same=no; cmp -s "$W/farm-joined-ch.meta" "$W/farm-one.meta" && f_same=yes
	r=$(ratio "$a_s" "$c_s")
	line farm-16-frames-2-chunks "$c_s" one-process-1-thread "$a_s" "$c_mib" "$a_mib" \
		"time=wall $(cpu "$c_cpu" "$a_cpu") ratio_cpu_2cores=$(ratio "$(awk -v a="$a_cpu" 'BEGIN {print 2 * a}')" "$c_cpu") same=$f_same target_ratio=1.8 pass=$(pass "$r" 1.8)"
	# a process per frame against one process: what each extra process costs
	if ! measure "$SLOW_RUNS" /dev/null sh -c "rm -rf '$W/farm-se' && mkdir '$W/farm-se' && for k in \$(seq 0 15); do
		'$f_r' '$f_scene' --frames \$k-\$k --threads 1 --quiet -o '$W/farm-se/f-%04d.meta' || exit 1; done"; then
		fail farm "$M_ERR"; return
	fi
	s_s=$M_S s_cpu=$M_CPU
	# per frame: CPU figures (steady under load), wall ones beside them (not)
	frame_cpu_ms=$(awk -v a="$a_cpu" 'BEGIN {printf "%.1f", a * 1000 / 16}')
	over_cpu_ms=$(awk -v s="$s_cpu" -v a="$a_cpu" 'BEGIN {printf "%.1f", (s - a) * 1000 / 16}')
	frame_ms=$(awk -v a="$a_s" 'BEGIN {printf "%.1f", a * 1000 / 16}')
	over_ms=$(awk -v s="$s_s" -v a="$a_s" 'BEGIN {printf "%.1f", (s - a) * 1000 / 16}')
	# GNU parallel's own cost for 16 jobs that do nothing
	measure "$SLOW_RUNS" /dev/null sh -c "seq 0 15 | parallel -j2 true" || M_CPU=na
	emit "BENCH name=farm-process-per-frame locus_s=$s_s anchor=one-process-16-frames anchor_s=$a_s" \
		"ratio=$(ratio "$a_s" "$s_s") locus_cpu_s=$s_cpu anchor_cpu_s=$a_cpu ratio_cpu=$(ratio "$a_cpu" "$s_cpu")" \
		"frame_cpu_ms=$frame_cpu_ms overhead_per_process_cpu_ms=$over_cpu_ms" \
		"overhead_pct_cpu=$(awk -v o="$over_cpu_ms" -v f="$frame_cpu_ms" 'BEGIN {if (f > 0) printf "%.1f", 100 * o / f; else print "na"}')" \
		"frame_wall_ms=$frame_ms overhead_per_process_wall_ms=$over_ms parallel_16_empty_jobs_cpu_s=$M_CPU"
}

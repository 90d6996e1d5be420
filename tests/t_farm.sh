#!/bin/sh
# t_farm.sh: rendering an animation on a farm (docs/farm.md): --frames lists and chunks, one whole
# file per frame, --skip-existing, failed frames, locus-meta cat, DPX sequences from many nodes;
# then the real engines: GNU parallel over local job slots, and a single-node Slurm (munged,
# slurmctld and slurmd started here on loopback ports from a generated slurm.conf) running
# scripts/farm/slurm-array.sh with frames already rendered and one task failing and rerun.
# A part whose engine cannot run here prints "SKIP t_farm PART: reason" instead of passing.
# FARM_REPORT=FILE keeps the Slurm run's records (scontrol, job completion log) in FILE.
. tests/lib.sh
R="$BIN/locus-render"
M="$BIN/locus-meta"
TOP=$(pwd)
ABIN=$(cd "$BIN" && pwd)
skip() { echo "SKIP t_farm $*"; }

# a small animation: frame k is t = k, every frame a different picture
printf 'view\n  eye 0 1 -6\n  size 40 30\nend\nlight point 3 6 -5\nobject a\n  point -1+0.2*t 0 0 weight 1+0.1*t\n  point 1 0 0\n  point 0 1.2 0.3\n  c 3.4+0.05*t\nend\n' > "$T/anim.scene"
A="$T/anim.scene"

# ---- frame lists and chunks ------------------------------------------------------------------
frames() { "$R" "$A" --list-frames "$@" 2>&1 | tr '\n' ' '; }
[ "$(frames --frames 4)" = "0 1 2 3 " ] && ok "--frames 4: frames 0..3" || notok "--frames 4: $(frames --frames 4)"
[ "$(frames --frames 3-12x4,1,20-21)" = "1 3 7 11 20 21 " ] && ok "--frames A-BxS and comma lists, sorted" \
	|| notok "--frames 3-12x4,1,20-21: $(frames --frames 3-12x4,1,20-21)"
# OpenCue's case: 10 frames in chunks of 4 are 4, 4 and 2; the task from SLURM_ARRAY_TASK_ID
c0=$(frames --frames 0-9 --chunk 4 --task 0); c2=$(SLURM_ARRAY_TASK_ID=2 frames --frames 0-9 --chunk 4)
[ "$c0" = "0 1 2 3 " ] && [ "$c2" = "8 9 " ] && ok "chunks of 4 over 10 frames: the last chunk holds 2" || notok "chunks: '$c0' '$c2'"
expect_exit 64 "a task past the last chunk refused" "$R" "$A" --frames 0-9 --chunk 4 --task 3 --list-frames
expect_exit 64 "--chunk without a task or SLURM_ARRAY_TASK_ID refused" env -u SLURM_ARRAY_TASK_ID "$R" "$A" --frames 0-9 --chunk 4 --list-frames
expect_exit 64 "a frame named twice refused" "$R" "$A" --frames 0-3,2 --list-frames
expect_exit 64 "--frames 3-x refused" "$R" "$A" --frames 3-x --list-frames
expect_exit 64 "a pattern with two numbers refused" "$R" "$A" -o "$T/a-%d-%d.meta"
expect_exit 64 "a pattern with %s refused" "$R" "$A" -o "$T/a-%s.meta"
expect_exit 64 "--skip-existing without a pattern refused" "$R" "$A" --frames 2 --skip-existing -o "$T/x.meta"

# ---- one file per frame, joined ------------------------------------------------------------
"$R" "$A" --frames 8 -o "$T/one.meta" --quiet
"$R" "$A" --frames 8 --binary -o "$T/one.lmb" --quiet
mkdir -p "$T/pf"
"$R" "$A" --frames 8 -o "$T/pf/f-%04d.meta" --quiet; rc=$?
n=$(ls "$T/pf" | grep -c '^f-000[0-7]\.meta$')
[ $rc = 0 ] && [ "$n" = 8 ] && ok "-o f-%04d.meta: eight files f-0000 ... f-0007" || notok "per-frame files: exit $rc, $n files"
[ "$(grep -c '^page' "$T/pf/f-0003.meta")" = 1 ] && head -3 "$T/pf/f-0003.meta" | grep -q '^# frame 3 t=3$' && tail -1 "$T/pf/f-0003.meta" | grep -q '^# end frame 3$' \
	&& ok "a frame's file: its page between '# frame 3 t=3' and '# end frame 3'" || notok "frame records of f-0003.meta"
"$M" cat "$T"/pf/f-*.meta -o "$T/joined.meta"; rc=$?
[ $rc = 0 ] && same_file "locus-meta cat of the eight files: the bytes of one --frames 8 run" "$T/joined.meta" "$T/one.meta" || notok "cat exit $rc"
"$R" "$A" --frames 8 -o "$T/pf/b-%02d.lmb" --quiet
"$M" cat "$T"/pf/b-*.lmb -o "$T/joined.lmb"
same_file "binary: -o b-%02d.lmb files joined equal one --binary run" "$T/joined.lmb" "$T/one.lmb"
# chunks written as one file each (--chunk without a pattern), joined in any order given
for i in 0 1 2; do "$R" "$A" --frames 8 --chunk 3 --task $i -o "$T/chunk-$i.meta" --quiet; done
"$M" cat "$T/chunk-2.meta" "$T/chunk-0.meta" "$T/chunk-1.meta" -o "$T/joined-c.meta"
same_file "chunk files 3 + 3 + 2, given out of order, joined: one run" "$T/joined-c.meta" "$T/one.meta"
"$M" cat "$T/pf/f-0000.meta" "$T/pf/f-0001.meta" "$T/pf/f-0003.meta" -o "$T/bad.meta" 2> "$T/err"; rc=$?
[ $rc = 65 ] && [ ! -e "$T/bad.meta" ] && [ "$(wc -l < "$T/err")" = 1 ] && grep -q "frame 2 is missing" "$T/err" \
	&& ok "cat: a missing frame is one line naming frame 2, exit 65, no output" || notok "cat missing: exit $rc, $(cat "$T/err")"
"$M" cat "$T"/pf/f-000[0-3].meta "$T/chunk-1.meta" -o "$T/bad.meta" 2> "$T/err"; rc=$?
[ $rc = 65 ] && [ ! -e "$T/bad.meta" ] && [ "$(wc -l < "$T/err")" = 1 ] && grep -q "frame 3 is duplicated: in .*f-0003.meta and in .*chunk-1.meta" "$T/err" \
	&& ok "cat: a duplicated frame names it and both files, exit 65, no output" || notok "cat duplicate: exit $rc, $(cat "$T/err")"
"$M" cat "$T"/pf/f-*.meta --frames 10 -o "$T/bad.meta" 2> "$T/err"; rc=$?
[ $rc = 65 ] && [ ! -e "$T/bad.meta" ] && grep -q "frame 8 is missing (--frames 10)" "$T/err" \
	&& ok "cat --frames 10: frame 8 missing at the end" || notok "cat --frames: exit $rc, $(cat "$T/err")"
"$R" "$A" -o "$T/still.meta" --quiet
"$M" cat "$T/still.meta" -o "$T/bad.meta" 2> "$T/err"; rc=$?
[ $rc = 65 ] && grep -q "expected frame records" "$T/err" && ok "cat: a file without frame records refused" || notok "cat still: $rc $(cat "$T/err")"

# ---- --skip-existing: complete files stay, incomplete and foreign ones are rendered again ----
mkdir -p "$T/sk"
"$R" "$A" --frames 0-1 -o "$T/sk/f-%04d.meta" --quiet
head -c 2000 "$T/pf/f-0002.meta" > "$T/sk/f-0002.meta"          # cut short
cp "$T/pf/f-0005.meta" "$T/sk/f-0003.meta"                        # another frame's file
touch -d '2000-01-01' "$T/sk/f-0000.meta"
"$R" "$A" --frames 0-4 -o "$T/sk/f-%04d.meta" --skip-existing 2> "$T/err"; rc=$?
old=$(find "$T/sk/f-0000.meta" ! -newer "$T/anim.scene" | wc -l)
[ $rc = 0 ] && [ "$old" = 1 ] && grep -q "frame 0: .* is there and complete, skipped" "$T/err" && grep -q "frame 2: rendered again: .*f-0002.meta:" "$T/err" \
	&& grep -q "frame 3: rendered again: .*expected the records of frame 3 alone" "$T/err" \
	&& ok "--skip-existing: frame 0 left untouched, the truncated and the foreign file rendered again" || notok "skip: exit $rc, $(cat "$T/err")"
for k in 0 1 2 3 4; do cmp -s "$T/sk/f-000$k.meta" "$T/pf/f-000$k.meta" || echo $k; done > "$T/diff"
[ ! -s "$T/diff" ] && ok "after --skip-existing every frame is the one-run frame" || notok "frames differ: $(cat "$T/diff")"
# meshes: one STL per frame; a cut STL is incomplete
"$R" "$A" --frames 3 -o "$T/sk/m-%02d.stl" --quiet && head -c 300 "$T/sk/m-01.stl" > "$T/m1" && mv "$T/m1" "$T/sk/m-01.stl"
"$R" "$A" --frames 3 -o "$T/sk/m-%02d.stl" --skip-existing 2> "$T/err"
grep -q "frame 0: .*m-00.stl is there and complete" "$T/err" && grep -q "frame 1: rendered again: .*expected 84 + 50 bytes a triangle" "$T/err" \
	&& ok "--skip-existing on STL frames: sizes checked" || notok "stl skip: $(cat "$T/err")"
expect_exit 64 "a mesh of several frames needs a pattern" "$R" "$A" --frames 3 -o "$T/m.stl"

# ---- failed frames: the others go on; the status and stderr say which ------------------------
printf 'object a\n  point 0 0 2e5*t\n  c 1\nend\nview\n  size 8 8\nend\n' > "$T/far.scene"
mkdir -p "$T/ff"
"$R" "$T/far.scene" --frames 0-7 -o "$T/ff/f-%d.meta" --quiet 2> "$T/err"; rc=$?
n=$(ls "$T/ff" | wc -l)
[ $rc = 65 ] && [ "$n" = 6 ] && grep -q "^locus-render: 2 of 8 frames failed: 6 7$" "$T/err" \
	&& ok "frames 6 and 7 fail, 0-5 written, exit 65, stderr names 6 and 7" || notok "failures: exit $rc, $n files, $(tail -1 "$T/err")"
rm -f "$T"/ff/*
"$R" "$T/far.scene" --frames 5-7,0 -o "$T/ff/f-%d.meta" --quiet --fail-fast 2> "$T/err"; rc=$?
[ $rc = 65 ] && [ -e "$T/ff/f-5.meta" ] && [ ! -e "$T/ff/f-7.meta" ] && grep -q "1 of 4 frames failed: 6; --fail-fast left 1 not rendered (7 ... 7)" "$T/err" \
	&& ok "--fail-fast stops at frame 6" || notok "fail-fast: exit $rc, $(tail -1 "$T/err")"
mkdir -p "$T/io/f-0002.meta"                                     # a frame whose file cannot be written
"$R" "$A" --frames 4 -o "$T/io/f-%04d.meta" --quiet 2> "$T/err"; rc=$?
[ $rc = 74 ] && [ -e "$T/io/f-0003.meta" ] && grep -q "1 of 4 frames failed: 2$" "$T/err" && ok "an unwritable frame: 74, the others written" \
	|| notok "io failure: exit $rc, $(cat "$T/err")"

# ---- DPX sequences from many nodes -----------------------------------------------------------
export SOURCE_DATE_EPOCH=1700000000
mkdir -p "$T/dpx1" "$T/dpxn"
"$BIN/locus-film" --size 48x32 "$T/one.meta" -o "$T/dpx1/f-%04d.dpx"; rc=$?
for f in "$T"/pf/f-*.meta; do "$BIN/locus-film" --size 48x32 "$f" -o "$T/dpxn/f-%04d.dpx" || rc=$?; done
d=0; for f in "$T"/dpx1/*.dpx; do cmp -s "$f" "$T/dpxn/$(basename "$f")" || d=$((d + 1)); done
[ $rc = 0 ] && [ "$(ls "$T/dpxn" | wc -l)" = 8 ] && [ $d = 0 ] && [ -e "$T/dpxn/f-0007.dpx" ] \
	&& ok "locus-film -o f-%04d.dpx: frames from eight files equal those of one file, named by frame" || notok "dpx: exit $rc, $d differ"
if command -v oiiotool > /dev/null 2>&1; then
	oiiotool --info -v "$T/dpxn/f-0007.dpx" > "$T/oiio.txt" 2>&1
	grep -q 'dpx:FramePosition: 7' "$T/oiio.txt" && grep -q 'dpx:FrameRate: 24' "$T/oiio.txt" && grep -q 'dpx:TimeCode: "00:00:00:07"' "$T/oiio.txt" \
		&& ok "OpenImageIO reads frame 7: position 7, 24 fps, time code 00:00:00:07" || notok "oiiotool: $(grep -i 'frame\|time' "$T/oiio.txt")"
	"$BIN/locus-film" --size 48x32 "$T/pf/f-0005.meta" --frame-rate 25 -o "$T/r25.dpx"
	oiiotool --info -v "$T/r25.dpx" 2>&1 | grep -q 'dpx:TimeCode: "00:00:00:05"' && ok "--frame-rate 25" || notok "--frame-rate 25"
else
	skip "oiio: oiiotool missing (openimageio-tools)"
fi
if command -v ffprobe > /dev/null 2>&1; then
	ffprobe -v error -start_number 0 -i "$T/dpxn/f-%04d.dpx" -count_frames -show_entries stream=nb_read_frames -show_entries frame_tags=timecode -of compact > "$T/ffp.txt" 2>&1
	grep -q 'nb_read_frames=8' "$T/ffp.txt" && grep -q 'timecode=00:00:00:07' "$T/ffp.txt" && grep -q 'timecode=00:00:00:00' "$T/ffp.txt" \
		&& ok "ffprobe reads the eight DPX as one sequence with time codes 00:00:00:00 ... 07" || notok "ffprobe: $(tail -3 "$T/ffp.txt")"
else
	skip "ffmpeg: ffprobe missing (ffmpeg)"
fi
unset SOURCE_DATE_EPOCH

# ---- GNU parallel over two local job slots ---------------------------------------------------
if command -v parallel > /dev/null 2>&1 && parallel --version 2>/dev/null | grep -q 'GNU parallel'; then
	mkdir -p "$T/gp"
	"$R" "$A" --frames 0-2 -o "$T/gp/f-%04d.meta" --quiet            # some frames already there
	"$R" "$A" --frames 8 --list-frames | timeout 120 parallel -j2 --joblog "$T/gp.log" \
		"$R" "$A" --frames {}-{} --threads 1 --skip-existing --quiet -o "$T/gp/f-%04d.meta"; rc=$?
	"$M" cat "$T"/gp/f-*.meta --frames 8 -o "$T/gp.meta"
	[ $rc = 0 ] && [ "$(tail -n +2 "$T/gp.log" | wc -l)" = 8 ] && same_file "GNU parallel -j2, frames 0-2 already there: joined equals one process" "$T/gp.meta" "$T/one.meta" \
		|| notok "parallel: exit $rc"
else
	skip "parallel: GNU parallel missing"
fi

# ---- a single-node Slurm ---------------------------------------------------------------------
slurm_test() {
	for p in munged slurmctld slurmd sbatch scontrol sinfo; do
		command -v $p > /dev/null 2>&1 || { skip "slurm: $p missing (munge, slurm-wlm)"; return 0; }
	done
	[ "$(id -u)" = 0 ] || { skip "slurm: slurmd runs jobs as their user and needs root here"; return 0; }
	S="$T/slurm"
	mkdir -p "$S/state" "$S/spool" "$S/log" "$S/frames"
	chmod 755 "$T" "$S"
	dd if=/dev/urandom of="$S/munge.key" bs=1024 count=1 2> /dev/null && chmod 600 "$S/munge.key"
	ports=$(python3 -c 'import socket
s=[socket.socket() for i in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(" ".join(str(x.getsockname()[1]) for x in s))')
	set -- $ports
	node=$(hostname -s 2>/dev/null || hostname)
	cat > "$S/slurm.conf" <<EOF
ClusterName=locus
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$1
SlurmdPort=$2
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$S/munge.sock
CredType=cred/munge
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
SlurmctldLogFile=$S/log/slurmctld.log
SlurmdLogFile=$S/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/linux
JobAcctGatherFrequency=1
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$S/log/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
PlugStackConfig=$S/plugstack.conf
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN
PartitionName=farm Nodes=$node Default=YES MaxTime=10 State=UP
EOF
	: > "$S/plugstack.conf"
	export SLURM_CONF="$S/slurm.conf"
	# the daemons in the foreground of background jobs, each bounded; stopped on every way out
	timeout 300 munged -F -f --socket="$S/munge.sock" --key-file="$S/munge.key" --log-file="$S/log/munged.log" \
		--pid-file="$S/munged.pid" --seed-file="$S/munge.seed" --num-threads=4 > "$S/log/munged.out" 2>&1 &
	MUNGE_PID=$!
	i=0; while [ ! -S "$S/munge.sock" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
	[ -S "$S/munge.sock" ] || { skip "slurm: munged did not start: $(tail -1 "$S/log/munged.out")"; return 0; }
	timeout 300 slurmctld -D -i > "$S/log/ctld.out" 2>&1 &
	CTLD_PID=$!
	timeout 300 slurmd -D -N "$node" > "$S/log/d.out" 2>&1 &
	SLURMD_PID=$!
	i=0
	until timeout 5 sinfo -h -o %t 2> /dev/null | grep -q idle; do
		i=$((i + 1))
		if [ $i -ge 30 ]; then
			skip "slurm: the node did not come up in 30 s: $(tail -1 "$S/log/slurmd.log" 2>/dev/null) $(tail -1 "$S/log/slurmctld.log" 2>/dev/null)"
			return 0
		fi
		sleep 1
	done
	ok "slurm: munged, slurmctld and slurmd up on 127.0.0.1:$1/$2, node $node idle"
	# frames 0-1 pre-rendered; frame 9's file cannot be written (a directory in its place), so
	# task 2 (frames 8-11 of 0-13 in chunks of 4) fails while the others finish
	"$R" "$A" --frames 0-1 -o "$S/frames/f-%04d.meta" --quiet
	mkdir "$S/frames/f-0009.meta"
	"$R" "$A" --frames 14 -o "$S/one.meta" --quiet
	cd "$S"
	LOCUS_RENDER="$ABIN/locus-render" timeout 180 sbatch --wait --parsable --array=0-3%2 -o "$S/log/task-%a.log" \
		"$TOP/scripts/farm/slurm-array.sh" "$A" 0-13 4 "$S/frames/f-%04d.meta" > "$S/job1" 2> "$S/sbatch1.err"; rc=$?
	cd "$TOP"
	job=$(cut -d';' -f1 < "$S/job1")
	[ -n "$job" ] && [ $rc != 0 ] && grep -q "JobState=FAILED .*ArrayTaskId=2 .*ExitCode=74:0" "$S/log/jobcomp.txt" \
		&& [ "$(grep -c 'JobState=COMPLETED' "$S/log/jobcomp.txt")" = 3 ] \
		&& ok "sbatch --array=0-3%2: tasks 0, 1, 3 completed, task 2 failed with 74 (frame 9 unwritable)" \
		|| notok "array job $job: sbatch exit $rc; $(cat "$S/sbatch1.err") $(cat "$S/log/jobcomp.txt")"
	grep -q "frame 0: .* is there and complete, skipped" "$S/log/task-0.log" && grep -q "1 of 4 frames failed: 9$" "$S/log/task-2.log" \
		&& ok "task logs: frame 0 skipped (pre-rendered), task 2 names frame 9" || notok "task logs: $(cat "$S"/log/task-*.log)"
	scontrol show job "$job" > "$S/scontrol1.txt" 2>&1
	grep -q "ArrayTaskThrottle=2" "$S/scontrol1.txt" && ok "scontrol: the array ran with at most 2 tasks at once" || notok "throttle: $(head -3 "$S/scontrol1.txt")"
	# the node is fixed; until task 2 runs again, cat refuses the set
	rmdir "$S/frames/f-0009.meta"
	"$M" cat "$S"/frames/f-*.meta --frames 14 -o "$S/joined.meta" 2> "$S/cat1.err"; rc=$?
	[ $rc = 65 ] && [ ! -e "$S/joined.meta" ] && grep -q "^locus-meta: frame 9 is missing" "$S/cat1.err" \
		&& ok "before the rerun cat refuses: $(cat "$S/cat1.err")" || notok "cat before rerun: exit $rc $(cat "$S/cat1.err")"
	# task 2 alone is submitted again and renders only frame 9
	cd "$S"
	LOCUS_RENDER="$ABIN/locus-render" timeout 120 sbatch --wait --parsable --array=2 -o "$S/log/rerun-%a.log" \
		"$TOP/scripts/farm/slurm-array.sh" "$A" 0-13 4 "$S/frames/f-%04d.meta" > "$S/job2" 2> "$S/sbatch2.err"; rc=$?
	cd "$TOP"
	job2=$(cut -d';' -f1 < "$S/job2")
	[ $rc = 0 ] && [ "$(grep -c 'is there and complete, skipped' "$S/log/rerun-2.log")" = 3 ] \
		&& ok "rerun of task 2 (job $job2): frames 8, 10, 11 skipped, frame 9 rendered" || notok "rerun: exit $rc $(cat "$S/sbatch2.err" "$S"/log/rerun-2.log)"
	"$M" cat "$S"/frames/f-*.meta --frames 14 -o "$S/joined.meta"; rc=$?
	[ $rc = 0 ] && same_file "Slurm array + rerun, joined: the bytes of one --frames 14 run" "$S/joined.meta" "$S/one.meta" || notok "cat after rerun: $rc"
	scontrol show job "$job2" > "$S/scontrol2.txt" 2>&1
	if [ -n "${FARM_REPORT:-}" ]; then
		{ echo "# sacct: $(timeout 10 sacct -j "$job" 2>&1 | head -1)"; echo "# job completion log (jobcomp/filetxt)"; cat "$S/log/jobcomp.txt"
		  echo "# scontrol show job $job (after the run)"; cat "$S/scontrol1.txt"; echo "# scontrol show job $job2"; cat "$S/scontrol2.txt"
		  echo "# task logs"; for f in "$S"/log/task-*.log "$S"/log/rerun-*.log; do echo "## $f"; cat "$f"; done; } > "$FARM_REPORT"
	fi
	return 0
}
stop_slurm() {
	for p in ${SLURMD_PID:-} ${CTLD_PID:-} ${MUNGE_PID:-}; do kill "$p" 2> /dev/null; done
	for p in ${SLURMD_PID:-} ${CTLD_PID:-} ${MUNGE_PID:-}; do
		i=0; while kill -0 "$p" 2> /dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
		kill -9 "$p" 2> /dev/null
	done
	SLURMD_PID= CTLD_PID= MUNGE_PID=
}
trap 'stop_slurm' EXIT
trap 'stop_slurm; exit 130' INT TERM HUP
slurm_test
stop_slurm
done_tests

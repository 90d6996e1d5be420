#!/bin/sh
# t_reliability.sh: every program (each bin/locus-*, fed as the table in feed() says) given
# truncated, garbage, enormous, NaN/infinite and wrong-version inputs answers with one line on
# stderr naming the input and the right exit code, within a time and memory bound, and leaves no
# file in its output directory; outputs to a device node, /dev/full, a missing directory and a
# planted temporary name are safe; SIGTERM mid-write leaves nothing.
# A failing check whose name matches a PENDING pattern is reported "ok ... # TODO" (the fix is in
# another branch); the coordinator empties the list when the fixes are merged.
PENDING="
"
# why each pending check fails today (first matching glob)
pending_reason() {
	case $1 in
	*:mode-kept) echo "w-io: the temporary renamed over a target does not take the target's mode" ;;
	*:devnode-*) echo "w-io: a device node or FIFO given as -o is replaced by a regular file" ;;
	*:planted-*) echo "w-io: locus-meta writes a fixed OUT.tmp (O_TRUNC, no O_EXCL, follows symlinks)" ;;
	*:sigterm-clean) echo "w-io: SIGTERM leaves the temporary behind" ;;
	*:stdout-full) echo "w-io: a write error on standard output does not give its cause (strerror)" ;;
	*:full-message) echo "w-io: a write error on standard output is silent" ;;
	render:hex-number|render:huge-constant) echo "w-bounds: scene numbers not checked against docs/scene-language.md" ;;
	render:nesting-*) echo "w-bounds: no limit on shape nesting depth or evaluation cost" ;;
	*:dash-fine) echo "w-fw: dash pieces not bounded by the pixels a path touches" ;;
	diff:img-huge-*) echo "w-bounds: the image readers allocate width x height x 3 from the header before checking the data" ;;
	diff:stdin-zero) echo "w-bounds: locus-diff reads a whole input into memory before looking at it" ;;
	diff:rgba-stable) echo "w-bounds: the PNG reader composites an RGBA picture onto uninitialised memory" ;;
	*) echo "?" ;;
	esac
}
. tests/lib.sh
D=$T/rel
mkdir -p "$D/in" "$D/out"
MEM_KB=1048576      # the memory bound (see LIMIT)
TIME=10             # seconds for an answer to bad input
TIME_WORK=3         # seconds for the work-bound cases (each pending one costs this much)

# the memory bound: ulimit -v natively; under the sanitizers (which reserve terabytes of address
# space) the allocator refuses a single allocation over 1 GiB and a resident size over 1.5 GiB
if [ "${SANITIZE:-}" = 1 ]; then
	LIMIT="export ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:max_allocation_size_mb=1024:allocator_may_return_null=1:hard_rss_limit_mb=1536\""
else
	LIMIT="ulimit -v $MEM_KB"
fi
in_pending() { set -f; for p in $PENDING; do case $1 in $p) set +f; return 0 ;; esac; done; set +f; return 1; }
# res NAME PASS DESC: one line, honouring PENDING
res() {
	n=$1 pass=$2; shift 2
	if [ "$pass" = 1 ]; then ok "$n: $*"
	elif in_pending "$n"; then ok "$n # TODO pending fix in another branch: $(pending_reason "$n") (now: $*)"
	else notok "$n: $*"; fi
}

# ---- the programs and how to feed them -----------------------------------------------------
# feed KEY IN OUT: the command line of program KEY reading IN and writing OUT (see ext)
feed() {
	k=$1 i=$2 o=$3
	case $k in
	render) echo "$BIN/locus-render --quiet $i -o $o" ;;
	meta-check) echo "$BIN/locus-meta check $i" ;;
	meta-fmt) echo "$BIN/locus-meta fmt $i -o $o" ;;
	meta-info) echo "$BIN/locus-meta info $i" ;;
	meta-convert) echo "$BIN/locus-meta convert $i -o $o" ;;
	raster) echo "$BIN/locus-raster $i -o $o" ;;
	play) echo "$BIN/locus-play -d ppm $i -o $o" ;;
	diff) echo "$BIN/locus-diff $i $D/in/good.png" ;;
	*) echo "$BIN/locus-$k $i -o $o" ;;   # a later driver: meta in, a file out
	esac
}
# the output file name of program KEY ("" = it writes only standard output)
ext() {
	case $1 in render|meta-fmt) echo out.meta ;; meta-convert) echo out.lmb ;; raster) echo out.png ;;
	play) echo out.ppm ;; meta-check|meta-info|diff) echo "" ;; *) echo out ;; esac
}
# what each program reads
kind() {
	case $1 in render) echo scene ;; diff) echo "meta image" ;; *) echo meta ;; esac
}
KEYS="render meta-check meta-fmt meta-info meta-convert raster play diff"
# (locus-printer is a print server, not a meta-in, file-out program: tests/t_printer.sh)
for p in "$BIN"/locus-*; do
	n=${p##*/locus-}
	case " $KEYS " in *" $n "*) ;; *) case $n in meta|render|raster|play|diff|printer) ;; *) KEYS="$KEYS $n" ;; esac ;; esac
done

# ---- every program answers --help, --version and refuses an unknown option (64) ------------
for p in "$BIN"/locus-*; do
	n=${p##*/}
	"$p" --help > "$D/help" 2>&1; a=$?
	v=$("$p" --version 2>&1); b=$?
	"$p" --no-such-option > /dev/null 2>&1; c=$?
	u=64; [ "$n" = locus-diff ] && u=2   # a diff tool's trouble is 2, as cmp's and diff's (issue 12)
	[ "$a" = 0 ] && [ -s "$D/help" ] && [ "$b" = 0 ] && [ "$c" = "$u" ] && case $v in "$n "*) true ;; *) false ;; esac
	res "${n#locus-}:options" $((1 - $?)) "--help $a, --version $b ('$v'), an unknown option $c"
done

# ---- inputs ----------------------------------------------------------------------------------
I=$D/in
printf 'LOCUS-META 1\npage 32 24\ncolour #ff0000\nwidth 3\nstroke\nmove 2 2\ndraw 30 20\nend\nend-page\n' > "$I/good.meta"
"$BIN/locus-raster" "$I/good.meta" -o "$I/good.png"
# meta
head -c 60 "$I/good.meta" > "$I/m-truncated.meta"
"$BIN/locus-meta" convert "$I/good.meta" -o "$I/good.lmb"
head -c 20 "$I/good.lmb" > "$I/m-truncated.lmb"
awk 'BEGIN { s = 7; for (i = 0; i < 4096; i++) { s = (s * 1103515245 + 12345) % 2147483648; printf "%c", 1 + s % 255 } }' > "$I/m-garbage.meta"
cp fixtures/bad/huge-dims.meta "$I/m-huge-dims.meta"
cp fixtures/bad/huge-dims.lmb "$I/m-huge-dims.lmb"
cp fixtures/bad/long-line.meta "$I/m-long-line.meta"
printf 'LOCUS-META 1\npage 8 8\nimage 0 0 1 1\nrow 4294967295 #000000\nend-page\n' > "$I/m-huge-count.meta"
awk 'BEGIN { print "LOCUS-META 1\npage 8 8\nstroke\nmove 0 0"; for (i = 0; i < 1000001; i++) print "draw 1 1"; print "end\nend-page" }' > "$I/m-many-points.meta"
cp fixtures/bad/nan.meta "$I/m-nan.meta"
cp fixtures/bad/inf.meta "$I/m-inf.meta"
cp fixtures/bad/version2.meta "$I/m-version.meta"
cp fixtures/bad/version2.lmb "$I/m-version.lmb"
: > "$I/m-empty.meta"
# work not bounded by input size (issue 6): a fine dash along one long segment
printf 'LOCUS-META 1\npage 16 16\ndash 0.001\nstroke\nmove -1000000 8\ndraw 1000000 8\nend\nend-page\n' > "$I/m-dash-fine.meta"
# scene
cp fixtures/fuzz/scene/default.scene "$I/s-good.scene"
head -c "$(( $(wc -c < "$I/s-good.scene") / 2 ))" "$I/s-good.scene" > "$I/s-truncated.scene"
cp "$I/m-garbage.meta" "$I/s-garbage.scene"
printf 'view\n  size 99999 99999\nend\nobject a\n  point 0 0 0\n  c 1\nend\n' > "$I/s-huge-size.scene"
awk 'BEGIN { printf "object a\n  point 0 0 0\n  c 1"; for (i = 0; i < 300000; i++) printf " + 0"; print "\nend" }' > "$I/s-long-line.scene"
printf 'object a\n  point 0 0 0\n  c nan\nend\n' > "$I/s-nan.scene"
printf 'object a\n  point 0 0 0\n  c inf\nend\n' > "$I/s-inf.scene"
printf 'object a\n  point 0 0 0\n  c 1e308\nend\n' > "$I/s-huge-constant.scene"
printf 'view\n  size 0x10 0x8\nend\nobject a\n  point 0 0 0\n  c 1\nend\n' > "$I/s-hex-number.scene"
printf 'LOCUS-SCENE 2\nobject a\n  point 0 0 0\n  c 1\nend\n' > "$I/s-version.scene"
# nesting (issue 6): each shape the distance to the previous one, three times over twelve levels
# (cost about 3^depth an evaluation), and twice over twenty levels (the parser's region step)
nest() {
	awk -v refs="$1" -v depth="$2" 'BEGIN { print "view\n  size 8 8\nend\nshape s0\n  point 0 0 0\n  c 1\nend"
		for (i = 1; i <= depth; i++) { printf "shape s%d\n", i
			for (j = 0; j < refs; j++) printf "  distance-to s%d\n", i - 1
			print "  c 0.1\n  bound -3 -3 -3 3 3 3\nend" }
		printf "object o\n  distance-to s%d\n  c 0.1\nend\n", depth }'
}
nest 3 12 > "$I/s-nesting-time.scene"
nest 2 20 > "$I/s-nesting-parse-time.scene"
# images
head -c 40 "$I/good.png" > "$I/img-truncated.png"
printf 'P6\n32 24\n255\nabc' > "$I/img-truncated.ppm"
"$BIN/locus-raster" -f rle "$I/good.meta" -o "$I/good.rle"
head -c 20 "$I/good.rle" > "$I/img-truncated.rle"
printf 'LRLE\002\000\000\000\040\000\000\000\030' > "$I/img-version.rle"
printf 'LRLE\001\000\001\000\000\000\001\000\000\000\000\000' > "$I/img-huge-rle.rle"
printf 'P6\n65535 65535\n255\n\000\000\000' > "$I/img-huge-ppm.ppm"
# a PNG header claiming 30000 x 30000 with nothing behind it (the CRC is right)
python3 -c '
import struct, sys, zlib
ihdr = struct.pack(">IIBBBBB", 30000, 30000, 8, 2, 0, 0, 0)
c = b"IHDR" + ihdr
sys.stdout.buffer.write(b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + c + struct.pack(">I", zlib.crc32(c)))' > "$I/img-huge-png.png" 2>/dev/null

# ---- bad inputs ------------------------------------------------------------------------------
# run_bad KEY CASE FILE WANT: the program answers within the bounds, one line naming the file,
# exit WANT, nothing left in the output directory
run_bad() {
	k=$1 c=$2 f=$3 want=$4
	[ "$k" = diff ] && want=2   # locus-diff: 2 for any trouble, as cmp and diff (issue 12)
	o=$D/out/$k-$c
	rm -rf "$o" && mkdir -p "$o"
	cmd=$(feed "$k" "$f" "$o/$(ext "$k")")
	lim=$LIMIT
	sh -c "$lim; exec timeout -s KILL $TIME $cmd" > "$o.stdout" 2> "$o.stderr" < /dev/null
	rc=$?
	lines=$(wc -l < "$o.stderr")
	left=$(ls -A "$o")
	base=${f##*/}
	why=""
	[ "$rc" = "$want" ] || why="$why exit $rc (wanted $want);"
	[ "$rc" = 137 ] && why="$why killed after $TIME s or out of memory;"
	[ "$lines" = 1 ] || why="$why $lines lines on stderr;"
	grep -q -F "$base" "$o.stderr" || why="$why message does not name $base;"
	[ -z "$left" ] || why="$why left behind: $left;"
	if [ -z "$why" ]; then res "$k:$c" 1 "exit $want, one line: $(head -c 120 "$o.stderr")"
	else res "$k:$c" 0 "$why $(head -c 160 "$o.stderr" | tr '\n' ' ')"; fi
}
for k in $KEYS; do
	for kd in $(kind "$k"); do
		case $kd in
		meta)
			for f in "$I"/m-*; do c=${f##*/m-}; c=${c%%.meta}; c=${c%%.lmb}; case $f in *.lmb) c=$c-binary ;; esac
				case $c in dash-fine) continue ;; esac
				run_bad "$k" "$c" "$f" 65
			done
			run_bad "$k" missing "$I/no-such-file.meta" 66 ;;
		scene)
			for f in "$I"/s-*; do c=${f##*/s-}; c=${c%%.scene}
				case $c in good|nesting-*) continue ;; esac
				run_bad "$k" "$c" "$f" 65
			done
			run_bad "$k" missing "$I/no-such-file.scene" 66 ;;
		image)
			for f in "$I"/img-*; do c=${f##*/}; c=${c%%.*}; run_bad "$k" "$c" "$f" 65; done ;;
		esac
	done
done

# ---- work bounded by the input (time and memory, one line when a limit is reached) ----------
# bounded KEY CASE FILE: within the bounds, exit 0 or 65, at most one line
bounded() {
	k=$1 c=$2 f=$3
	o=$D/out/$k-$c
	rm -rf "$o" && mkdir -p "$o"
	lim=$LIMIT
	sh -c "$lim; exec timeout -s KILL $TIME_WORK $(feed "$k" "$f" "$o/$(ext "$k")")" > /dev/null 2> "$o.stderr" < /dev/null
	rc=$?
	lines=$(wc -l < "$o.stderr")
	if { [ "$rc" = 0 ] || [ "$rc" = 65 ]; } && [ "$lines" -le 1 ]; then res "$k:$c" 1 "answered (exit $rc) within $TIME_WORK s and $MEM_KB KiB"
	else res "$k:$c" 0 "exit $rc, $lines lines on stderr (137: over $TIME_WORK s or the memory bound)"; fi
}
for k in raster meta-check; do bounded "$k" dash-fine "$I/m-dash-fine.meta"; done
bounded render nesting-time "$I/s-nesting-time.scene"
bounded render nesting-parse-time "$I/s-nesting-parse-time.scene"
# locus-diff reading an endless standard input
o=$D/out/diff-stdin
mkdir -p "$o"
lim=$LIMIT
sh -c "$lim; head -c 3000000000 /dev/zero | timeout -s KILL $TIME $BIN/locus-diff - $I/good.png" > /dev/null 2> "$o.stderr"
rc=$?
[ "$rc" = 2 ] && [ "$(wc -l < "$o.stderr")" = 1 ]; res diff:stdin-zero $((1 - $?)) "3 GB of zeros on stdin: exit $rc, $(head -c 100 "$o.stderr")"
# the same RGBA PNG read twice is the same picture
if command -v convert >/dev/null 2>&1; then
	convert "$I/good.png" -alpha set -channel A -evaluate set 50% "$I/rgba.png" 2>/dev/null
	"$BIN/locus-diff" "$I/rgba.png" "$I/rgba.png" > "$o.rgba" 2>&1
	rc=$?
	res diff:rgba-stable $([ "$rc" = 0 ] && echo 1 || echo 0) "an RGBA PNG compared with itself: exit $rc $(head -c 100 "$o.rgba")"
fi

# ---- outputs: device nodes, full devices, missing directories, planted temporaries ----------
good_of() { [ "$1" = render ] && echo "$I/s-good.scene" || echo "$I/good.meta"; }
# one_line FILE: exactly one line on stderr
one_line() { [ "$(wc -l < "$1")" = 1 ]; }
MKNOD=0
mknod "$D/probe" c 1 3 2>/dev/null && [ -c "$D/probe" ] && MKNOD=1
rm -f "$D/probe"
for k in $KEYS; do
	e=$(ext "$k")
	g=$(good_of "$k")
	o=$D/out/$k-o
	rm -rf "$o" && mkdir -p "$o"
	if [ -z "$e" ]; then
		# standard output only: a full standard output is an I/O error with a message
		[ "$k" = meta-check ] && continue
		$(feed "$k" "$g" -) > /dev/full 2> "$o.err"
		rc=$?
		w=74; [ "$k" = diff ] && w=2   # locus-diff: 2 for any trouble (issue 12)
		[ "$rc" = "$w" ] && one_line "$o.err"; res "$k:full-message" $((1 - $?)) "stdout on /dev/full: exit $rc, $(wc -l < "$o.err") lines: $(head -c 100 "$o.err")"
		continue
	fi
	# standard output on /dev/full: 74 and one line giving the cause
	$(feed "$k" "$g" -) > /dev/full 2> "$o.err"
	rc=$?
	[ "$rc" = 74 ] && one_line "$o.err" && grep -q "No space left on device" "$o.err"
	res "$k:stdout-full" $((1 - $?)) "-o - on /dev/full: exit $rc, $(wc -l < "$o.err") lines: $(head -c 100 "$o.err")"
	# a copy of /dev/null and of /dev/full made in the scratch directory (never the system's)
	if [ "$MKNOD" = 1 ]; then
		mknod "$o/null" c 1 3 && $(feed "$k" "$g" "$o/null") > /dev/null 2> "$o.err"
		rc=$?
		[ "$rc" = 0 ] && [ -c "$o/null" ]; res "$k:devnode-kept" $((1 - $?)) "-o a character device: exit $rc, still a device: $([ -c "$o/null" ] && echo yes || echo no)"
		mknod "$o/full" c 1 7 && $(feed "$k" "$g" "$o/full") > /dev/null 2> "$o.err"
		rc=$?
		[ "$rc" = 74 ] && one_line "$o.err" && [ -c "$o/full" ]
		res "$k:devnode-full" $((1 - $?)) "-o a full device: exit $rc, $(wc -l < "$o.err") lines, still a device: $([ -c "$o/full" ] && echo yes || echo no): $(head -c 100 "$o.err")"
		rm -f "$o/null" "$o/full"
	else
		ok "$k:devnode-kept: mknod not permitted here: skipped"
	fi
	mkfifo "$o/fifo"
	cat "$o/fifo" > "$o.fifo-data" &
	cpid=$!
	$(feed "$k" "$g" "$o/fifo") > /dev/null 2> "$o.err"
	rc=$?
	if [ -p "$o/fifo" ]; then wait_bounded 20 "$k:devnode-fifo (its reader)" "$cpid"; else kill "$cpid" 2>/dev/null; wait "$cpid" 2>/dev/null; fi
	[ "$rc" = 0 ] && [ -p "$o/fifo" ] && [ -s "$o.fifo-data" ]
	res "$k:devnode-fifo" $((1 - $?)) "-o a FIFO: exit $rc, still a FIFO: $([ -p "$o/fifo" ] && echo yes || echo no), $(cat "$o.fifo-data" 2>/dev/null | wc -c) bytes through it"
	rm -f "$o/fifo"
	# a missing directory
	$(feed "$k" "$g" "$o/nodir/$e") > /dev/null 2> "$o.err"
	rc=$?
	[ "$rc" = 74 ] && one_line "$o.err" && grep -q nodir "$o.err" && [ -z "$(ls -A "$o")" ]
	res "$k:missing-dir" $((1 - $?)) "-o in a missing directory: exit $rc: $(head -c 100 "$o.err")"
	# a user's own file named like a temporary survives a failed run and a good one
	echo mine > "$o/$e.tmp"
	$(feed "$k" "$I/m-truncated.meta" "$o/$e") > /dev/null 2>&1
	[ "$k" = render ] && $(feed "$k" "$I/s-truncated.scene" "$o/$e") > /dev/null 2>&1
	[ "$(cat "$o/$e.tmp" 2>/dev/null)" = mine ] && [ ! -e "$o/$e" ]
	res "$k:planted-tmp-kept" $((1 - $?)) "a file named $e.tmp survives a failed run"
	# a symlink named like a temporary: a good run writes the target, never the link's target
	rm -f "$o/$e.tmp"
	echo victim > "$o/victim"
	ln -s victim "$o/$e.tmp"
	$(feed "$k" "$g" "$o/$e") > /dev/null 2> "$o.err"
	rc=$?
	[ "$rc" = 0 ] && [ "$(cat "$o/victim")" = victim ] && [ -f "$o/$e" ] && [ ! -L "$o/$e" ]
	res "$k:planted-link-safe" $((1 - $?)) "a symlink named $e.tmp: exit $rc, its target kept: $([ "$(cat "$o/victim")" = victim ] && echo yes || echo no)"
	# mode of an existing target is kept
	rm -f "$o/$e.tmp" "$o/victim"
	chmod 640 "$o/$e" 2>/dev/null
	$(feed "$k" "$g" "$o/$e") > /dev/null 2>&1
	m=$(stat -c %a "$o/$e" 2>/dev/null)
	res "$k:mode-kept" $([ "$m" = 640 ] && echo 1 || echo 0) "a rewritten target keeps its mode (640, now $m)"
done

# ---- SIGTERM mid-write: nothing left ---------------------------------------------------------
# input that keeps a streaming program busy: pages of strokes, then a pause on an open pipe
awk 'BEGIN { print "LOCUS-META 1"; for (p = 0; p < 3; p++) { print "page 400 300"
	for (i = 0; i < 3000; i++) printf "stroke\nmove %d %d\ndraw %d %d\nend\n", i % 400, i % 300, (i * 7) % 400, (i * 3) % 300
	print "end-page" } }' > "$I/busy.meta"
awk '{ sub(/size 16 12/, "size 8000 6000") } 1' "$I/s-good.scene" > "$I/busy.scene"
for k in $KEYS; do
	e=$(ext "$k")
	[ -n "$e" ] || continue
	o=$D/out/$k-term
	wpid=
	rm -rf "$o" && mkdir -p "$o"
	if [ "$k" = render ]; then
		$(feed "$k" "$I/busy.scene" "$o/$e") > /dev/null 2>&1 &
	else
		# standard input stays open (the writer sleeps) so the program is caught mid-stream
		mkfifo "$o.pipe"
		(cat "$I/busy.meta"; exec sleep 30) > "$o.pipe" &
		wpid=$!
		$(feed "$k" - "$o/$e") < "$o.pipe" > /dev/null 2>&1 &
	fi
	pid=$!
	sleep 1
	during=$(ls -A "$o" | tr '\n' ' ')
	kill -TERM "$pid" 2>/dev/null
	wait_bounded 30 "$k:sigterm-clean" "$pid"
	rc=$?
	[ -z "$wpid" ] || { kill "$wpid" 2>/dev/null; wait "$wpid" 2>/dev/null; rm -f "$o.pipe"; wpid=; }
	left=$(ls -A "$o" | tr '\n' ' ')
	[ -z "$left" ] && [ "$rc" = 143 ]
	res "$k:sigterm-clean" $((1 - $?)) "SIGTERM after 1 s (files then: ${during:-none}): exit $rc, left: ${left:-nothing}"
done
done_tests

#!/bin/sh
# t_output.sh: every program's output path (drivers/io/transport.h): devices and FIFOs written in
# place and never replaced, write errors named with their cause (exit 74), no file from a failed
# run, temporaries that never follow a symlink, the target's mode kept, and no temporary left
# by SIGTERM or SIGHUP. Device nodes are private copies (mknod) or, for the names /dev/null and
# /dev/stdout, a scratch /dev in a private mount namespace: a system node is never at risk.
. tests/lib.sh
: "${T:?T (a scratch directory) must be set: run through tests/run.sh}"
META=fixtures/meta/f-test.meta
BADMETA=fixtures/bad/nan.meta
SCENE=fixtures/render/trifocal-wireframe.scene
printf 'frobnicate\n' > "$T/bad.scene"
PROGS="raster play fmt convert render"

# cmd_of PROG OUT [IN]: the command line writing OUT (paths in $T hold no spaces)
cmd_of() {
	case $1 in
	raster) echo "$BIN/locus-raster -o $2 ${3:-$META}" ;;
	play) echo "$BIN/locus-play -d ppm -o $2 ${3:-$META}" ;;
	fmt) echo "$BIN/locus-meta fmt ${3:-$META} -o $2" ;;
	convert) echo "$BIN/locus-meta convert ${3:-$META} -o $2" ;;
	render) echo "$BIN/locus-render ${3:-$SCENE} -o $2 --quiet" ;;
	esac
}
bad_of() { [ "$1" = render ] && echo "$T/bad.scene" || echo "$BADMETA"; }
# run PROG OUT [IN]: locus-meta info writes standard output only, so OUT is a redirection there
run() {
	if [ "$1" = info ]; then "$BIN/locus-meta" info "${3:-$META}" > "$2"; else $(cmd_of "$@"); fi
}
# fresh NAME: an empty directory $D
fresh() { D="$T/$1"; rm -rf "$D"; mkdir -p "$D"; }
# only DIR NAME...: DIR holds exactly these names
only() {
	d=$1; shift
	[ "$(cd "$d" && ls -A | sort | tr '\n' ' ')" = "$(for n in "$@"; do echo "$n"; done | sort | tr '\n' ' ')" ]
}
# one_line FILE WORDS...: FILE is one line holding every word
one_line() {
	f=$1; shift
	[ "$(wc -l < "$f")" = 1 ] || return 1
	for w in "$@"; do grep -qF -- "$w" "$f" || return 1; done
}

mkdir -p "$T/ref"
for p in $PROGS info; do run $p "$T/ref/$p" 2>/dev/null; done

# ---- device nodes: private copies of null (1,3) and full (1,7) -------------------------------
DEVS=
if mknod "$T/null" c 1 3 2>/dev/null && mknod "$T/full" c 1 7 2>/dev/null; then
	DEVS=$T
elif [ ! -w /dev ]; then
	DEVS=/dev   # not root: no program could replace these even when wrong
fi
if [ -n "$DEVS" ]; then
	for p in $PROGS info; do
		run $p "$DEVS/null" 2> "$T/err"; rc=$?
		[ $rc = 0 ] && [ -c "$DEVS/null" ] && [ ! -s "$T/err" ] && ok "$p: output to a null device node, which stays a device" \
			|| notok "$p: to a null device node: exit $rc, $(ls -l "$DEVS/null"), $(cat "$T/err")"
		run $p "$DEVS/full" 2> "$T/err"; rc=$?
		[ $p = info ] && name="<stdout>" || name="$DEVS/full"
		[ $rc = 74 ] && [ -c "$DEVS/full" ] && one_line "$T/err" "$name" "No space left on device" \
			&& ok "$p: output to /dev/full: exit 74, one line naming it and the cause" \
			|| notok "$p: to /dev/full: exit $rc, $(ls -l "$DEVS/full"), '$(cat "$T/err")'"
	done
	for p in raster play fmt convert render; do
		run $p - > "$DEVS/full" 2> "$T/err"; rc=$?
		[ $rc = 74 ] && one_line "$T/err" "<stdout>" "No space left on device" \
			&& ok "$p: standard output on /dev/full: exit 74, one line naming <stdout> and the cause" \
			|| notok "$p: stdout on /dev/full: exit $rc, '$(cat "$T/err")'"
	done
	"$BIN/locus-meta" --help > "$DEVS/full" 2> "$T/err"; rc=$?
	[ $rc = 74 ] && one_line "$T/err" "<stdout>" "No space left on device" && ok "locus-meta --help on /dev/full: exit 74, one line" \
		|| notok "locus-meta --help on /dev/full: exit $rc, '$(cat "$T/err")'"
	"$BIN/locus-play" -l > "$DEVS/full" 2> "$T/err"; rc=$?
	[ $rc = 74 ] && one_line "$T/err" "<stdout>" "No space left on device" && ok "locus-play -l on /dev/full: exit 74, one line" \
		|| notok "locus-play -l on /dev/full: exit $rc, '$(cat "$T/err")'"
else
	ok "device node cases # SKIP cannot make private device nodes as root"
fi

# ---- the names /dev/null and /dev/stdout, in a private mount namespace with a scratch /dev ----
NS=
if [ -w /dev ] && [ -n "$DEVS" ] && command -v unshare > /dev/null 2>&1; then
	mkdir -p "$T/dev" && mknod "$T/dev/null" c 1 3 && ln -s /proc/self/fd/1 "$T/dev/stdout"
	unshare -m sh -c "mount --bind '$T/dev' /dev && [ ! -e /dev/full ]" 2>/dev/null && NS=1
elif [ ! -w /dev ]; then
	NS=0   # not root: the real /dev cannot be harmed
fi
# indev SCRIPT: run a shell script with /dev the scratch one (NS=1) or the real one (NS=0)
indev() {
	if [ "$NS" = 1 ]; then unshare -m sh -c "mount --bind '$T/dev' /dev && $1"; else sh -c "$1"; fi
}
if [ -n "$NS" ]; then
	[ "$NS" = 1 ] && devnull=$T/dev/null || devnull=/dev/null
	for p in $PROGS; do
		indev "$(cmd_of $p /dev/null)" 2> "$T/err"; rc=$?
		[ $rc = 0 ] && [ -c "$devnull" ] && ok "$p: -o /dev/null keeps /dev/null a device" \
			|| notok "$p: -o /dev/null: exit $rc, $(ls -l "$devnull"), $(cat "$T/err")"
		indev "$(cmd_of $p /dev/stdout) > /dev/null" 2> "$T/err"; rc=$?
		[ $rc = 0 ] && [ -c "$devnull" ] && { [ "$NS" = 0 ] || [ -L "$T/dev/stdout" ]; } \
			&& ok "$p: -o /dev/stdout onto /dev/null: written in place, both kept" \
			|| notok "$p: -o /dev/stdout: exit $rc, $(ls -l "$devnull"), $(cat "$T/err")"
	done
else
	ok "-o /dev/null and -o /dev/stdout # SKIP root without a private mount namespace"
fi

# /dev/fd/1 (procfs: nothing can be created there) written through the descriptor: a shell's >>
for p in $PROGS; do
	fresh fd
	printf 'head\n' > "$D/out"
	$(cmd_of $p /dev/fd/1) >> "$D/out" 2> "$T/err"; rc=$?
	{ printf 'head\n'; cat "$T/ref/$p"; } > "$T/want"
	[ $rc = 0 ] && cmp -s "$D/out" "$T/want" && ok "$p: -o /dev/fd/1 writes through the descriptor (appends after >>)" \
		|| notok "$p: -o /dev/fd/1: exit $rc, $(cat "$T/err")"
done

# ---- a FIFO is written in place ------------------------------------------------------------
for p in $PROGS info; do
	fresh fifo
	mkfifo "$D/pipe"
	timeout 20 cat "$D/pipe" > "$T/got" &
	reader=$!
	timeout 20 sh -c "$(if [ $p = info ]; then echo "$BIN/locus-meta info $META > $D/pipe"; else cmd_of $p "$D/pipe"; fi)" 2> "$T/err"
	rc=$?
	[ -p "$D/pipe" ] || kill $reader 2>/dev/null   # replaced: the reader would wait in vain
	wait $reader
	[ $rc = 0 ] && [ -p "$D/pipe" ] && only "$D" pipe && cmp -s "$T/got" "$T/ref/$p" \
		&& ok "$p: a FIFO is written in place (same bytes as a file, nothing else created)" \
		|| notok "$p: FIFO: exit $rc, $(ls -l "$D"), $(cat "$T/err")"
done
# several pages into a FIFO follow one another, as on standard output
fresh fifo
mkfifo "$D/pipe"
timeout 20 cat "$D/pipe" > "$T/got" &
reader=$!
timeout 20 "$BIN/locus-raster" -f ppm -o "$D/pipe" fixtures/meta/multipage.meta; rc=$?
[ -p "$D/pipe" ] || kill $reader 2>/dev/null
wait $reader
"$BIN/locus-raster" -f ppm fixtures/meta/multipage.meta > "$T/want"
[ $rc = 0 ] && only "$D" pipe && cmp -s "$T/got" "$T/want" && ok "raster: three pages into a FIFO, in a row" \
	|| notok "raster: pages into a FIFO: exit $rc, $(ls "$D")"

# ---- a missing directory: one line, exit 74, nothing created -------------------------------
for p in $PROGS; do
	fresh nodir
	run $p "$D/missing/out" 2> "$T/err"; rc=$?
	[ $rc = 74 ] && only "$D" && one_line "$T/err" "$D/missing/out" "No such file or directory" \
		&& ok "$p: output in a missing directory: exit 74, one line, nothing created" \
		|| notok "$p: missing directory: exit $rc, $(ls -A "$D"), '$(cat "$T/err")'"
done

# ---- symlinks at the temporary names are never followed ------------------------------------
# plant N OUT CMD...: symlinks to OUT's sibling "victim" at OUT.tmp (the old fixed name) and at
# the first N candidate names OUT.PID-K.tmp of the process that then runs CMD (exec: same PID)
plant() {
	n=$1; shift
	sh -c 'n=$1 o=$2; shift 2; ln -s victim "$o.tmp"; k=0
		while [ $k -lt $n ]; do ln -s victim "$o.$$-$k.tmp"; k=$((k + 1)); done; exec "$@"' sh "$n" "$@"
}
for p in $PROGS; do
	fresh link
	printf 'victim\n' > "$D/victim"
	plant 3 "$D/out" $(cmd_of $p "$D/out") 2> "$T/err"; rc=$?
	links=$(find "$D" -name 'out.*tmp' -type l | wc -l)
	[ $rc = 0 ] && [ "$(cat "$D/victim")" = victim ] && [ "$links" = 4 ] && cmp -s "$D/out" "$T/ref/$p" \
		&& ok "$p: symlinks at OUT.tmp and the first candidate temporaries: not followed, left alone" \
		|| notok "$p: planted symlinks: exit $rc, victim '$(head -c 40 "$D/victim")', $links links, $(cat "$T/err")"
	fresh link
	printf 'victim\n' > "$D/victim"
	plant 64 "$D/out" $(cmd_of $p "$D/out") 2> "$T/err"; rc=$?
	[ $rc = 74 ] && [ "$(cat "$D/victim")" = victim ] && [ ! -e "$D/out" ] && one_line "$T/err" "$D/out" "File exists" \
		&& ok "$p: every candidate temporary taken by a symlink: exit 74, one line, the link's file untouched" \
		|| notok "$p: all candidates planted: exit $rc, victim '$(head -c 40 "$D/victim")', '$(cat "$T/err")'"
done

# ---- a user's own OUT.tmp survives; a failed run leaves the old OUT; modes are kept ---------
for p in $PROGS; do
	fresh own
	printf 'mine\n' > "$D/out.tmp"
	printf 'old\n' > "$D/out"
	run $p "$D/out" "$(bad_of $p)" 2> "$T/err"; rc=$?
	[ $rc = 65 ] && [ "$(cat "$D/out.tmp")" = mine ] && [ "$(cat "$D/out")" = old ] && only "$D" out out.tmp \
		&& ok "$p: a failed run keeps the user's OUT.tmp and the old OUT, adds nothing" \
		|| notok "$p: failed run: exit $rc, $(ls -A "$D"), out.tmp '$(cat "$D/out.tmp" 2>/dev/null)'"
	run $p "$D/out" 2> "$T/err"; rc=$?
	[ $rc = 0 ] && [ "$(cat "$D/out.tmp")" = mine ] && cmp -s "$D/out" "$T/ref/$p" && only "$D" out out.tmp \
		&& ok "$p: a successful run keeps the user's OUT.tmp too" || notok "$p: OUT.tmp after success: $(ls -A "$D")"
	fresh mode
	printf 'old\n' > "$D/out"
	chmod 600 "$D/out"
	run $p "$D/out" 2> "$T/err"; rc=$?
	[ $rc = 0 ] && [ "$(stat -c %a "$D/out")" = 600 ] && cmp -s "$D/out" "$T/ref/$p" \
		&& ok "$p: a replaced file keeps its mode (600)" || notok "$p: mode: exit $rc, $(stat -c %a "$D/out")"
	if [ "$(id -u)" = 0 ]; then
		chown 65534:65534 "$D/out"
		run $p "$D/out" 2> "$T/err"
		[ "$(stat -c %u:%g:%a "$D/out")" = 65534:65534:600 ] && ok "$p: root replacing a file keeps its owner and group" \
			|| notok "$p: owner $(stat -c %u:%g:%a "$D/out")"
	fi
	(umask 002; run $p "$D/new") 2> "$T/err"
	[ "$(stat -c %a "$D/new")" = 664 ] && ok "$p: a new file gets 0666 & ~umask (664 under umask 002)" \
		|| notok "$p: new file mode $(stat -c %a "$D/new")"
	ln -s out "$D/link"
	run $p "$D/link" 2> "$T/err"; rc=$?
	[ $rc = 0 ] && [ -L "$D/link" ] && cmp -s "$D/out" "$T/ref/$p" && [ "$(stat -c %a "$D/out")" = 600 ] \
		&& ok "$p: a symlink to a file stays a symlink; its file is replaced" || notok "$p: through a symlink: exit $rc, $(ls -l "$D")"
done

# ---- SIGTERM or SIGHUP mid-job: no temporary left, status 128 + signal ----------------------
# wait_tmp DIR N: until DIR holds N temporaries (at most 10 s)
wait_tmp() {
	i=0
	while [ "$(ls "$1" | grep -c '\.tmp$')" -lt "$2" ] && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
	[ $i -lt 200 ]
}
# killed SIG STATUS PROG N: PROG reads a FIFO that stalls mid-input (N temporaries by then)
killed() {
	sig=$1 want=$2 p=$3 n=$4
	fresh sig
	mkfifo "$D/in"
	exec 3<> "$D/in"   # read-write: nobody blocks opening it
	# at the default disposition whatever this shell inherited (nohup, a background job)
	$DEFAULT_SIGNALS $(cmd_of $p "$D/out.x" "$D/in") 2> "$T/err" &
	pid=$!
	# a first page whole, then the start of a second: two outputs by then for the raster drivers
	printf 'LOCUS-META 1\npage 64 48\nclear #ff0000\nend-page\npage 64 48\nclear #00ff00\n' >&3
	wait_tmp "$D" "$n"; seen=$?
	kill -$sig $pid
	{ wait_bounded 20 "$p: SIG$sig mid-job" $pid; } 2>/dev/null; rc=$?
	exec 3>&-
	[ $rc = 124 ] && return
	[ $seen = 0 ] && [ $rc = "$want" ] && only "$D" in \
		&& ok "$p: SIG$sig mid-job ($n temporaries): exit $want, nothing left" \
		|| notok "$p: SIG$sig: saw temporaries $seen, exit $rc, left $(ls -A "$D")"
}
killed TERM 143 raster 2
killed TERM 143 play 2
killed TERM 143 fmt 1
killed TERM 143 convert 1
killed HUP 129 fmt 1
killed HUP 129 raster 2
# locus-render reads its scene whole first: a big render instead (killed as soon as it writes)
fresh sig
sed 's/size 96 72/size 6400 4800/' fixtures/render/trifocal-raytrace.scene > "$T/big.scene"
$DEFAULT_SIGNALS "$BIN/locus-render" "$T/big.scene" -o "$D/out.meta" --quiet --threads 1 2> "$T/err" &
pid=$!
wait_tmp "$D" 1; seen=$?
kill -TERM $pid
{ wait_bounded 30 "render: SIGTERM mid-render" $pid; } 2>/dev/null; rc=$?
[ $rc = 124 ] || [ $seen = 0 ] && [ $rc = 143 ] && only "$D" && ok "render: SIGTERM mid-render: exit 143, nothing left" \
	|| notok "render: SIGTERM: saw temporary $seen, exit $rc, left $(ls -A "$D")"
done_tests

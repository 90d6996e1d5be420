#!/bin/sh
# t_tcp.sh: locus-hpgl -o tcp:127.0.0.1:PORT into the plotter emulator listening on the loopback
# address (tests/emu/plotemu.c --tcp): it reads slowly (a byte rate, a 1024-byte buffer that TCP
# holds back from), drops the first connection once mid-job, and compares what arrived with the
# HP-GL written to a file (bytes, and strokes through the HP-GL reader).
. tests/lib.sh
: "${T:?T (a scratch directory) must be set: run through tests/run.sh}"
: "${TESTBIN:=build/native/tests}"
EMU=$TESTBIN/emu-plotter
H=$BIN/locus-hpgl
META=fixtures/contour/trifocal.meta
# (locus-hpgl warns that the contour plot's background is not drawn: the warning is left out)
"$H" "$META" -o "$T/job.hpgl" 2>/dev/null || notok "locus-hpgl writes the contour plot to a file"
word() { tr ' ' '\n' < "$2" | sed -n "s/^$1=//p" | head -1; }

# A slow reader: 8 KB/s through a 1 KB buffer; the sender waits at the end for the printer's close.
"$EMU" --tcp --rate 8000 --pen-scale 20 --expect "$T/job.hpgl" -- "$H" "$META" -o "tcp:127.0.0.1:@PORT@" > "$T/slow" 2> "$T/slow.err"
rc=$?
[ $rc = 0 ] && [ "$(word child "$T/slow")" = 0 ] && [ "$(word connections "$T/slow")" = 1 ] \
	&& ok "a slow reader gets the whole contour plot: $(word accepted "$T/slow") bytes in $(word seconds "$T/slow") s, $(word expected "$T/slow") strokes as sent" \
	|| notok "slow reader: $(cat "$T/slow" "$T/slow.err")"
# The rate was the reader's, so the sender really waited on it.
awk -v s="$(word seconds "$T/slow")" 'BEGIN { exit !(s >= 1.0) }' && ok "the sender waited for the slow reader to finish ($(word seconds "$T/slow") s for 10.5 KB at 8 KB/s)" \
	|| notok "the reader's rate did not hold the sender: $(cat "$T/slow")"

# The printer drops the first connection after 3000 bytes; the job fails in one line, a second
# run delivers it whole.
cat > "$T/twice.sh" <<EOF
"$H" "$META" -o "tcp:127.0.0.1:\$1" 2> "$T/first.all"; echo \$? > "$T/first.rc"
grep -v warning "$T/first.all" > "$T/first.err"
exec "$H" "$META" -o "tcp:127.0.0.1:\$1"
EOF
"$EMU" --tcp --rate 8000 --pen-scale 20 --drop-after 3000 --expect "$T/job.hpgl" -- sh "$T/twice.sh" @PORT@ > "$T/drop" 2> "$T/drop.err"
rc=$?
[ "$(cat "$T/first.rc")" = 74 ] && [ "$(wc -l < "$T/first.err")" = 1 ] && grep -q "dropped the connection" "$T/first.err" \
	&& ok "a dropped connection: exit 74, one line: $(cat "$T/first.err")" || notok "drop: exit $(cat "$T/first.rc"): $(cat "$T/first.err")"
[ $rc = 0 ] && [ "$(word connections "$T/drop")" = 2 ] && [ "$(word strokes "$T/drop")" = same ] \
	&& ok "sent again after the drop, the job arrives whole (bytes and strokes)" || notok "after the drop: $(cat "$T/drop" "$T/drop.err")"

# Bad names and absent printers: one line, and what to do.
bad() {
	desc=$1 name=$2 words=$3
	"$H" "$META" -o "$name" > "$T/o" 2> "$T/e"; rc=$?
	[ $rc = 74 ] && [ "$(wc -l < "$T/e")" = 1 ] && grep -qF -- "$words" "$T/e" && [ ! -s "$T/o" ] \
		&& ok "$desc: exit $rc, one line: $(cat "$T/e")" || notok "$desc: exit $rc: $(cat "$T/e")"
}
bad "no host" "tcp:" "name a host"
bad "bad port" "tcp:127.0.0.1:99999" "bad port"
bad "bad setting" "tcp:127.0.0.1?speed=1" "the one setting is timeout=SECONDS"
bad "nobody listening" "tcp:127.0.0.1:1" "is the printer on"
done_tests

#!/bin/sh
# t_tcp.sh: locus-hpgl -o tcp:127.0.0.1:PORT into the plotter emulator listening on the loopback
# address (tests/emu/plotemu.c --tcp): it reads slowly (a byte rate, a 1024-byte buffer that TCP
# holds back from), drops the first connection once mid-job, and compares what arrived with the
# HP-GL written to a file (bytes, and strokes through the HP-GL reader).
. tests/emu/lib.sh
EMU=$EMU_PLOTTER

# A slow reader: 8 KB/s through a 1 KB buffer; the sender waits at the end for the printer's close.
"$EMU" --tcp --rate 8000 --pen-scale 20 --expect "$T/job.hpgl" -- "$H" "$META" -o "tcp:127.0.0.1:@PORT@" > "$T/slow" 2> "$T/slow.err"
rc=$?
[ $rc = 0 ] && [ "$(word child "$T/slow")" = 0 ] && [ "$(word connections "$T/slow")" = 1 ] \
	&& ok "a slow reader gets the whole contour plot: $(word accepted "$T/slow") bytes in $(word seconds "$T/slow") s, $(word expected "$T/slow") strokes as sent" \
	|| notok "slow reader: $(cat "$T/slow" "$T/slow.err")"
# The rate was the reader's, so the sender really waited on it.
awk -v s="$(word seconds "$T/slow")" 'BEGIN { exit !(s >= 1.0) }' && ok "the sender waited for the slow reader to finish ($(word seconds "$T/slow") s for 10.5 KB at 8 KB/s)" \
	|| notok "the reader's rate did not hold the sender: $(cat "$T/slow")"

# The printer drops the first connection after 3000 bytes (what its TCP acknowledged it keeps);
# the job fails in one line with exit 75 (EX_TEMPFAIL), a second run delivers it whole.
cat > "$T/twice.sh" <<EOF
"$H" "$META" -o "tcp:127.0.0.1:\$1" 2> "$T/first.all"; echo \$? > "$T/first.rc"
grep -v warning "$T/first.all" > "$T/first.err"
exec "$H" "$META" -o "tcp:127.0.0.1:\$1"
EOF
"$EMU" --tcp --rate 8000 --pen-scale 20 --drop-after 3000 --expect "$T/job.hpgl" -- sh "$T/twice.sh" @PORT@ > "$T/drop" 2> "$T/drop.err"
rc=$?
[ "$(cat "$T/first.rc")" = 75 ] && [ "$(wc -l < "$T/first.err")" = 1 ] && grep -Eq "(closed|dropped) the connection having taken [0-9]+ of 10514 bytes" "$T/first.err" \
	&& ok "a dropped connection, seen at the end: exit 75, one line: $(cat "$T/first.err")" || notok "drop: exit $(cat "$T/first.rc"): $(cat "$T/first.err")"
[ $rc = 0 ] && [ "$(word connections "$T/drop")" = 2 ] && [ "$(word strokes "$T/drop")" = same ] \
	&& ok "sent again after the drop, the job arrives whole (bytes and strokes)" || notok "after the drop: $(cat "$T/drop" "$T/drop.err")"

# journal NAME META HPGL HOW AT [LOCUS-HPGL OPTIONS]: a journaled job that the printer drops
# (HOW --drop-after: it reads what its TCP acknowledged, then closes) or resets (HOW
# --reset-after: switched off after reading AT bytes, what waited unread in its socket is lost),
# then resumed with --resume on a fresh connection: the first run exits 75 with one line naming
# the resume command and the journal never says done; its point is at most what the printer
# read (acknowledged is not consumed: the point lies before the peer's receive window); the
# parts cut there draw every segment of the job (segment by segment), the repeated window only
# repeated.
journal() {
	n=$1 m=$2 hp=$3 how=$4 after=$5; shift 5
	f=$(echo "$n" | tr ' ' -)
	rm -f "$T/$f.j"
	"$EMU" --tcp --rate "${RATE:-200000}" --rcvbuf "${RCVBUF:-4096}" --pen-scale 1000 "$how" "$after" --record "$T/$f.p1" --deadline 40 -- "$H" "$@" "$m" \
		-o "tcp:127.0.0.1:@PORT@?timeout=10" --journal "$T/$f.j" > "$T/$f.r1" 2> "$T/$f.all"
	nowarn "$T/$f.all" "$T/$f.err"
	cp "$T/$f.j" "$T/$f.j1"
	took=$(word first "$T/$f.r1") acked=$(sed -n 's/^acked //p' "$T/$f.j") safe=$(sed -n 's/^safe //p' "$T/$f.j")
	[ "$(word child "$T/$f.r1")" = 75 ] && [ "$(wc -l < "$T/$f.err")" = 1 ] && [ -n "$acked" ] && [ "$acked" -le "$took" ] \
		&& grep -q "having taken [0-9]* of [0-9]* bytes sent.*; page [0-9]*, command [0-9]* (byte $safe of the job) reached; resume with: .*--resume $T/$f.j" "$T/$f.err" \
		&& grep -q "^state interrupted" "$T/$f.j" \
		&& ok "$n: exit 75, journal interrupted at $safe (confirmed $acked) <= the $took bytes the printer read; one line: $(cut -c1-150 "$T/$f.err")..." \
		|| notok "$n: exit $(word child "$T/$f.r1"), printer read $took, journal: $(tr '\n' ' ' < "$T/$f.j"); $(cat "$T/$f.err")"
	"$EMU" --tcp --rate 200000 --pen-scale 1000 --record "$T/$f.p2" --deadline 40 -- "$H" "$@" "$m" -o "tcp:127.0.0.1:@PORT@?timeout=10" --resume "$T/$f.j" > "$T/$f.r2" 2>&1
	[ "$(word child "$T/$f.r2")" = 0 ] && grep -q "^state done" "$T/$f.j" && ok "$n: the resumed job completes, the journal says done" \
		|| notok "$n resumed: $(cat "$T/$f.r2" "$T/$f.j")"
	head -c "$took" "$T/$f.p1" > "$T/$f.p1r"   # what the printer read (the record may hold more)
	parts_cover "$n" "$hp" "$safe" "$T/$f.p1r" "$T/$f.p2" "${MAXREP:-2000}"
}
# Mid-job: a 122 KB job, dropped at 20000 bytes while the sender still writes (send fails).
sh tests/emu/bigjob.sh 6000 > "$T/big.meta"
"$H" --no-optimize "$T/big.meta" -o "$T/big.hpgl" 2>/dev/null
journal "drop mid-job" "$T/big.meta" "$T/big.hpgl" --drop-after 20000 --no-optimize
# After the last byte: the contour plot is all in the sender's socket when the printer drops at
# 7000; the sender learns it only from the half-close at the end (the peer's acknowledgements).
journal "drop after the last byte" "$META" "$T/job.hpgl" --drop-after 7000
# A printer switched off mid-job, its small receive buffer full (read slowly): the bytes its TCP
# acknowledged but it had not read are lost; the resume goes back past them.
RATE=20000 journal "reset mid-job, slow reader" "$T/big.meta" "$T/big.hpgl" --reset-after 20000 --no-optimize
# Switched off after the whole job was in its (large) receive buffer, all of it acknowledged:
# the reset comes in the wait at the end; before, the job counted as delivered (exit 0, done).
RCVBUF=0 journal "reset after the last byte" "$T/big.meta" "$T/big.hpgl" --reset-after 30000 --no-optimize
# locus-ps runs its documents itself (one output for every page): a PostScript job dropped by the
# printer is as temporary a failure as an HP-GL one (75, the same line), not an I/O error (74).
# The emulator reads the PostScript as HP-GL, so its pen is fast here: an "lb" in the text is a
# label to it, and at a real pen's pace the drop at 3000 bytes would come after the sender's
# 30 s wait for room.
"$EMU" --tcp --rate 8000 --pen-scale 1000 --drop-after 3000 -- "$BIN/locus-ps" -f ps "$META" \
	-o "tcp:127.0.0.1:@PORT@" > "$T/ps" 2> "$T/ps.err"
[ "$(word child "$T/ps")" = 75 ] && [ "$(wc -l < "$T/ps.err")" = 1 ] && grep -q "closed the connection having taken" "$T/ps.err" \
	&& ok "locus-ps -f ps into a printer that drops the connection: exit 75, one line: $(cat "$T/ps.err")" \
	|| notok "locus-ps dropped: $(cat "$T/ps" "$T/ps.err")"

# A journal resumes HP-GL only: locus-ps's PostScript and PDF documents with --journal are
# refused in one line before a byte goes (no journal file left), and resuming an HP-GL journal
# with a PostScript job sends nothing either (before, the restore PU;PA0,0; went ahead of
# %!PS-Adobe-3.0).
for fmt in ps pdf; do
	rm -f "$T/lang.j"
	"$EMU" --tcp --rate 200000 --pen-scale 1000 --deadline 30 -- "$BIN/locus-ps" -f $fmt "$META" \
		-o "tcp:127.0.0.1:@PORT@?timeout=10" --journal "$T/lang.j" > "$T/lang" 2> "$T/lang.err"
	c=$(word child "$T/lang")
	[ "$c" != 0 ] && [ "$c" != 75 ] && [ "$(wc -l < "$T/lang.err")" = 1 ] && grep -q "keeps HP-GL jobs only" "$T/lang.err" \
		&& [ "$(word received "$T/lang")" = 0 ] && [ ! -e "$T/lang.j" ] \
		&& ok "locus-ps -f $fmt --journal: refused (exit $c), nothing sent, no journal; one line: $(cat "$T/lang.err")" \
		|| notok "locus-ps -f $fmt --journal: exit $c, $(cat "$T/lang" "$T/lang.err"), journal: $(cat "$T/lang.j" 2>&1)"
done
cp "$T/drop-after-the-last-byte.j1" "$T/lang.j"
"$EMU" --tcp --rate 200000 --pen-scale 1000 --deadline 30 -- "$BIN/locus-ps" -f ps "$META" \
	-o "tcp:127.0.0.1:@PORT@?timeout=10" --resume "$T/lang.j" > "$T/lang" 2> "$T/lang.err"
[ "$(word received "$T/lang")" = 0 ] && [ "$(wc -l < "$T/lang.err")" = 1 ] && grep -q "keeps HP-GL jobs only" "$T/lang.err" \
	&& cmp -s "$T/lang.j" "$T/drop-after-the-last-byte.j1" \
	&& ok "locus-ps -f ps --resume of an HP-GL journal: nothing sent, the journal untouched" \
	|| notok "PostScript resumed from an HP-GL journal: $(cat "$T/lang" "$T/lang.err")"

# Bad names and absent printers: one line, and what to do.
bad 74 "no host" "tcp:" "name a host"
bad 74 "bad port" "tcp:127.0.0.1:99999" "bad port"
bad 74 "bad setting" "tcp:127.0.0.1?speed=1" "the one setting is timeout=SECONDS"
bad 74 "nobody listening" "tcp:127.0.0.1:1" "is the printer on"
done_tests

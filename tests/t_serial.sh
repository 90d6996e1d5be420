#!/bin/sh
# t_serial.sh: locus-hpgl -o serial:... into the plotter emulator on a pseudo-terminal
# (tests/emu/plotemu.c): the emulator models the line (the byte rate of the baud the sender set,
# bytes in flight after XOFF/CTS), a 1024-byte buffer that drops overflow silently and a pen that
# drains it; it reads what arrived with the HP-GL reader and compares bytes and strokes with the
# HP-GL locus-hpgl writes to a file. Every flow mode delivers a whole contour plot; with pacing
# off the loss is seen. Also: termios as asked, timeouts, and bad names in one line.
. tests/emu/lib.sh
EMU=$EMU_PLOTTER
# deliver NAME FLOW HANDSHAKE [EMU OPTIONS...]: run the job through the emulator; report in $T/NAME
deliver() {
	n=$1 f=$2 h=$3; shift 3
	"$EMU" --handshake "$h" --pen-scale 4 --expect "$T/job.hpgl" --record "$T/$n.got" "$@" \
		-- "$H" "$META" -o "serial:@TTY@?baud=115200&flow=$f" > "$T/$n" 2> "$T/$n.err"
}

for m in xonxoff:x rtscts:h escb:n; do
	f=${m%:*} h=${m#*:}
	if deliver "$f" "$f" "$h"; then
		ok "flow=$f: the whole contour plot arrives, bytes and strokes ($(word expected "$T/$f") strokes) as sent"
	else
		notok "flow=$f: $(cat "$T/$f" "$T/$f.err")"
	fi
	[ "$(word dropped "$T/$f")" = 0 ] && [ "$(word peak "$T/$f")" -gt 512 ] && [ "$(word peak "$T/$f")" -le 1024 ] \
		&& ok "flow=$f: the buffer filled (peak $(word peak "$T/$f") of 1024) and dropped nothing" \
		|| notok "flow=$f: buffer use: $(cat "$T/$f")"
done
[ "$(word xoff "$T/xonxoff")" -gt 0 ] && ok "flow=xonxoff: the plotter sent XOFF $(word xoff "$T/xonxoff") times; the sender's line (IXON set) paused each time" \
	|| notok "xonxoff: no XOFF was needed: the test proves nothing ($(cat "$T/xonxoff"))"
[ "$(word xoff "$T/rtscts")" -gt 0 ] && ok "flow=rtscts: CTS dropped $(word xoff "$T/rtscts") times and the sender (CRTSCTS set) held" \
	|| notok "rtscts: $(cat "$T/rtscts")"
[ "$(word queries "$T/escb")" = 2 ] && [ "$(word escapes "$T/escb")" -gt 20 ] \
	&& ok "flow=escb: ESC.L and ESC.B before each chunk ($(word escapes "$T/escb") escapes), OI at the start, OE at the end" \
	|| notok "escb: $(cat "$T/escb")"
[ "$(word baud "$T/xonxoff")" = 115200 ] && [ "$(word bits "$T/xonxoff")" = 10 ] \
	&& ok "termios: 115200 baud, 8N1 (10 bits a character) as asked" || notok "termios: $(cat "$T/xonxoff")"

# Pacing off: the line outruns the pen, the buffer overflows, the loss shows.
if deliver none none n; then
	notok "flow=none: no loss seen, the test proves nothing: $(cat "$T/none")"
else
	[ "$(word dropped "$T/none")" -gt 0 ] && [ "$(word strokes "$T/none")" != same ] \
		&& ok "flow=none: $(word dropped "$T/none") bytes dropped by the full buffer, strokes $(word strokes "$T/none" | cut -c1-60): loss is detected" \
		|| notok "flow=none: $(cat "$T/none")"
fi
# The plotter asks XOFF but the sender does not listen (flow=none on its side): loss too.
if deliver deaf none x; then notok "deaf sender: no loss seen"; else
	[ "$(word dropped "$T/deaf")" -gt 0 ] && ok "XOFF ignored by a sender with flow=none: $(word dropped "$T/deaf") bytes lost, detected" \
		|| notok "deaf: $(cat "$T/deaf")"
fi

# 7 data bits, even parity, 2 stop bits: 11 bits a character at the line.
"$EMU" --pen-scale 100 -- "$H" "$META" -o "serial:@TTY@?baud=57600&bits=7&parity=even&stop=2" > "$T/7e2" 2>&1
[ "$(word baud "$T/7e2")" = 57600 ] && [ "$(word bits "$T/7e2")" = 11 ] && ok "termios: 57600 baud 7E2 (11 bits a character)" \
	|| notok "7E2: $(cat "$T/7e2")"

# A plotter that never drains: XOFF holds, the sender gives up after timeout=1 with one line
# (a job larger than the pseudo-terminal's own buffer, which takes a small job whole).
sh tests/emu/bigjob.sh 6000 > "$T/big.meta"
"$EMU" --speed 1 --pen-change 0 -- "$H" --no-optimize "$T/big.meta" -o "serial:@TTY@?baud=115200&flow=xonxoff&timeout=1" > "$T/held" 2> "$T/held.err"
[ "$(word child "$T/held")" = 75 ] && [ "$(wc -l < "$T/held.err")" = 1 ] && grep -q "took nothing for 1 s (XOFF held" "$T/held.err" \
	&& ok "XOFF held for good: exit 75 (EX_TEMPFAIL: try again, or resume) after timeout=1, one line: $(cat "$T/held.err")" || notok "held: $(cat "$T/held" "$T/held.err")"
# A one-way cable: the HP-GL handshake gets no answer.
"$EMU" --mute -- "$H" "$META" -o "serial:@TTY@?flow=escb" > "$T/mute" 2> "$T/mute.err"
[ "$(word child "$T/mute")" = 74 ] && grep -q "no answer to ESC.L" "$T/mute.err" && [ "$(word accepted "$T/mute")" = 0 ] \
	&& ok "flow=escb on a cable without replies: one line, exit 74, nothing sent" || notok "mute: $(cat "$T/mute" "$T/mute.err")"

# The cable is pulled at byte 5000 of a flow=escb job with a journal; the job resumes on a new
# line from the last point an ESC.B answer confirmed. Cut there, the two parts draw every segment
# of the job once; what the plotter had beyond it, unconfirmed, is counted (drawn again).
rm -f "$T/j"
"$EMU" --handshake n --pen-scale 4 --hangup-after 5000 --record "$T/p1" -- "$H" "$META" -o "serial:@TTY@?baud=115200&flow=escb" --journal "$T/j" > "$T/h1" 2> "$T/h1.all"
safe=$(sed -n 's/^safe //p' "$T/j")
nowarn "$T/h1.all" "$T/h1.err"
[ "$(word child "$T/h1")" = 75 ] && [ "$(wc -l < "$T/h1.err")" = 1 ] && grep -q "(byte $safe of the job) reached; resume with: $H -o 'serial:.*' --resume $T/j $META\$" "$T/h1.err" \
	&& ok "cable pulled mid-job: one line with the byte reached ($safe, confirmed by ESC.B) and the resume command" || notok "hangup: $(cat "$T/h1" "$T/h1.err" "$T/j")"
"$EMU" --handshake n --pen-scale 4 --record "$T/p2" -- "$H" "$META" -o "serial:@TTY@?baud=115200&flow=escb" --resume "$T/j" > "$T/h2" 2>&1
head -c "$safe" "$T/p1" > "$T/p1.cut"
"$SEG" "$T/job.hpgl" | sort > "$T/seg.job"
"$SEG" "$T/p1.cut" "$T/p2" | sort > "$T/seg.parts"
dup=$("$SEG" "$T/p1" "$T/p2" 2>/dev/null | sort | uniq -d | wc -l)
[ "$(word child "$T/h2")" = 0 ] && cmp -s "$T/seg.job" "$T/seg.parts" \
	&& ok "resumed over serial: the parts cut at the confirmed point draw all $(wc -l < "$T/seg.job") segments once ($dup more were sent but unconfirmed)" \
	|| notok "serial resume: $(cat "$T/h2"; diff "$T/seg.job" "$T/seg.parts" | head -3)"

# Ctrl-C mid-job: SIGINT to a flow=escb job at 9600 baud after a second stops it cleanly: one
# line with the page and command reached and the exact resume command, exit 75, the journal
# marked interrupted; the resumed job and the first part cut at the journal's point draw every
# segment once (nothing lost, nothing doubled).
rm -f "$T/ji"
cat > "$T/int.sh" <<EOF
env --default-signal=INT "$H" "$META" -o "serial:\$1?baud=9600&flow=escb" --journal "$T/ji" 2> "$T/int.all" & pid=\$!
sleep 1.2; kill -INT \$pid
# bounded: a job that ignores SIGINT is killed after 30 s (exit 137 fails the check, not the suite)
(sleep 30; kill -KILL \$pid) > /dev/null 2>&1 & dog=\$!
wait \$pid; echo \$? > "$T/int.rc"; kill \$dog 2> /dev/null
EOF
"$EMU" --handshake n --pen-scale 4 --record "$T/i1" -- sh "$T/int.sh" @TTY@ > "$T/i1.r" 2>&1
nowarn "$T/int.all" "$T/int.err"
isafe=$(sed -n 's/^safe //p' "$T/ji")
[ "$(cat "$T/int.rc")" = 75 ] && [ "$(wc -l < "$T/int.err")" = 1 ] && grep -q "^state interrupted" "$T/ji" \
	&& grep -q "interrupted by SIGINT (Ctrl-C) after [0-9]* bytes; page 1, command $(sed -n 's/^command //p' "$T/ji") (byte $isafe of the job) reached; resume with: $H -o 'serial:.*' --resume $T/ji $META\$" "$T/int.err" \
	&& [ "$isafe" -gt 0 ] && [ "$isafe" -lt 5000 ] \
	&& ok "SIGINT mid-job: exit 75, journal interrupted at byte $isafe, one line: $(cut -c1-200 "$T/int.err")" || notok "SIGINT: rc $(cat "$T/int.rc"): $(cat "$T/int.err" "$T/ji" "$T/i1.r")"
"$EMU" --handshake n --pen-scale 4 --record "$T/i2" -- "$H" "$META" -o "serial:@TTY@?baud=115200&flow=escb" --resume "$T/ji" > "$T/i2.r" 2>&1
[ "$(word child "$T/i2.r")" = 0 ] && grep -q "^state done" "$T/ji" && ok "after SIGINT, --resume completes the job" || notok "SIGINT resume: $(cat "$T/i2.r" "$T/ji")"
parts_whole "SIGINT then --resume" "$T/job.hpgl" "$isafe" "$T/i1" "$T/i2"

# The sender killed (SIGKILL: no handler runs) mid-job at 9600 baud, most likely mid-number: the
# plotter keeps the unfinished command ("...,-11,-1,-"). The resumed job first ends it (the
# job's own next bytes up to where the command may end, then ';'), then restores the state: the
# bytes the plotter had plus the resumed bytes read cleanly with the HP-GL reader (strict: no
# malformed number, no odd coordinate count), and draw every segment (none missing).
rm -f "$T/jk"
cat > "$T/kill.sh" <<EOF
"$H" --no-optimize "$T/big.meta" -o "serial:\$1?baud=9600&flow=xonxoff" --journal "$T/jk" 2> /dev/null & pid=\$!
sleep 1.2; kill -KILL \$pid; wait \$pid; echo \$? > "$T/kill.rc"
EOF
"$EMU" --pen-scale 1000 --record "$T/k1" -- sh "$T/kill.sh" @TTY@ > "$T/k1.r" 2>&1
kacked=$(sed -n 's/^acked //p' "$T/jk") ksafe=$(sed -n 's/^safe //p' "$T/jk")
"$EMU" --pen-scale 1000 --record "$T/k2" -- "$H" --no-optimize "$T/big.meta" -o "serial:@TTY@?baud=115200&flow=xonxoff" --resume "$T/jk" > "$T/k2.r" 2>&1
head -c "$kacked" "$T/k1" > "$T/k1.held"
cat "$T/k1.held" "$T/k2" > "$T/kjoin"
"$SEG" "$T/kjoin" > "$T/kjoin.seg" 2> "$T/kjoin.err"; krc=$?
sort "$T/kjoin.seg" > "$T/kjoin.sorted"
"$H" --no-optimize "$T/big.meta" -o "$T/big.hpgl" 2>/dev/null
"$SEG" "$T/big.hpgl" | sort > "$T/kjob.sorted"
kmiss=$(comm -23 "$T/kjob.sorted" "$T/kjoin.sorted" | wc -l)
[ "$(cat "$T/kill.rc")" = 137 ] && [ "$(word child "$T/k2.r")" = 0 ] && [ $krc = 0 ] && [ "$kmiss" = 0 ] \
	&& [ "$(wc -c < "$T/k1")" -ge "$kacked" ] \
	&& ok "SIGKILL mid-job (the plotter held '$(tail -c 12 "$T/k1.held" | tr -d '\n')' past the point $ksafe; it got $(wc -c < "$T/k1") bytes, the journal knew $kacked), resumed: the joined bytes read cleanly (strict), no segment missing ($(wc -l < "$T/kjoin.seg") drawn for $(wc -l < "$T/kjob.sorted"); resumed bytes begin '$(head -c 24 "$T/k2")')" \
	|| notok "SIGKILL then --resume: kill rc $(cat "$T/kill.rc"), resume $(cat "$T/k2.r"), held $(wc -c < "$T/k1")/$kacked: $(cat "$T/kjoin.err") $kmiss missing; seam: $(tail -c 20 "$T/k1.held")|$(head -c 40 "$T/k2")"

# Bad names, absent devices, no terminal, no permission: one line that says what to do.
bad 74 "unknown setting" "serial:$T/tty?speed=9600" "unknown setting 'speed'"
bad 74 "bad baud" "serial:$T/tty?baud=9601" "no standard rate"
bad 74 "bad flow" "serial:$T/tty?flow=dtr" "bad flow 'dtr'"
bad 74 "bad bits" "serial:$T/tty?bits=9" "bad bits '9'"
bad 74 "no device named" "serial:?baud=9600" "name a serial device"
bad 74 "absent device" "serial:$T/ttyUSB9" "is it plugged in"
: > "$T/plain"
bad 74 "not a terminal" "serial:$T/plain" "is not a serial line"
if [ "$(id -u)" = 0 ] && command -v setpriv > /dev/null; then
	"$EMU" -- setpriv --reuid=65534 --regid=65534 --clear-groups "$H" "$META" -o "serial:@TTY@" > "$T/perm" 2> "$T/perm.err"
	[ "$(word child "$T/perm")" = 74 ] && grep -q "permission denied: add yourself to the group" "$T/perm.err" \
		&& ok "permission denied: the group to join is named: $(cat "$T/perm.err")" || notok "perm: $(cat "$T/perm" "$T/perm.err")"
else
	ok "permission case # SKIP needs root to drop to another user"
fi
done_tests

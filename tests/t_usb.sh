#!/bin/sh
# t_usb.sh: locus-hpgl -o usb:... through the real libusb-1.0 code into a USB printer-class
# plotter emulated under umockdev (tests/emu/usbemu.c: a testbed device and a usbdevfs ioctl
# handler; the program runs under umockdev-wrapper): a whole contour plot, the device ID (and
# its little-endian variant), the kernel driver detached and given back, a stall, a short write,
# a busy printer (transfers time out, partial counts kept), paper empty in words, an unplug
# mid-job, serial-number matching, --list-devices, and bad names in one line.
. tests/emu/lib.sh
EMU=$EMU_USB
need_umockdev "USB printer class"
# job NAME [EMU OPTIONS...] -- OUTPUT: one job into the emulator; report in $T/NAME, errors in NAME.err
job() {
	n=$1; shift
	opts=
	while [ "$1" != -- ]; do opts="$opts $1"; shift; done
	shift
	# shellcheck disable=SC2086
	"$EMU" $opts --expect "$T/job.hpgl" -- "$H" "$META" -o "$1" > "$T/$n" 2> "$T/$n.all"
	grep -v warning "$T/$n.all" > "$T/$n.err"
}

job plain -- usb:03f0:0107
[ "$(word child "$T/plain")" = 0 ] && [ "$(word bytes "$T/plain")" = same ] \
	&& ok "a whole contour plot over USB: $(word received "$T/plain") bytes, as sent" || notok "plain job: $(cat "$T/plain" "$T/plain.err")"
[ "$(word detached "$T/plain")" = 1 ] && [ "$(word attached "$T/plain")" = 1 ] && [ "$(word driver "$T/plain")" = usblp ] \
	&& [ "$(word claims "$T/plain")" = 1 ] && [ "$(word releases "$T/plain")" = 1 ] \
	&& ok "usblp detached, the interface claimed and released, usblp given back at the end" || notok "driver: $(cat "$T/plain")"
[ "$(word setconfig "$T/plain")" = 0 ] && [ "$(word idreads "$T/plain")" = 1 ] \
	&& ok "the configuration already in use is not set again; the device ID is read once" || notok "config/id: $(cat "$T/plain")"

job any -- usb:any
[ "$(word bytes "$T/any")" = same ] && ok "usb:any finds the printer-class device" || notok "usb:any: $(cat "$T/any" "$T/any.err")"
job sn -- usb:03f0:0107:LT0001
[ "$(word bytes "$T/sn")" = same ] && ok "usb:VID:PID:SERIAL matches the serial number string" || notok "serial: $(cat "$T/sn" "$T/sn.err")"
job badsn -- usb:03f0:0107:LT0002
[ "$(word child "$T/badsn")" = 74 ] && grep -q "no printer with serial number 'LT0002'" "$T/badsn.err" && [ "$(word received "$T/badsn")" = 0 ] \
	&& ok "another serial number: one line, exit 74, nothing sent" || notok "bad serial: $(cat "$T/badsn" "$T/badsn.err")"

ID="MFG:Locus;MDL:Emulated 7475A;CMD:HPGL;CLS:PRINTER;DES:Locus test plotter;"
"$EMU" -- "$BIN/locus-play" --list-devices > "$T/list" 2>&1
grep -qxF "usb:03f0:0107:LT0001  bidirectional  $ID" "$T/list" && ok "--list-devices: the output name, bidirectional, the IEEE-1284 ID" \
	|| notok "--list-devices: $(cat "$T/list")"
"$EMU" --id-le -- "$BIN/locus-play" --list-devices > "$T/listle" 2>&1
grep -qF "  $ID" "$T/listle" && ok "a device ID whose length comes little-endian is read whole" || notok "LE id: $(cat "$T/listle")"

job stall --stall-at 5000 -- usb:03f0:0107
[ "$(word bytes "$T/stall")" = same ] && [ "$(word stalls "$T/stall")" = 1 ] && [ "$(word clears "$T/stall")" -ge 1 ] \
	&& ok "a stall at byte 5000: the halt is cleared, the rest follows, nothing lost or doubled" || notok "stall: $(cat "$T/stall" "$T/stall.err")"
job short --short-at 3000 -- usb:03f0:0107
[ "$(word bytes "$T/short")" = same ] && ok "a short write at byte 3000: the next write starts where the device stopped" \
	|| notok "short: $(cat "$T/short" "$T/short.err")"
job busy --hold-at 4000 2500 -- usb:03f0:0107
[ "$(word bytes "$T/busy")" = same ] && ok "a printer busy for 2.5 s at byte 4000: timed-out transfers keep their partial count, the job completes" \
	|| notok "busy: $(cat "$T/busy" "$T/busy.err")"
job paper --hold-at 4000 9000 --status 0x38 -- "usb:03f0:0107?timeout=2"
[ "$(word child "$T/paper")" = 75 ] && [ "$(wc -l < "$T/paper.err")" = 1 ] && grep -q "took nothing for 2 s after 4000 bytes (paper empty)" "$T/paper.err" \
	&& ok "a printer out of paper: after timeout=2 one line with the byte count and the port status in words" || notok "paper: $(cat "$T/paper" "$T/paper.err")"
job unplug --unplug-at 6000 -- usb:03f0:0107
[ "$(word child "$T/unplug")" = 75 ] && [ "$(wc -l < "$T/unplug.err")" = 1 ] && grep -q "went away after 6000 bytes" "$T/unplug.err" \
	&& [ "$(word received "$T/unplug")" = 6000 ] && ok "unplugged at byte 6000: one line naming how far it got, exit 75 (EX_TEMPFAIL)" \
	|| notok "unplug: $(cat "$T/unplug" "$T/unplug.err")"

# Unplugged mid-number with --journal, then resumed with --resume on a fresh device: the two
# parts hold every pen-down segment of the job once (through the HP-GL reader), none redrawn,
# none skipped.
rm -f "$T/j"
"$EMU" --unplug-at 6003 --record "$T/part1" -- "$H" "$META" -o usb:03f0:0107 --journal "$T/j" > "$T/u1" 2> "$T/u1.all"
nowarn "$T/u1.all" "$T/u1.err"
safe=$(sed -n 's/^safe //p' "$T/j")
[ "$(word child "$T/u1")" = 75 ] && [ "$(wc -l < "$T/u1.err")" = 1 ] && grep -qF "page 1, command $(sed -n 's/^command //p' "$T/j") (byte $safe of the job) reached; resume with: $H -o usb:03f0:0107 --resume $T/j $META" "$T/u1.err" 	&& [ "$safe" -le 6003 ] && [ "$safe" -gt 5900 ] 	&& ok "unplugged with --journal: one line with the page, command and byte reached (boundary $safe of 6003 sent) and the exact resume command" 	|| notok "journal: $(cat "$T/u1" "$T/u1.err" "$T/j")"
"$EMU" --record "$T/part2" -- "$H" "$META" -o usb:03f0:0107 --resume "$T/j" > "$T/u2" 2> "$T/u2.all"
head -c "$safe" "$T/part1" > "$T/part1.cut"
"$SEG" "$T/job.hpgl" | sort > "$T/seg.job"
"$SEG" "$T/part1.cut" "$T/part2" | sort > "$T/seg.parts"
[ "$(word child "$T/u2")" = 0 ] && [ -s "$T/seg.job" ] && cmp -s "$T/seg.job" "$T/seg.parts" 	&& ok "resume=: the rest with the modal state restored; the parts draw each of the $(wc -l < "$T/seg.job") segments once" 	|| notok "resume: $(cat "$T/u2" "$T/u2.all"; diff "$T/seg.job" "$T/seg.parts" | head -5)"
"$SEG" "$T/part1.cut" "$T/part2" "$T/part2" | sort > "$T/seg.twice"
cmp -s "$T/seg.job" "$T/seg.twice" && notok "control: a part sent twice should show as doubled" || ok "control: a part sent twice shows as doubled segments"
grep -q "^state done" "$T/j" && ok "the journal says done after the resumed job" || notok "journal state: $(cat "$T/j")"
"$EMU" -- "$H" "$META" -o "usb:03f0:0107?resume=$T/j" > "$T/u3" 2> "$T/u3.all"
grep -q "delivered whole: nothing to resume" "$T/u3.all" && [ "$(word received "$T/u3")" = 0 ] 	&& ok "resuming a finished job: one line, nothing sent" || notok "resume done: $(cat "$T/u3" "$T/u3.all")"
rm -f "$T/j2"
"$EMU" --unplug-at 3000 -- "$H" "$META" -o "usb:03f0:0107?journal=$T/j2" > /dev/null 2>&1
"$EMU" -- "$H" fixtures/meta/f-test.meta -o "usb:03f0:0107?resume=$T/j2" > "$T/u4" 2> "$T/u4.all"
grep -Eq "the job differs from the journaled one|the job ended before the point the journal reached" "$T/u4.all" && [ "$(word received "$T/u4")" = 0 ] 	&& ok "resuming with another job: refused in one line, nothing sent" || notok "other job: $(cat "$T/u4" "$T/u4.all")"

# Ctrl-C while the printer is busy (it takes nothing from byte 4000 on): SIGINT stops the job in
# one line with the point and the resume command, exit 75; the resumed job completes the plot.
rm -f "$T/ji"
cat > "$T/int.sh" <<EOF
env --default-signal=INT "\$@" 2> "$T/int.all" & pid=\$!
sleep 1.5; kill -INT \$pid
# bounded: a job that ignores SIGINT is killed after 30 s (exit 137 fails the check, not the suite)
(sleep 30; kill -KILL \$pid) > /dev/null 2>&1 & dog=\$!
wait \$pid; echo \$? > "$T/int.rc"; kill \$dog 2> /dev/null
EOF
"$EMU" --hold-at 4000 9000 --record "$T/i1" -- sh "$T/int.sh" "$H" "$META" -o usb:03f0:0107 --journal "$T/ji" > "$T/i1.r" 2>&1
nowarn "$T/int.all" "$T/int.err"
isafe=$(sed -n 's/^safe //p' "$T/ji")
[ "$(cat "$T/int.rc")" = 75 ] && [ "$(wc -l < "$T/int.err")" = 1 ] && grep -q "^state interrupted" "$T/ji" \
	&& grep -qF "interrupted by SIGINT (Ctrl-C) after 4000 bytes; page 1, command $(sed -n 's/^command //p' "$T/ji") (byte $isafe of the job) reached; resume with: $H -o usb:03f0:0107 --resume $T/ji $META" "$T/int.err" \
	&& ok "SIGINT while the printer is busy: exit 75, the journal at byte $isafe, one line: $(cut -c1-160 "$T/int.err")..." || notok "usb SIGINT: rc $(cat "$T/int.rc"): $(cat "$T/int.err" "$T/ji" "$T/i1.r")"
"$EMU" --record "$T/i2" -- "$H" "$META" -o usb:03f0:0107 --resume "$T/ji" > "$T/i2.r" 2>&1
[ "$(word child "$T/i2.r")" = 0 ] && ok "after SIGINT, --resume completes the job over USB" || notok "usb SIGINT resume: $(cat "$T/i2.r")"
parts_whole "USB: SIGINT then --resume" "$T/job.hpgl" "$isafe" "$T/i1" "$T/i2"

# --journal and --resume in every program that sends jobs, the same as the name parameters.
rm -f "$T/jp"
"$EMU" --unplug-at 3000 -- "$BIN/locus-play" -d hpgl "$META" -o usb:03f0:0107 --journal "$T/jp" > "$T/pl1" 2>&1
"$EMU" --expect "$T/job.hpgl" -- "$BIN/locus-play" -d hpgl "$META" -o "usb:03f0:0107?resume=$T/jp" --resume "$T/jp" > "$T/pl2" 2>&1
[ "$(word child "$T/pl1")" = 75 ] && [ "$(word child "$T/pl2")" = 0 ] && grep -q "^state done" "$T/jp" \
	&& ok "locus-play -d hpgl: --journal, then --resume with the same resume= in the name too" || notok "locus-play journal: $(cat "$T/pl1" "$T/pl2" "$T/jp")"
for p in locus-hpgl locus-ps locus-play; do
	"$BIN/$p" --help | grep -q -- "--resume FILE" || notok "$p --help: no --resume"
	"$BIN/$p" -d hpgl "$META" -o "usb:03f0:0107?journal=$T/a" --journal "$T/b" > /dev/null 2> "$T/cl.err"; rc=$?
	[ "$p" = locus-play ] || { "$BIN/$p" "$META" -o "usb:03f0:0107?journal=$T/a" --journal "$T/b" > /dev/null 2> "$T/cl.err"; rc=$?; }
	[ $rc = 64 ] && grep -q "already says journal=$T/a, and --journal $T/b: give one" "$T/cl.err" \
		&& ok "$p: --journal against another journal= in the name: usage error 64, one line" || notok "$p conflict: exit $rc $(cat "$T/cl.err")"
done
"$H" "$META" -o "$T/x.hpgl" --resume "$T/j" 2> "$T/cl.err"; rc=$?
[ $rc = 64 ] && grep -q "needs a device link output" "$T/cl.err" && [ ! -e "$T/x.hpgl" ] && ok "--resume into a file: usage error 64" || notok "resume file: $rc $(cat "$T/cl.err")"
"$H" "$META" -o usb:03f0:0107 --resume "$T/j" --journal "$T/j" 2> "$T/cl.err"; rc=$?
[ $rc = 64 ] && ok "--journal and --resume together: usage error 64: $(cat "$T/cl.err")" || notok "both: $rc $(cat "$T/cl.err")"

# Recorded sessions (fixtures/usb/*.pcap, usbmon link type 220) replayed by umockdev-run -p: the
# replay completes only if the program makes the same transfers with the same bytes, in order.
SYS=/sys/devices/pci0000:00/0000:00:14.0/usb1/1-1
replay() { umockdev-run -d fixtures/usb/plotter.umockdev -p "$SYS=fixtures/usb/$1" -- "$H" "$2" -o "usb:03f0:0107?timeout=2"; }
replay f-test-job.pcap fixtures/meta/f-test.meta > /dev/null 2> "$T/r1" && ok "recorded session f-test-job.pcap replays: device ID, then the job's bulk transfers as recorded" \
	|| notok "replay job: $(tail -3 "$T/r1")"
replay f-test-stall.pcap fixtures/meta/f-test.meta > /dev/null 2> "$T/r2" && ok "recorded session with a stall replays: the rest after the halt is cleared, as recorded" \
	|| notok "replay stall: $(tail -3 "$T/r2")"
replay f-test-job.pcap fixtures/meta/strokes.meta > /dev/null 2> "$T/r3"; rc=$?
[ $rc = 75 ] && grep -q "Replay may be stuck" "$T/r3" && ok "control: another job against the recording gets stuck and fails (exit 75: a device that does not answer may later)" \
	|| notok "replay control: exit $rc, $(tail -2 "$T/r3")"

# No such device (no emulator at all), bad names.
"$EMU" -- "$H" "$META" -o usb:03f0:0999 > "$T/absent" 2> "$T/absent.all"
grep -q "no USB printer-class device with that VID:PID: is it plugged in and on?" "$T/absent.all" && [ "$(word child "$T/absent")" = 74 ] \
	&& ok "an absent VID:PID: one line that says to plug it in, and how to list or wait" || notok "absent: $(cat "$T/absent" "$T/absent.all")"
bad 74 "a VID that is no hex" "usb:zz:0107" "name the printer as usb:VID:PID"
bad 74 "no PID" "usb:03f0" "name the printer as usb:VID:PID"
bad 74 "an unknown setting" "usb:03f0:0107?speed=1" "settings are wait=SECONDS"
done_tests

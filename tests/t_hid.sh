#!/bin/sh
# t_hid.sh: locus-hpgl -o hid:10c4:ea80?... through the real hidapi (libusb backend) into a
# CP2110 HID UART bridge emulated under umockdev (tests/emu/usbemu.c --cp2110): the UART enabled
# and set up by feature reports (0x41, 0x50, 0x43), the job in reports whose ID is the byte count,
# usbhid detached and given back; HP-GL's ESC.B pacing through the bridge's replies (flow=escb),
# Ctrl-C and --resume; bad names in one line.
. tests/emu/lib.sh
EMU=$EMU_USB
need_umockdev "CP2110 bridge"

"$EMU" --cp2110 --expect "$T/job.hpgl" -- "$H" "$META" -o "hid:10c4:ea80?baud=115200&parity=even&bits=7&stop=2&flow=rtscts" > "$T/h" 2> "$T/h.err"
[ "$(word child "$T/h")" = 0 ] && [ "$(word bytes "$T/h")" = same ] \
	&& ok "a whole contour plot through the CP2110 bridge: $(word received "$T/h") bytes in reports of at most 63" || notok "hid job: $(cat "$T/h" "$T/h.err")"
[ "$(word uart "$T/h")" = on ] && [ "$(word baud "$T/h")" = 115200 ] && [ "$(word parity "$T/h")" = 2 ] && [ "$(word flow "$T/h")" = 1 ] \
	&& [ "$(word bits "$T/h")" = 7 ] && [ "$(word stop "$T/h")" = 2 ] && [ "$(word purges "$T/h")" = 1 ] \
	&& ok "feature reports: UART enabled, 115200 baud even parity RTS/CTS 7 bits 2 stop, FIFOs purged" || notok "uart: $(cat "$T/h")"
[ "$(word detached "$T/h")" = 1 ] && [ "$(word driver "$T/h")" = usbhid ] && ok "usbhid detached for the job and given back" || notok "driver: $(cat "$T/h")"
"$EMU" --cp2110 --expect "$T/job.hpgl" -- "$H" "$META" -o "hid:10c4:ea80:0001ABCD" > "$T/sn" 2>&1
[ "$(word bytes "$T/sn")" = same ] && [ "$(word baud "$T/sn")" = 9600 ] && ok "hid:VID:PID:SERIAL finds the bridge by serial number; 9600 8N1 by default" \
	|| notok "serial: $(cat "$T/sn")"
"$EMU" --cp2110 -- "$H" "$META" -o "hid:10c4:ea80:FFFF" > "$T/nosn" 2> "$T/nosn.err"
[ "$(word child "$T/nosn")" = 74 ] && [ "$(word received "$T/nosn")" = 0 ] && grep -q "no such serial number" "$T/nosn.err" \
	&& ok "another serial number: one line, nothing sent" || notok "bad serial: $(cat "$T/nosn" "$T/nosn.err")"
# flow=escb through the bridge: the plotter behind it (a 1024-byte buffer that drops overflow,
# a pen draining 4000 B/s, slower than the link) answers ESC.L, ESC.B, OI and OE in input
# reports; the link sends chunks of at most half the buffer after ESC.B said there is room.
"$EMU" --cp2110 --pen-rate 4000 --expect "$T/job.hpgl" -- "$H" "$META" -o "hid:10c4:ea80?baud=115200&flow=escb" --journal "$T/je" > "$T/escb" 2> "$T/escb.err"
[ "$(word child "$T/escb")" = 0 ] && [ "$(word bytes "$T/escb")" = same ] && [ "$(word dropped "$T/escb")" = 0 ] \
	&& [ "$(word peak "$T/escb")" -gt 512 ] && [ "$(word escapes "$T/escb")" -gt 40 ] \
	&& grep -q "^acked 10514" "$T/je" && grep -q "^state done" "$T/je" \
	&& ok "flow=escb over the bridge: the whole plot, $(word escapes "$T/escb") ESC.L/ESC.B queries answered, the buffer filled (peak $(word peak "$T/escb")) and dropped nothing; the journal acked all" \
	|| notok "hid escb: $(cat "$T/escb" "$T/escb.err" "$T/je")"
"$EMU" --cp2110 --pen-rate 4000 --expect "$T/job.hpgl" -- "$H" "$META" -o "hid:10c4:ea80?baud=115200" > "$T/nopace" 2>&1
[ "$(word dropped "$T/nopace")" -gt 0 ] && [ "$(word bytes "$T/nopace")" != same ] \
	&& ok "control: without pacing the same plotter loses $(word dropped "$T/nopace") bytes (the model can fail)" || notok "no pacing: $(cat "$T/nopace")"
# Ctrl-C mid-job (a pen of 1500 B/s): exit 75, the journal's point from the ESC.B answers, and
# the resumed job with the first part cut there draws every segment once.
rm -f "$T/ji"
cat > "$T/int.sh" <<EOF
env --default-signal=INT "\$@" 2> "$T/int.all" & pid=\$!
sleep 1.5; kill -INT \$pid
# bounded: a job that ignores SIGINT is killed after 30 s (exit 137 fails the check, not the suite)
(sleep 30; kill -KILL \$pid) > /dev/null 2>&1 & dog=\$!
wait \$pid; echo \$? > "$T/int.rc"; kill \$dog 2> /dev/null
EOF
"$EMU" --cp2110 --pen-rate 1500 --record "$T/i1" -- sh "$T/int.sh" "$H" "$META" -o "hid:10c4:ea80?flow=escb" --journal "$T/ji" > "$T/i1.r" 2>&1
nowarn "$T/int.all" "$T/int.err"
isafe=$(sed -n 's/^safe //p' "$T/ji") iacked=$(sed -n 's/^acked //p' "$T/ji")
[ "$(cat "$T/int.rc")" = 75 ] && [ "$(wc -l < "$T/int.err")" = 1 ] && grep -q "interrupted by SIGINT (Ctrl-C).*(byte $isafe of the job) reached; resume with: .*--resume $T/ji" "$T/int.err" \
	&& [ "$iacked" -le "$(word received "$T/i1.r")" ] && [ "$isafe" -gt 0 ] \
	&& ok "SIGINT over the bridge: exit 75, the journal at byte $isafe (ESC.B confirmed $iacked of the $(word received "$T/i1.r") the plotter took)" || notok "hid SIGINT: $(cat "$T/int.rc" "$T/int.err" "$T/ji" "$T/i1.r")"
"$EMU" --cp2110 --record "$T/i2" -- "$H" "$META" -o "hid:10c4:ea80?flow=escb" --resume "$T/ji" > "$T/i2.r" 2>&1
[ "$(word child "$T/i2.r")" = 0 ] && ok "after SIGINT, --resume over the bridge completes the job" || notok "hid resume: $(cat "$T/i2.r")"
parts_whole "bridge: SIGINT then --resume" "$T/job.hpgl" "$isafe" "$T/i1" "$T/i2"
"$EMU" --cp2110 -- "$BIN/locus-play" --list-devices > "$T/list" 2>&1
grep -qxF "hid:10c4:ea80:0001ABCD  HID UART bridge  Silicon Labs CP2110 HID USB-to-UART Bridge" "$T/list" \
	&& ok "--list-devices names the bridge as -o takes it, with maker and product" || notok "list: $(cat "$T/list")"
bad 74 "absent bridge" "hid:10c4:ea80" "no HID bridge with that VID:PID"
bad 74 "bad name" "hid:cp2110" "name the bridge as hid:VID:PID"
bad 74 "bad setting" "hid:10c4:ea80?flow=xonxoff" "bad setting 'flow'"
done_tests

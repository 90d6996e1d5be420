#!/bin/sh
# t_hid.sh: locus-hpgl -o hid:10c4:ea80?... through the real hidapi (libusb backend) into a
# CP2110 HID UART bridge emulated under umockdev (tests/emu/usbemu.c --cp2110): the UART enabled
# and set up by feature reports (0x41, 0x50, 0x43), the job in reports whose ID is the byte count,
# usbhid detached and given back; bad names in one line.
. tests/lib.sh
: "${T:?T (a scratch directory) must be set: run through tests/run.sh}"
: "${TESTBIN:=build/native/tests}"
EMU=$TESTBIN/emu-usb
H=$BIN/locus-hpgl
META=fixtures/contour/trifocal.meta
if ! command -v umockdev-wrapper > /dev/null || [ ! -x "$EMU" ]; then
	ok "CP2110 bridge # SKIP umockdev is not installed"
	done_tests
fi
"$H" "$META" -o "$T/job.hpgl" 2>/dev/null || notok "locus-hpgl writes the contour plot to a file"
word() { tr ' ' '\n' < "$2" | sed -n "s/^$1=//p" | head -1; }

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
"$EMU" --cp2110 -- "$BIN/locus-play" --list-devices > "$T/list" 2>&1
grep -qxF "hid:10c4:ea80:0001ABCD  HID UART bridge  Silicon Labs CP2110 HID USB-to-UART Bridge" "$T/list" \
	&& ok "--list-devices names the bridge as -o takes it, with maker and product" || notok "list: $(cat "$T/list")"
bad() {
	desc=$1 name=$2 words=$3
	"$H" "$META" -o "$name" > "$T/o" 2> "$T/e.all"; rc=$?
	grep -v warning "$T/e.all" > "$T/e"
	[ $rc = 74 ] && [ "$(wc -l < "$T/e")" = 1 ] && grep -qF -- "$words" "$T/e" && [ ! -s "$T/o" ] \
		&& ok "$desc: exit $rc, one line: $(cat "$T/e")" || notok "$desc: exit $rc: $(cat "$T/e")"
}
bad "absent bridge" "hid:10c4:ea80" "no HID bridge with that VID:PID"
bad "bad name" "hid:cp2110" "name the bridge as hid:VID:PID"
bad "bad setting" "hid:10c4:ea80?flow=xonxoff" "bad setting 'flow'"
done_tests

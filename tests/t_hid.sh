#!/bin/sh
# t_hid.sh: locus-hpgl -o hid:10c4:ea80?... through the real hidapi (libusb backend) into a
# CP2110 HID UART bridge emulated under umockdev (tests/emu/usbemu.c --cp2110): the UART enabled
# and set up by feature reports (0x41, 0x50, 0x43), the job in reports whose ID is the byte count,
# usbhid detached and given back; bad names in one line.
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
"$EMU" --cp2110 -- "$BIN/locus-play" --list-devices > "$T/list" 2>&1
grep -qxF "hid:10c4:ea80:0001ABCD  HID UART bridge  Silicon Labs CP2110 HID USB-to-UART Bridge" "$T/list" \
	&& ok "--list-devices names the bridge as -o takes it, with maker and product" || notok "list: $(cat "$T/list")"
bad 74 "absent bridge" "hid:10c4:ea80" "no HID bridge with that VID:PID"
bad 74 "bad name" "hid:cp2110" "name the bridge as hid:VID:PID"
bad 74 "bad setting" "hid:10c4:ea80?flow=xonxoff" "bad setting 'flow'"
done_tests

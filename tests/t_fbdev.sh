#!/bin/sh
# t_fbdev.sh: locus-vga -o fb:/dev/fb0 through the real open, ioctl and mmap path, on fake
# framebuffers under umockdev (tests/fbdev/fbharness.c): 32-bit true colour with unusual bit
# fields, 24-bit packed, 16-bit 5-6-5, 8-bit pseudo-colour with FBIOPUTCMAP, padded lines; the node's memory
# read back and compared with the dump of the same picture; --hold restores screen and colour map,
# also when SIGINT or SIGTERM ends the hold.
. tests/lib.sh
: "${TESTBIN:=build/native/tests}"
H=$TESTBIN/fbharness
CHK="python3 tests/fbdev/fbcheck.py"
F=fixtures/meta/f-test.meta
if [ ! -x "$H" ] || ! command -v umockdev-wrapper > /dev/null; then
	ok "fake framebuffer harness not built or umockdev missing # SKIP"
	done_tests
fi
# the screens' sizes in mm give the mode's pixel shape (13h: 5:6), so the picture on the
# screen is exactly the mode's dump
$BIN/locus-vga $F -o "$T/f13.dump"
$BIN/locus-vga --mode 12h $F -o "$T/f12.dump"
fb() {   # fb DESC BPP XRES YRES WMM HMM LINE_LENGTH DUMP MODE -- ARGS (of $PROG, default locus-vga)
	d=$1 bpp=$2 xr=$3 yr=$4 wm=$5 hm=$6 ll=$7 dump=$8 mode=$9
	shift 10
	if ! "$H" "$bpp" "$xr" "$yr" "$wm" "$hm" "$ll" "$T/o" -- "$BIN/${PROG:-locus-vga}" "$@" > "$T/err" 2>&1; then
		notok "$d: ${PROG:-locus-vga} failed: $(head -c 200 "$T/err")"
		return
	fi
	$CHK fbmem "$T/o.mem" "$bpp" "$xr" "$yr" "$ll" "$dump" "$mode" "$T/o.cmap" "$d"
}
fb "13h on a 32-bit screen" 32 320 200 200 150 1344 "$T/f13.dump" 13h -- $F -o fb:/dev/fb0
grep -q FBIOGET_FSCREENINFO "$T/o.log" && ok "32-bit: screen queried by ioctl" || notok "32-bit: no FBIOGET_FSCREENINFO"
fb "13h on a 24-bit screen" 24 320 200 200 150 968 "$T/f13.dump" 13h -- $F -o fb:/dev/fb0
fb "13h on a 16-bit screen" 16 320 200 200 150 704 "$T/f13.dump" 13h -- $F -o fb:/dev/fb0
fb "13h on an 8-bit screen" 8 320 200 200 150 352 "$T/f13.dump" 13h -- $F -o fb:/dev/fb0
fb "12h on an 8-bit screen" 8 640 480 320 240 672 "$T/f12.dump" 12h -- --mode 12h $F -o fb:/dev/fb0
fb "32-bit, --hold: restored" 32 320 200 200 150 1344 - 13h -- --hold 0.02 $F -o fb:/dev/fb0
fb "8-bit, --hold: restored" 8 320 200 200 150 352 - 13h -- --hold 0.02 $F -o fb:/dev/fb0
# Ctrl-C (SIGINT) or SIGTERM during a long --hold: the old screen and colour map come back at
# once and the program ends as the signal ends it (130, 143), not after the 30 seconds
sig() {   # sig DESC SIGNAL STATUS BPP LINE_LENGTH
	d=$1 s=$2 want=$3 bpp=$4 ll=$5
	t0=$(date +%s)
	# at the default dispositions: a background job of a non-interactive shell starts with INT ignored
	FBH_SIGNAL=$s $DEFAULT_SIGNALS "$H" "$bpp" 320 200 200 150 "$ll" "$T/o" -- "$BIN/locus-vga" --hold 30 $F -o fb:/dev/fb0 > "$T/err" 2>&1
	r=$? t=$(( $(date +%s) - t0 ))
	if [ "$r" = "$want" ] && [ "$t" -lt 20 ] && grep -q "signal $s" "$T/o.log"; then
		ok "$d: exit $r after ${t} s"
	else
		notok "$d: exit $r (wanted $want) after ${t} s: $(head -c 200 "$T/err")"
	fi
	$CHK fbmem "$T/o.mem" "$bpp" 320 200 "$ll" - 13h "$T/o.cmap" "$d"
}
sig "8-bit, SIGINT during --hold" INT 130 8 352
grep -c FBIOPUTCMAP "$T/o.log" | grep -qx 2 && ok "8-bit, SIGINT: the colour map put twice (the picture's, then the old one)" ||
	notok "8-bit, SIGINT: FBIOPUTCMAP $(grep -c FBIOPUTCMAP "$T/o.log") times"
sig "32-bit, SIGTERM during --hold" TERM 143 32 1344
# the same through locus-play's device option
PROG=locus-play fb "locus-play -d vga -O fb=/dev/fb0" 8 320 200 200 150 352 "$T/f13.dump" 13h -- -d vga -O fb=/dev/fb0 $F
done_tests

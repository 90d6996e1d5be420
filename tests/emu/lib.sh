# lib.sh: what the transport tests (t_serial.sh, t_usb.sh, t_hid.sh, t_tcp.sh) share; source it
# from the repository top. It sources tests/lib.sh, checks T, and sets EMU_PLOTTER, EMU_USB, SEG
# (the emulators and the segment lister), H (locus-hpgl), META (the contour plot) and
# $T/job.hpgl (that plot as HP-GL in a file, what each link must deliver).
. tests/lib.sh
: "${T:?T (a scratch directory) must be set: run through tests/run.sh}"
: "${TESTBIN:=build/native/tests}"
EMU_PLOTTER=$TESTBIN/emu-plotter
EMU_USB=$TESTBIN/emu-usb
SEG=$TESTBIN/hpgl-segments
H=$BIN/locus-hpgl
META=fixtures/contour/trifocal.meta
# (locus-hpgl warns that the contour plot's background is not drawn: nowarn leaves it out)
"$H" "$META" -o "$T/job.hpgl" 2>/dev/null || notok "locus-hpgl writes the contour plot to a file"
# word KEY FILE: the value of KEY=... in an emulator's report
word() { tr ' ' '\n' < "$2" | sed -n "s/^$1=//p" | head -1; }
# nowarn IN OUT: the error lines without locus-hpgl's warnings
nowarn() { grep -v warning "$1" > "$2"; }
# need_umockdev WHAT: skip the whole script when umockdev or the USB emulator is missing
need_umockdev() {
	if ! command -v umockdev-wrapper > /dev/null || [ ! -x "$EMU_USB" ]; then
		ok "$1 # SKIP umockdev (umockdev-wrapper, libumockdev-dev) is not installed"
		done_tests
	fi
}
# bad WANT DESC NAME WORDS: locus-hpgl into the output NAME fails with exit WANT, one line
# holding WORDS, and nothing on standard output
bad() {
	want=$1 desc=$2 name=$3 words=$4
	"$H" "$META" -o "$name" > "$T/o" 2> "$T/e.all"; rc=$?
	nowarn "$T/e.all" "$T/e"
	[ $rc = "$want" ] && [ "$(wc -l < "$T/e")" = 1 ] && grep -qF -- "$words" "$T/e" && [ ! -s "$T/o" ] \
		&& ok "$desc: exit $rc, one line: $(cat "$T/e")" || notok "$desc: exit $rc: $(cat "$T/e")"
}
# parts_whole DESC WHOLE SAFE PART1 PART2: PART1 cut at byte SAFE (the journal's point when the
# first part stopped), then PART2, draw the pen-down segments of the HP-GL file WHOLE, each once
# (through the HP-GL reader)
parts_whole() {
	safe=$3
	head -c "$safe" "$4" > "$T/pw.cut"
	"$SEG" "$2" | sort > "$T/pw.whole"
	"$SEG" "$T/pw.cut" "$5" 2>/dev/null | sort > "$T/pw.parts"
	if [ -s "$T/pw.whole" ] && cmp -s "$T/pw.whole" "$T/pw.parts"; then
		ok "$1: cut at byte $safe, the parts draw each of the $(wc -l < "$T/pw.whole") segments once"
	else
		notok "$1: $(diff "$T/pw.whole" "$T/pw.parts" | head -3)"
	fi
}
# parts_cover DESC WHOLE SAFE PART1 PART2: like parts_whole, for a link whose journal point is
# conservative (tcp:): the parts draw every segment of WHOLE (none missing, compared segment by
# segment), and what they draw twice is only the repeated window (each extra one a segment of
# WHOLE, at most MAXREP of them: $6)
parts_cover() {
	safe=$3 maxrep=$6
	head -c "$safe" "$4" > "$T/pw.cut"
	"$SEG" "$2" | sort > "$T/pw.whole"
	"$SEG" "$T/pw.cut" "$5" 2>/dev/null | sort > "$T/pw.parts"
	missing=$(comm -23 "$T/pw.whole" "$T/pw.parts" | wc -l)
	extra=$(comm -13 "$T/pw.whole" "$T/pw.parts" | wc -l)
	foreign=$(comm -13 "$T/pw.whole" "$T/pw.parts" | sort -u | comm -23 - "$T/pw.whole" | wc -l)
	if [ -s "$T/pw.whole" ] && [ "$missing" = 0 ] && [ "$foreign" = 0 ] && [ "$extra" -le "$maxrep" ]; then
		ok "$1: cut at byte $safe, the parts draw all $(wc -l < "$T/pw.whole") segments, none missing; $extra drawn again (the unconfirmed window)"
	else
		notok "$1: $missing segments missing, $extra extra ($foreign not in the job): $(comm -3 "$T/pw.whole" "$T/pw.parts" | head -3)"
	fi
}

#!/bin/sh
# t_vecdash.sh: dashes on the vector devices cost what the page shows. A dash pattern along
# lines that run far off the page made one piece per period of their whole length (a 3 KB
# meta file of a zigzag +-500,000 px across a 100x100 page, dash 1 1, drove locus-play -d svg
# past 3 GB; fixtures/dash/long.meta gave a 26 MB SVG); the pieces are now made only within the
# page and the stroke's reach (dash.c's closed-form walk with a window, as the raster path).
# Stated bound: output at most 1 MB, 5 s and 1 GB of address space for each of SVG, PDF and
# HP-GL (HP-GL took 12 s before, walking every piece to clip it); the zigzag's 199 segments show at most 142 px each on the page, about 14,000 pieces.
. tests/lib.sh
: "${T:?T (a scratch directory) must be set: run through tests/run.sh}"
P=$BIN/locus-play
awk 'BEGIN { print "LOCUS-META 1"; print "# zigzag: 199 segments +-500,000 px across a 100x100 page"
	print "page 100 100"; print "dash 1 1"; print "stroke"; print "move 0 -500000"
	for (i = 1; i < 200; i++) print "draw " i / 2 " " (i % 2 ? 500000 : -500000)
	print "end"; print "end-page" }' > "$T/zig.meta"
for m in "$T/zig.meta" fixtures/dash/long.meta; do
	for dv in svg pdf hpgl; do
		o=$T/out.$dv
		rm -f "$o"
		# (AddressSanitizer reserves terabytes of address space: no ulimit -v under SANITIZE=1,
		# where the time bound, 20 s for the slower build, is what holds)
		if [ "${SANITIZE:-0}" = 1 ]; then
			timeout 20 "$P" -d $dv "$m" -o "$o" 2> "$T/err"; rc=$?
		else
			( ulimit -v 1048576; exec timeout 5 "$P" -d $dv "$m" -o "$o" ) 2> "$T/err"; rc=$?
		fi
		size=$(wc -c < "$o" 2>/dev/null || echo 0)
		[ $rc = 0 ] && [ "$size" -gt 0 ] && [ "$size" -le 1048576 ] \
			&& ok "$(basename "$m") ($(wc -c < "$m") bytes) -d $dv: $size bytes, within 5 s and 1 GB" \
			|| notok "$(basename "$m") -d $dv: exit $rc, $size bytes: $(head -c 300 "$T/err")"
	done
done
# the pieces are the visible ones: the SVG of long.meta is well-formed XML and has dashes
"$P" -d svg fixtures/dash/long.meta -o "$T/long.svg" 2>/dev/null
n=$(grep -o ' M' "$T/long.svg" | wc -l)
if command -v xmllint > /dev/null; then
	xmllint --noout "$T/long.svg" 2> "$T/x" && [ "$n" -ge 20 ] && ok "long.meta's SVG is XML with $n dash pieces on the page" \
		|| notok "long.svg: $(cat "$T/x") ($n pieces)"
fi
# the HP-GL of the zigzag draws the segments of the unwindowed walk (the pieces the old code
# made, clipped to the page): the same 9,950 segments through the HP-GL reader
"$P" -d hpgl "$T/zig.meta" -o "$T/zig.hpgl" 2>/dev/null
segs=$("$TESTBIN/hpgl-segments" "$T/zig.hpgl" | wc -l)
[ "$segs" = 9950 ] && ok "the zigzag's HP-GL draws its 9950 visible dash pieces" || notok "zigzag HP-GL: $segs segments"
done_tests

#!/bin/sh
# t_render_pair.sh: a multi-band page replayed by two threads (even and odd bands, the first two
# painted while the page is spooled) has the bytes of the one-thread banded replay and of the
# whole page, exact and anti-aliased, on the raster and film devices; a failure mid-page stops
# both threads with one line.
. tests/lib.sh
R=$BIN/locus-raster
F=$BIN/locus-film

# 1500 random strokes (every width, join, cap, dashes), fills, spans and image rows, a clear
# halfway, on a 640 x 480 page
awk 'BEGIN {
	s = 4711
	print "LOCUS-META 1\npage 640 480"
	for (k = 0; k < 1500; k++) {
		if (k == 750) print "clear #e0f0f0"
		s = (s * 1103515245 + 12345) % 2147483648; printf "colour #%06x\n", s % 16777216
		printf "width %d\n", (k % 7 == 0) ? 9 : (k % 3)
		printf "join %s\ncap %s\n", (k % 3 == 0) ? "miter" : (k % 3 == 1) ? "round" : "bevel", (k % 4 == 0) ? "butt" : (k % 4 == 1) ? "round" : "square"
		print (k % 5 == 0) ? "dash 4 2.5" : "dash"
		print (k % 6 == 0) ? "fill" : "stroke"
		s = (s * 1103515245 + 12345) % 2147483648; x = s % 640000 / 1000
		s = (s * 1103515245 + 12345) % 2147483648; y = s % 480000 / 1000
		printf "move %.3f %.3f\n", x, y
		for (i = 0; i < 20; i++) {
			s = (s * 1103515245 + 12345) % 2147483648; x += (s % 30000) / 1000 - 15
			s = (s * 1103515245 + 12345) % 2147483648; y += (s % 30000) / 1000 - 15
			printf "draw %.3f %.3f\n", x, y
		}
		print "end"
		if (k % 40 == 0) printf "span %d %d 60 #00a000\n", k % 500, (k * 7) % 480
	}
	print "image 20 200 3 5"
	for (i = 0; i < 5; i++) print "row 1 #ff0000 2 #0000ff"
	print "end-page" }' > "$T/pair.meta"

"$R" -f ppm "$T/pair.meta" -o "$T/whole.ppm" || notok "whole page"
# 300-row bands of 1920-byte rows: two of them exceed a 1 MiB budget, so one thread replays
"$R" -f ppm --band-rows 300 --mem-budget 1 "$T/pair.meta" -o "$T/one.ppm" || notok "one-thread bands"
same_file "bands replayed by one thread = the whole page" "$T/one.ppm" "$T/whole.ppm"
for n in 1 7 37 160; do
	"$R" -f ppm --band-rows $n "$T/pair.meta" -o "$T/two-$n.ppm" || notok "two-thread bands of $n"
	same_file "bands of $n rows replayed by two threads = the whole page" "$T/two-$n.ppm" "$T/whole.ppm"
done
"$R" -f ppm --antialias --band-rows 600 --mem-budget 8 "$T/pair.meta" -o "$T/aa-one.ppm" || notok "aa one thread"
"$R" -f ppm --antialias --band-rows 45 "$T/pair.meta" -o "$T/aa-two.ppm" || notok "aa two threads"
same_file "anti-aliased: two-thread bands of 45 sample rows = one-thread bands" "$T/aa-two.ppm" "$T/aa-one.ppm"

# the film device: a 1200 x 800 frame in bands of 50 rows (two threads) and of 400 rows in a
# 2 MiB budget (one thread) give the same file
SOURCE_DATE_EPOCH=1700000000
export SOURCE_DATE_EPOCH
"$F" --size 1200x800 --band-rows 50 "$T/pair.meta" -o "$T/two.dpx" || notok "film two threads"
"$F" --size 1200x800 --band-rows 400 --mem-budget 2 "$T/pair.meta" -o "$T/one.dpx" || notok "film one thread"
same_file "film frame: two-thread bands = one-thread bands" "$T/two.dpx" "$T/one.dpx"

# a write failure in the middle: one line, exit 74, for bands handed on by either thread
for n in 5 37; do
	"$R" -f ppm --band-rows $n "$T/pair.meta" -o /dev/full 2> "$T/full.err"
	rc=$?
	[ $rc = 74 ] && [ "$(wc -l < "$T/full.err")" = 1 ] && ok "bands of $n onto a full device: 74, one line" ||
		notok "bands of $n onto a full device: exit $rc: $(cat "$T/full.err")"
done
# bad input after many records: 65, no output
{ sed '$d' "$T/pair.meta"; echo "draw 1 2"; } > "$T/bad.meta"
"$R" -f ppm --band-rows 7 "$T/bad.meta" -o "$T/bad.ppm" 2> "$T/bad.err"
rc=$?
[ $rc = 65 ] && [ ! -e "$T/bad.ppm" ] && ok "bad input mid-page in bands: 65, no output" || notok "bad input in bands: exit $rc"
done_tests

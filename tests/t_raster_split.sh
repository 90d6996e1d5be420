#!/bin/sh
# t_raster_split.sh: a whole page painted by two threads (rows split at the middle) has the bytes
# of the one-thread banded replay, across many hand-overs, several pages, and bad input.
. tests/lib.sh
R=$BIN/locus-raster

# A file of about 4 MB of records: random walks of every stroke style across the middle row,
# fills, spans, an image and a clear halfway; then a small page (one thread) and a tall one.
gen() {
	awk -v pages="$1" 'BEGIN {
		s = 12345
		print "LOCUS-META 1"
		for (pg = 0; pg < pages; pg++) {
			h = pg == 1 ? 100 : 480 + 40 * pg
			print "page 640 " h
			for (k = 0; k < 1200; k++) {
				if (k == 600) print "clear #f0f0e0"
				s = (s * 1103515245 + 12345) % 2147483648; c = s % 16777216
				printf "colour #%06x\n", c
				printf "width %d\n", (k % 7 == 0) ? 6 : (k % 3)
				printf "join %s\n", (k % 3 == 0) ? "miter" : (k % 3 == 1) ? "round" : "bevel"
				printf "cap %s\n", (k % 4 == 0) ? "butt" : (k % 4 == 1) ? "round" : "square"
				if (k % 5 == 0) print "dash 4 2.5"; else print "dash"
				print (k % 11 == 0) ? "fill" : "stroke"
				s = (s * 1103515245 + 12345) % 2147483648; x = s % 640000 / 1000
				s = (s * 1103515245 + 12345) % 2147483648; y = s % (h * 1000) / 1000
				printf "move %.3f %.3f\n", x, y
				for (i = 0; i < 100; i++) {
					s = (s * 1103515245 + 12345) % 2147483648; x += (s % 9000) / 1000 - 4.5
					s = (s * 1103515245 + 12345) % 2147483648; y += (s % 9000) / 1000 - 4.5
					printf "draw %.3f %.3f\n", x, y
				}
				if (k % 9 == 0) print "close"
				print "end"
				if (k % 50 == 0) printf "span %d %d 40 #00ff00\n", k % 600, (k * 7) % h
			}
			print "image 10 " int(h / 2) - 2 " 3 4"
			for (i = 0; i < 4; i++) print "row 1 #ff0000 2 #0000ff"
			print "end-page"
		}
	}'
}
gen 3 > "$T/split.meta"
[ "$(wc -c < "$T/split.meta")" -gt 2000000 ] && ok "test input is large (several record blocks for the helper)" ||
	notok "test input is only $(wc -c < "$T/split.meta") bytes"

check "three pages, two threads" "$R" -f ppm "$T/split.meta" -o "$T/two.ppm"
check "three pages, banded replay (bands of 13 rows, two painters)" "$R" -f ppm --band-rows 13 "$T/split.meta" -o "$T/one.ppm"
for n in 001 002 003; do
	same_file "page $n: two-thread page identical to the banded replay" "$T/two-$n.ppm" "$T/one-$n.ppm"
done
# the pictures have something in both halves (so that both threads had something to paint)
printf 'LOCUS-META 1\npage 640 480\nend-page\n' > "$T/blank.meta"
"$R" -f ppm "$T/blank.meta" -o "$T/blank.ppm"
head -c 460815 "$T/two-001.ppm" | tail -c 460800 > "$T/top"
tail -c 460800 "$T/two-001.ppm" > "$T/bottom"
tail -c 460800 "$T/blank.ppm" > "$T/white"
if ! cmp -s "$T/top" "$T/white" && ! cmp -s "$T/bottom" "$T/white"; then ok "page 1 painted in its top and bottom halves"
else notok "page 1 left a half blank"; fi

# an error after many statements on a split page: exit 65, no output left, no hang
{ gen 1 | sed '$d'; echo "draw 1 2"; } > "$T/bad.meta"
expect_exit 65 "error in the middle of a split page: exit 65" "$R" -f ppm "$T/bad.meta" -o "$T/bad.ppm"
[ ! -e "$T/bad.ppm" ] && [ ! -e "$T/bad-001.ppm" ] && ok "no output left after the error" || notok "output left after the error"
done_tests

#!/bin/sh
# t_svg_import_occlude.sh: locus-meta import -O occlude (hidden-line removal): on the fixture
# fixtures/import/occlude.svg (fixtures/README.md) the grid is cut under the even-odd ring but
# kept in its hole, cut under the whole non-zero square, the ring's outline cut under the white
# circle; -O occlude composes with -O dedupe; --stats reports it; and on vpype's 500 circles
# (../shared/corpus/svg) given white fills, the occluded plot rasterises like the painted drawing.
. tests/lib.sh
M=$BIN/locus-meta
F=fixtures/import/occlude.svg
# samples COLOUR FILE: points every 0.25 mm along the strokes of COLOUR, "x y" in SVG user units
# (--dpi 25.4 makes one meta pixel one millimetre, one user unit; y flipped back)
samples() {
	awk -v want="$1" 'BEGIN { c = "#000000" } /^colour/ { c = $2 } /^(stroke|fill)/ { k = $1 }
		/^move/ { px = $2; py = $3; if (c == want) print px, 100 - py }
		/^draw/ { if (c == want) { L = sqrt(($2-px)^2 + ($3-py)^2); n = int(L / 0.25) + 1
			for (i = 1; i <= n; i++) print px + ($2-px)*i/n, 100 - (py + ($3-py)*i/n) } px = $2; py = $3 }' "$2"
}
# count_in FILE AWKCOND: samples satisfying the condition (x, y)
count_in() { awk "{ x = \$1; y = \$2 } $2 { n++ } END { print n + 0 }" "$1"; }
"$M" import --dpi 25.4 -O occlude "$F" -o "$T/o.meta" 2> "$T/err" && "$M" import --dpi 25.4 "$F" -o "$T/n.meta" &&
	"$M" check "$T/o.meta" > /dev/null && ok "-O occlude imports the fixture, the meta file is valid" || notok "occlude import: $(cat "$T/err")"
samples '#000000' "$T/o.meta" > "$T/ob"; samples '#000000' "$T/n.meta" > "$T/nb"
ring='x > 20.3 && x < 59.7 && y > 20.3 && y < 59.7 && !(x > 29.7 && x < 50.3 && y > 29.7 && y < 50.3)'
hole='x > 30.3 && x < 49.7 && y > 30.3 && y < 49.7'
green='x > 68.3 && x < 91.7 && y > 8.3 && y < 31.7'
circle='(x-65)^2 + (y-65)^2 < 19.7^2'
a=$(count_in "$T/ob" "$ring") b=$(count_in "$T/ob" "$hole") c=$(count_in "$T/ob" "$green") d=$(count_in "$T/ob" "$circle")
na=$(count_in "$T/nb" "$ring") nc=$(count_in "$T/nb" "$green") nd=$(count_in "$T/nb" "$circle")
[ "$a" = 0 ] && [ "$b" -gt 200 ] && [ "$c" = 0 ] && [ "$d" = 0 ] && [ "$na" -gt 300 ] && [ "$nc" -gt 300 ] && [ "$nd" -gt 300 ] &&
	ok "grid cut under the even-odd ring ($na samples -> 0) but kept in its hole ($b), cut under the non-zero square ($nc -> 0) and the white circle ($nd -> 0)" ||
	notok "occlusion: ring $a (was $na) hole $b green $c (was $nc) circle $d (was $nd)"
# the fills became outlines: the red ring's outline is cut where the circle covers its corner
samples '#ff0000' "$T/o.meta" > "$T/or"
r_all=$(wc -l < "$T/or") r_in=$(count_in "$T/or" "$circle")
grep -q '^fill' "$T/o.meta" && notok "-O occlude left fill paths" ||
	{ [ "$r_all" -gt 400 ] && [ "$r_in" = 0 ] && ! grep -q '^colour #ffffff' "$T/o.meta" &&
		ok "fills drawn as outlines ($r_all red samples), the ring's corner under the circle cut, the white fill draws nothing" ||
		notok "outlines: red $r_all, under the circle $r_in, $(grep -c '^colour #ffffff' "$T/o.meta") white"; }
# composes with dedupe; --stats before and after
"$M" import --dpi 25.4 -O occlude -O dedupe "$F" -o "$T/od1.meta" && "$M" import --dpi 25.4 -O occlude,dedupe "$F" -o "$T/od2.meta" &&
	cmp -s "$T/od1.meta" "$T/od2.meta" && ok "-O occlude -O dedupe and -O occlude,dedupe agree" || notok "-O lists differ"
"$M" import -O occlude,dedupe --stats "$F" -o "$T/od.meta" > "$T/st" 2>&1
b_down=$(sed -n 's/.*before: pen-down \([0-9.]*\) mm.*/\1/p' "$T/st") a_down=$(sed -n 's/.*after occlude+dedupe: pen-down \([0-9.]*\) mm.*/\1/p' "$T/st")
[ -n "$b_down" ] && [ -n "$a_down" ] && awk -v b="$b_down" -v a="$a_down" 'BEGIN { exit !(a < 0.8 * b) }' &&
	ok "--stats: pen-down $b_down mm before, $a_down mm after occlude+dedupe" || notok "stats: $(cat "$T/st")"
"$M" import -O nonsense "$F" -o "$T/x.meta" 2> "$T/err"; r=$?
[ $r = 64 ] && [ ! -e "$T/x.meta" ] && grep -q 'unknown (dedupe\[=MM\], occlude)' "$T/err" && ok "-O nonsense: exit 64" || notok "-O nonsense: $r $(cat "$T/err")"
# --- a real drawing: vpype's 500 circles, given white fills (a copy in the scratch directory) ---
if need_corpus svg/vpype "-O occlude on vpype's 500 circles"; then
	sed 's/style="fill:none;stroke:#666"/style="fill:#fff;stroke:#666"/' "$CORPUS_DIR/svg/vpype/benchmark/500_circles.svg" > "$T/c.svg"
	bounded 60 "occlude 500 circles" "$M" import -O occlude --stats "$T/c.svg" -o "$T/co.meta" > "$T/cst" 2>&1 &&
		"$M" import "$T/c.svg" -o "$T/cn.meta" && "$BIN/locus-raster" "$T/co.meta" -o "$T/co.png" && "$BIN/locus-raster" "$T/cn.meta" -o "$T/cn.png" || notok "500 circles: $(cat "$T/cst")"
	if [ -f "$T/co.png" ] && command -v compare > /dev/null; then
		px=$(compare -metric AE -fuzz 20% "$T/cn.png" "$T/co.png" null: 2>&1)
		lifts=$(sed -n 's/.*after occlude: .* \([0-9]*\) lifts.*/\1/p' "$T/cst")
		grep -q '^fill' "$T/co.meta"; f=$?
		[ "$f" = 1 ] && [ "${px%%.*}" -lt 400 ] 2>/dev/null && [ "$lifts" -lt 1000 ] &&
			ok "500 white circles: the occluded lines rasterise like the painted drawing ($px of 4,000,000 pixels differ), $lifts lifts" ||
			notok "500 circles: $px pixels differ, $lifts lifts, $(cat "$T/cst")"
	fi
fi
done_tests

#!/bin/sh
# t_svg_import_text.sh: SVG <text> imported as meta text statements in the stroke font
# (fixtures/import/text.svg, explained in fixtures/README.md): position, size (capital height
# 0.7 em), angle, text-anchor shifted by the advances of docs/stroke-font.md's table, the pen
# colour; one warning per kind with its line; bad values as SVG says; and rsvg-convert's picture
# of the same file has its ink of each colour in the same place within 5 mm.
. tests/lib.sh
M=$BIN/locus-meta
F=fixtures/import/text.svg
timeout 20 "$M" import "$F" -o "$T/t.meta" 2> "$T/err"; r=$?
[ "$r" = 0 ] && "$M" check "$T/t.meta" > /dev/null && ok "text.svg imports to a valid meta file" || notok "import: exit $r $(cat "$T/err")"
[ "$(grep -c 'warning' "$T/err")" = 1 ] && grep -q 'text.svg:6: warning: text drawn in the stroke font' "$T/err" &&
	ok "one warning for the file: text drawn in the stroke font, naming the first text's line" || notok "warnings: $(cat "$T/err")"
# the advance (font units) of each character, from the font's table in docs/stroke-font.md
awk -F' [|] ' '/^[|] [0-9a-f][0-9a-f] [|]/ { c = $3; gsub(/`/, "", c); if (c == "space") c = " "; print c "\t" $4 }' docs/stroke-font.md > "$T/adv"
[ "$(wc -l < "$T/adv")" -ge 95 ] || notok "advances not found in docs/stroke-font.md"
# expected: page 454 x 303 px (120 x 80 mm, the height rounded up), 3.7795 px a user unit, y up;
# the capital height is 0.7 font-size; start shifts 0, middle half the advance, end all of it
awk -F'\t' -v K=3.779527559 -v PH=303 '
	FILENAME == ARGV[1] { adv[$1] = $2; next }
	function A(s,   i, a) { a = 0; for (i = 1; i <= length(s); i++) a += adv[substr(s, i, 1)]; return a }
	function want(name, s, x, y, fs, ang, anchor,   size, w) {
		size = 0.7 * fs * K; w = A(s) * size / 6
		ex[s] = sprintf("%.3f %.3f %.3f %s", x * K - anchor * w / 2, PH - y * K, size, ang) }
	BEGIN { }
	FILENAME == ARGV[2] && FNR == 1 {
		want("start", "HELLO", 10, 18, 12, 0, 0); want("middle", "MIDDLE", 60, 36, 8, 0, 1)
		want("end", "END", 110, 52, 2.5 * 96 / 25.4, 0, 2)
		want("rot", "ROT", 20, 74, 10, 30, 0); want("ab", "AB", 62, 72, 10, 0, 0)
		abw = A("AB") * 0.7 * 10 / 6; want("cd", "CD", 62 + abw + 4, 72, 10, 0, 0) }
	/^text / { s = $6; gsub(/"/, "", s); got = sprintf("%.3f %.3f %.3f %s", $2, $3, $4, $5); n++
		split(got, g, " "); split(ex[s], e, " ")
		if (!(s in ex) || (g[1]-e[1])^2 > 0.01^2 || (g[2]-e[2])^2 > 0.01^2 || (g[3]-e[3])^2 > 0.01^2 || g[4] != e[4]) { print "text " s ": got " got ", expected " ex[s]; bad++ } }
	END { if (n != 6) print "found " n " text statements, expected 6"; exit !(n == 6 && !bad) }' "$T/adv" "$T/t.meta" > "$T/why" &&
	ok "text statements: position, capital height 0.7 em (px, mm, class), angle from rotate, anchors start/middle/end by the font's advances, a tspan's dx" ||
	notok "text statements: $(cat "$T/why")"
[ "$(grep -E '^(colour|text)' "$T/t.meta" | sed -n '2,12p' | awk '{ print $1 == "colour" ? $2 : $NF }' | tr '\n' ' ')" = '#000000 "HELLO" #ff0000 "MIDDLE" #0000ff "END" #008000 "ROT" "AB" #ff00ff "CD" ' ] &&
	ok "pens: the fill colour when there is no stroke, the stroke colour when there is (END), a tspan's own fill" ||
	notok "colours: $(grep -E '^(colour|text)' "$T/t.meta" | tr '\n' ' ')"
grep -q '^width 2.268$' "$T/t.meta" && ok "stroked text drawn with its stroke width (0.6 user units)" || notok "width of END"
# --- pens by colour: text items take part like other items ---
timeout 20 "$M" import --pens by-colour "$F" -o "$T/p.meta" 2> /dev/null && [ "$(grep -c '^text' "$T/p.meta")" = 6 ] &&
	ok "--pens by-colour keeps the text statements" || notok "by-colour"
# --- --stats counts the glyphs' strokes: I (2 + 6 + 2 units) and - (3) at 1 mm a unit, rotated ---
printf '%s\n' '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">' \
	'<text x="10" y="50" style="font-size:8.5714286px" transform="rotate(90 10 50)">I-</text></svg>' > "$T/st.svg"
timeout 20 "$M" import --stats "$T/st.svg" -o "$T/st.meta" > "$T/err" 2>&1
grep -q 'before: pen-down 13.0 mm, .* 4 lifts' "$T/err" && ok "--stats: text's pen-down length and lifts from the font's strokes (13.0 mm, 4 lifts)" ||
	notok "stats of text: $(cat "$T/err")"
# --- what the statement cannot carry: one warning per kind with its line; bad values as SVG says ---
printf '%s\n' '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="100" height="100">' \
	'<text x="1 2 3" y="50" letter-spacing="2">A</text>' \
	'<text x="bad" y="40" font-size="-3" text-anchor="bogus" fill="#000">B</text>' \
	'<text x="10" y="60" transform="skewX(20)" textLength="30">C</text>' \
	'<path id="p" d="M0 0 L 50 50"/><text><textPath xlink:href="#p">D</textPath></text>' \
	'<text x="5" y="90">   E  F' '  G   </text><text x="0" y="0" fill="none">H</text></svg>' > "$T/w.svg"
timeout 20 "$M" import "$T/w.svg" -o "$T/w.meta" 2> "$T/err"
grep -q 'w.svg:2: warning: per-character text positions' "$T/err" && grep -q 'w.svg:2: warning: letter-spacing or word-spacing' "$T/err" &&
	grep -q 'w.svg:4: warning: text under a skew' "$T/err" && grep -q 'w.svg:4: warning: text rotate, textLength' "$T/err" &&
	grep -q 'w.svg:5: warning: textPath (left out)' "$T/err" && [ "$(grep -c warning "$T/err")" = 6 ] &&
	ok "letter-spacing, per-character x, skew, textLength, textPath: each named once with its line" || notok "warnings: $(cat "$T/err")"
grep -q '^text 1 50 11.2 0 "A"$' "$T/w.meta" && grep -q '^text 0 60 11.2 0 "B"$' "$T/w.meta" && grep -q '^text 5 10 11.2 0 "E F G"$' "$T/w.meta" &&
	! grep -q '"D"\|"H"' "$T/w.meta" &&
	ok "the first of several x; a bad x is 0, a negative font-size and a bad text-anchor ignored; spaces collapsed; textPath and unpainted text left out" ||
	notok "bad values: $(grep '^text' "$T/w.meta" | tr '\n' ' ')"
# --- drawn: locus-raster's picture, and rsvg-convert's of the same SVG: each colour's ink in the same place ---
if ! command -v rsvg-convert > /dev/null || ! command -v convert > /dev/null; then
	skip "rsvg-convert or ImageMagick missing: no comparison of the pictures"
	ok "text drawn where rsvg-convert draws it # SKIP rsvg-convert or ImageMagick missing"
else
	timeout 60 "$BIN/locus-raster" --antialias "$T/t.meta" -o "$T/l.png" && timeout 60 rsvg-convert -b white "$F" -o "$T/r.png" ||
		notok "rendering text.svg"
	for f in l r; do
		timeout 60 convert "$T/$f.png" -depth 8 txt:- | awk -v C='0 0 0,255 0 0,0 0 255,0 128 0,255 0 255' '
			BEGIN { n = split(C, cs, ","); for (i = 1; i <= n; i++) { split(cs[i], q, " "); r[i] = q[1]; g[i] = q[2]; b[i] = q[3]; x0[i] = y0[i] = 1e9; x1[i] = y1[i] = -1 } }
			/^[0-9]/ { split($1, p, /[,:]/); s = $2; gsub(/[()]/, "", s); split(s, v, ",")
				for (i = 1; i <= n; i++) if ((v[1]-r[i])^2 + (v[2]-g[i])^2 + (v[3]-b[i])^2 < 8100) {
					if (p[1] < x0[i]) x0[i] = p[1]; if (p[1] > x1[i]) x1[i] = p[1]; if (p[2] < y0[i]) y0[i] = p[2]; if (p[2] > y1[i]) y1[i] = p[2] } }
			END { for (i = 1; i <= n; i++) print i, x0[i], y0[i], x1[i], y1[i] }' > "$T/$f.box"
	done
	# at 3.78 px a mm: tops and bottoms within 2 mm (7.6 px); left and right edges within 6 mm
	# (22.7 px), as the stroke font is narrower than a sans or a serif, so the far end of a line
	# (the right edge of start-anchored text, the left of end-anchored) moves by a few mm
	paste "$T/l.box" "$T/r.box" | awk '{ for (k = 2; k <= 5; k++) { d = $k - $(k + 5); if (d < 0) d = -d; if (k % 2) { if (d > my) my = d } else if (d > mx) mx = d }
		if ($3 < 0 || $8 < 0) none++ } END { printf "%.1f mm across, %.1f mm up and down\n", mx / 3.7795, my / 3.7795; exit !(mx <= 22.7 && my <= 7.6 && !none) }' > "$T/far" &&
		ok "each colour's ink where rsvg-convert puts it (farthest edges: $(cat "$T/far"))" ||
		notok "ink boxes differ by $(cat "$T/far"): $(paste "$T/l.box" "$T/r.box" | tr '\n' ';')"
fi
done_tests

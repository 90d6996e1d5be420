#!/bin/sh
# t_import.sh: locus-meta import turns HP-GL (the corpus) and plotutils metafiles (what graph and
# plot write, portable and binary) into valid meta files that draw what the originals draw.
. tests/lib.sh
M=$BIN/locus-meta
C=$CORPUS_DIR/hpgl
corpus=0
need_corpus hpgl "the HP-GL corpus imports, --pens on corpus files and the corpus goldens" && corpus=1
n=0
[ $corpus = 1 ] && for f in $C/*; do
	case $f in *.md) continue ;; esac
	b=$(basename "$f")
	if "$M" import "$f" -o "$T/$b.meta" 2> "$T/err" && "$M" check "$T/$b.meta" > /dev/null &&
			$BIN/locus-raster -o "$T/$b.png" "$T/$b.meta" 2>> "$T/err"; then
		n=$((n + 1))
	else
		notok "import $b: $(cat "$T/err")"
	fi
done
[ $corpus = 0 ] || { [ $n -ge 17 ] && ok "all $n corpus files import to valid meta files that render" || notok "only $n corpus files imported"; }
# one known stroke: pen 2 (red), plotter units to millimetres, the page the extent plus 2 %
printf 'IN;SP2;PU0,0;PD4000,0,4000,2000;' > "$T/k.hpgl"
"$M" import "$T/k.hpgl" > "$T/k.meta"
grep -q "^page 416 216$" "$T/k.meta" && grep -q "^size 104 54$" "$T/k.meta" && grep -q "^colour #ff0000$" "$T/k.meta" &&
	grep -q "^move 8 8$" "$T/k.meta" && grep -q "^draw 408 8$" "$T/k.meta" && grep -q "^draw 408 208$" "$T/k.meta" &&
	ok "HP-GL: a red stroke at 4 pixels a millimetre with the margin" || notok "known stroke: $(cat "$T/k.meta")"
# --- round 2: what the plotter draws beyond the strokes (one check per command family) ---
imp() { printf '%s' "$1" > "$T/c.hpgl" && "$M" import "$T/c.hpgl" -o "$T/c.meta" 2> "$T/err" || notok "import of '$1': $(cat "$T/err")"; }
# PW: 0.5 mm at 4 pixels a millimetre is a line 2 pixels wide; PC: the pen's colour
imp 'IN;PW0.5,1;PC1,10,20,30;SP1;PA0,0;PD4000,0;'
grep -q "^width 2$" "$T/c.meta" && grep -q "^colour #0a141e$" "$T/c.meta" &&
	ok "PW 0.5 mm: width 2 pixels; PC 1,10,20,30: colour #0a141e" || notok "PW/PC: $(grep -E '^(width|colour)' "$T/c.meta")"
# WU 1: PW in percent of the P1-P2 diagonal (5000 units: 1 % = 50 units = 5 pixels)
imp 'IN;IP0,0,4000,3000;WU1;PW1;SP1;PA0,0;PD4000,0;'
grep -q "^width 5$" "$T/c.meta" && ok "WU 1; PW 1: 1 % of the diagonal, 5 pixels" || notok "WU: $(grep '^width' "$T/c.meta")"
# LT 2,10: a pattern of 10 % of the 5000-unit diagonal (50 pixels), dash 50 % then gap; LT 2,4,1: 4 mm
imp 'IN;IP0,0,4000,3000;SP1;LT2,10;PA0,0;PD4000,0;LT2,4,1;PU0,1000;PD4000,1000;LT;PU0,2000;PD4000,2000;'
[ "$(grep '^dash' "$T/c.meta" | tr '\n' '|')" = "dash 25 25|dash 8 8|dash|" ] &&
	ok "LT 2,10 (percent): dash 25 25; LT 2,4,1 (mm): dash 8 8; LT: solid" || notok "LT: $(grep '^dash' "$T/c.meta" | tr '\n' '|')"
# LT -2 adaptive: a 4000-unit line holds a whole number of 450-unit patterns (9 of 444.4)
imp 'IN;IP0,0,4000,3000;SP1;LT-2,9;PA0,0;PD4000,0;'
grep -q "^dash 22.222 22.222$" "$T/c.meta" && ok "LT -2 adaptive: 9 whole patterns along the line" || notok "adaptive: $(grep '^dash' "$T/c.meta")"
# FT 3,400,45: hatch lines at 45 degrees, 400 units (40 pixels) apart, inside the rectangle
imp 'IN;SP1;FT3,400,45;PA0,0;RA4000,4000;'
awk '/^move/{x=$2; y=$3} /^draw/{dx=$2-x; dy=$3-y; if (dx < 0) { dx = -dx; dy = -dy }
	a = atan2(dy, dx) * 45 / atan2(1, 1); if (a < 44.9 || a > 45.1) bad++
	v = (-x + y) / sqrt(2); vs[n++] = v; if ($2 < 7.9 || $2 > 408.1 || $3 < 7.9 || $3 > 408.1) bad++ }
	END { if (n < 10) bad++; for (i = 1; i < n; i++) { d = vs[i] - vs[i-1]; if (d < 0) d = -d; if (d < 39.9 || d > 40.1) bad++ }
	exit bad > 0 }' "$T/c.meta" && [ "$(grep -c '^fill$' "$T/c.meta")" = 0 ] &&
	ok "FT 3,400,45: hatch lines at 45 degrees, 40 pixels apart, within the rectangle" || notok "FT 3: $(head -c 600 "$T/c.meta")"
# FT 4: the same lines and as many again at 90 degrees more; FT 10,25: 25 % of blue over white
imp 'IN;SP1;FT4,400,0;PA0,0;RA4000,4000;'
h=$(awk '/^move/{y=$3} /^draw/{if ($3 == y) h++; else v++} END {print h + 0, v + 0}' "$T/c.meta")
[ "$h" = "10 10" ] && ok "FT 4,400,0: 10 horizontal and 10 vertical lines" || notok "FT 4: $h"
imp 'IN;PC1,0,0,255;SP1;FT10,25;PA0,0;RA4000,4000;'
grep -q "^colour #bfbfff$" "$T/c.meta" && grep -q "^fill$" "$T/c.meta" && ok "FT 10,25: filled in #bfbfff" || notok "FT 10: $(grep -E '^(colour|fill)' "$T/c.meta")"
# PM with a hole: FP (even-odd) leaves the inner square white; FP 1 (non-zero, both drawn the
# same way round) fills it; EP draws no edge along the pen-up move between the contours
pix() { convert "$1" -format "%[pixel:p{$2,$3}]" info: 2>/dev/null; }
for rule in '' 1; do
	imp "IN;SP1;PA0,0;PM0;PD4000,0,4000,4000,0,4000,0,0;PM1;PU1000,1000;PD3000,1000,3000,3000,1000,3000,1000,1000;PM2;FP$rule;"
	$BIN/locus-raster -o "$T/pm$rule.png" "$T/c.meta" || notok "raster of PM"
done
W='srgb(255,255,255)' K='srgb(0,0,0)'
[ "$(pix "$T/pm.png" 208 208)" = "$W" ] && [ "$(pix "$T/pm.png" 58 358)" = "$K" ] && [ "$(pix "$T/pm1.png" 208 208)" = "$K" ] &&
	ok "PM/FP: even-odd leaves the hole white, non-zero fills it" || notok "PM: $(pix "$T/pm.png" 208 208) $(pix "$T/pm.png" 58 358) $(pix "$T/pm1.png" 208 208)"
imp 'IN;SP1;PA0,0;PM0;PD4000,0,4000,4000,0,4000,0,0;PM1;PU1000,1000;PD3000,1000,3000,3000,1000,3000,1000,1000;PM2;EP;'
[ "$(grep -c '^move' "$T/c.meta")" = 2 ] && [ "$(grep -c '^draw' "$T/c.meta")" = 8 ] && ok "EP: two contours, no edge between them" || notok "EP: $(grep -c '^move' "$T/c.meta") subpaths"
# labels: a reference stroke fixes the page (0 .. 8000 units: the point 4000,4000 is pixel
# 416,416); SI 0.5,1 (200 x 400 units); the ink's box tells where the label went
ink() { awk '/^end$/ && !e { e = 1; next } e && /^(move|draw)/ { if (n++ == 0 || $2 < x0) x0 = $2; if ($2 > x1) x1 = $2; if (n == 1 || $3 < y0) y0 = $3; if ($3 > y1) y1 = $3 }
	END { printf "%.0f %.0f %.0f %.0f", x0, y0, x1, y1 }' "$T/c.meta"; }
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;LBAB$(printf '')"
[ "$(ink)" = "416 416 466 456" ] && ok "LB (LO 1): starts at the point, two 300-unit cells, cap height 400" || notok "LO 1: $(ink)"
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;LO5;LBAB$(printf '')"
[ "$(ink)" = "391 396 441 436" ] && ok "LO 5: the label centred on the point" || notok "LO 5: $(ink)"
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;LO13;LBAB$(printf '')"
[ "$(ink)" = "426 356 476 396" ] && ok "LO 13: left top, half a character off the point" || notok "LO 13: $(ink)"
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;CP2,-1;LBA$(printf '')"
[ "$(ink)" = "476 336 496 376" ] && ok "CP 2,-1: two cells right, a line (2 cap heights) down" || notok "CP: $(ink)"
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;DI0,1;LBAB$(printf '')"
[ "$(ink)" = "376 416 416 466" ] && ok "DI 0,1: the label runs up" || notok "DI: $(ink)"
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;SL1;LBI$(printf '')"
grep -q "^move 456 456$" "$T/c.meta" && grep -q "^move 416 416$" "$T/c.meta" && grep -q "^draw 421 416$" "$T/c.meta" && ok "SL 1: the I leans 45 degrees (its top 40 pixels right)" || notok "SL: $(sed -n 14,24p "$T/c.meta" | tr '\n' ' ')"
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;ES1;LBAB$(printf '')"
[ "$(ink)" = "416 416 496 456" ] && ok "ES 1: a cell and a half more between the characters" || notok "ES: $(ink)"
# the pen after a label: at the next character's origin (two 300-unit cells on), or with a CR
# before the terminator back at the carriage-return point (HP-GL/2: LB, LO)
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;LBAB$(printf '\003')PD4000,0;"
grep -q "^move 476 416$" "$T/c.meta" && grep -q "^draw 416 16$" "$T/c.meta" && ok "after LB the pen is past the label" || notok "pen after LB: $(grep -E '^(move|draw)' "$T/c.meta" | tail -2 | tr '\n' ' ')"
imp "IN;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;LO18;LBAB$(printf '\r\003')PD4000,0;"
grep -q "^move 416 416$" "$T/c.meta" && grep -q "^draw 416 16$" "$T/c.meta" && ok "a CR before the terminator: the pen back at the point (LO 18)" || notok "pen after CR: $(grep -E '^(move|draw)' "$T/c.meta" | tail -2 | tr '\n' ' ')"
imp "IN;DTX;SI0.5,1;PA0,0;PD0,8000;PU4000,4000;LBABXPU;"
[ "$(ink)" = "416 416 466 456" ] && ok "DT X: the label ends at its terminator" || notok "DT: $(ink)"
imp "IN;SI0.5,1;SM+;PA0,0;PD0,8000;PU;SM;PA4000,4000;"
[ "$(grep -c '^move' "$T/c.meta")" = 5 ] && awk '/^move/ { m++; mx[m] = $2; my[m] = $3; getline; dx[m] = $2; dy[m] = $3 }
	function near(a, b) { return a - b < 0.01 && b - a < 0.01 }
	END { exit !(near(mx[2], mx[1]) && near(dx[2], mx[1]) && near((mx[3] + dx[3]) / 2, mx[1]) && near((my[2] + dy[2]) / 2, my[3]) && near(my[3], my[1])) }' "$T/c.meta" &&
	ok "SM +: a symbol centred on each point of PA and PD, none after SM;" || notok "SM: $(sed -n 9,40p "$T/c.meta" | tr '\n' ' ')"
# IW clips strokes (and the page is what is drawn)
imp 'IN;IW0,0,2000,2000;SP1;PA0,0;PD4000,4000;'
grep -q "^page 208 208$" "$T/c.meta" && grep -q "^draw 204 204$" "$T/c.meta" && ok "IW: the line clipped at the window" || notok "IW: $(grep -E '^(page|draw)' "$T/c.meta")"
# the reader's errors carry through under --strict: byte offset, 65, no output file (tolerant,
# the default since issue 22, skips the command with a warning: tests/t_hpgl_import_real.sh)
printf 'IN;SP1;PD100,' > "$T/bad.hpgl"
"$M" import --strict "$T/bad.hpgl" -o "$T/bad.meta" 2> "$T/err"; rc=$?
[ $rc = 65 ] && grep -q "bad.hpgl: byte" "$T/err" && [ ! -e "$T/bad.meta" ] && ok "bad HP-GL: 65, byte named, no output" || notok "bad HP-GL: $rc $(cat "$T/err")"
expect_exit 66 "missing input: 66" "$M" import "$T/none.hpgl"
# plotutils: graph's binary and portable metafiles give the same meta file
printf '0 0\n1 1\n2 0\n3 2\n' > "$T/d.txt"
graph -T meta "$T/d.txt" > "$T/g1.plot" && graph -T meta -O "$T/d.txt" > "$T/g2.plot" || notok "graph -T meta"
head -c 8 "$T/g1.plot" | grep -q "#PLOT 1" && head -c 8 "$T/g2.plot" | grep -q "#PLOT 2" && ok "graph wrote both forms" || notok "metafile forms"
"$M" import "$T/g1.plot" -o "$T/g1.meta" && "$M" import "$T/g2.plot" -o "$T/g2.meta" && same_file "binary and portable metafile: one meta file" "$T/g1.meta" "$T/g2.meta"
# plot's own conversion of the portable form back to binary: the same again
plot -T meta "$T/g2.plot" > "$T/g3.plot" && "$M" import "$T/g3.plot" -o "$T/g3.meta" && same_file "plot -T meta's rewrite: the same meta file" "$T/g1.meta" "$T/g3.meta"
# without axis labels (the fonts differ), the picture is graph's own PNG within a few pixels
graph -T meta -g 0 "$T/d.txt" > "$T/n.plot" && graph -T png -g 0 "$T/d.txt" > "$T/n.png"
"$M" import "$T/n.plot" | $BIN/locus-raster -o "$T/nl.png"
check "plotutils drawing = graph -T png within 25 dB PSNR" $BIN/locus-diff --psnr 25 "$T/nl.png" "$T/n.png"
# pic2plot's metafile (boxes, arrows, text) imports and renders
printf '.PS\nbox "A"; arrow; circle "B"\n.PE\n' | pic2plot -T meta > "$T/p.plot" 2>/dev/null &&
	"$M" import "$T/p.plot" -o "$T/p.meta" && $BIN/locus-raster -o "$T/p.png" "$T/p.meta" && ok "pic2plot's metafile imports" || notok "pic2plot"
# bad metafiles: the byte named, 65
head -c 40 "$T/g1.plot" > "$T/cut.plot"
"$M" import "$T/cut.plot" 2> "$T/err" > /dev/null; rc=$?
[ $rc = 65 ] && grep -q "cut.plot: byte [0-9]*: " "$T/err" && ok "truncated metafile: 65 with the byte" || notok "cut: $rc $(cat "$T/err")"
printf '#PLOT 2\no\nQ 1 2\nx\n' > "$T/q.plot"
"$M" import "$T/q.plot" 2> "$T/err" > /dev/null; rc=$?
[ $rc = 65 ] && grep -q "q.plot: byte 10: unknown plotutils op code" "$T/err" && ok "unknown op code: 65 at its byte" || notok "unknown op: $rc $(cat "$T/err")"
# --pens: a profile's carousel for the pens a file sets no PC/PW for (hp2xx-lo.hp: SP1, no PC,
# no PW): pen 1 red and 1 mm (4 px at the import's 4 px/mm); a file's own PW still wins
# (hp2xx-la.hp sets PW 5.0 for its pen 1); a bad spec and a metafile are usage errors, no output
if [ $corpus = 1 ]; then
"$M" import --pens "1=red:1mm" $C/hp2xx-lo.hp -o "$T/pens.meta" && grep -q "^colour #d02020" "$T/pens.meta" && grep -q "^width 4$" "$T/pens.meta" \
	&& ! grep -q "^colour #d02020" fixtures/import/hp2xx-lo.hp.meta && ok "--pens: pen 1 takes the spec's colour and width" || notok "--pens: $(grep -E '^(colour|width)' "$T/pens.meta" | sort -u)"
"$M" import --pens "1=red:1mm" $C/hp2xx-la.hp | grep -q "^width 20$" && ok "--pens: the file's own PW 5.0 wins over the spec" || notok "--pens against PW"
rm -f "$T/bad.meta"
"$M" import --pens "1=zz" $C/hp2xx-lo.hp -o "$T/bad.meta" 2> "$T/err"; rc=$?
[ $rc = 64 ] && [ "$(wc -l < "$T/err")" = 1 ] && grep -q "^locus-meta: --pens: '1=zz': unknown colour" "$T/err" && [ ! -e "$T/bad.meta" ] \
	&& ok "a bad --pens spec: 64, one line, no output: $(cat "$T/err")" || notok "bad pens: $rc $(cat "$T/err")"
fi
"$M" import --pens "1=red" fixtures/import/zigzag.plot > /dev/null 2> "$T/err"; rc=$?
[ $rc = 64 ] && grep -q "plotutils metafile, which has no pens" "$T/err" && ok "--pens on a plotutils metafile: 64" || notok "pens on plot: $rc $(cat "$T/err")"

# goldens (fixtures/import/, looked at; fixtures/README.md): corpus files and graph's zigzag
I=fixtures/import
for f in hp2xx-arcs.hp inkscape-hpgl_output-shapes.hpgl hp2xx-fill.plt hp2xx-fwedges.plt hp2xx-pm.hp \
		hp2xx-pw.hpg hp2xx-la.hp hp2xx-ul.hp hp2xx-lo.hp hp2xx-cp.hp hp2xx-symbols.hp \
		hp2xx-win_1.hp acad-designjet-XANADU2.plt; do
	[ $corpus = 1 ] || break
	"$M" import $C/$f -o "$T/$f.meta" && same_file "golden: $f" "$T/$f.meta" $I/$f.meta
done
"$M" import $I/zigzag.plot -o "$T/z.meta" && same_file "golden: graph's portable zigzag" "$T/z.meta" $I/zigzag.meta
plot -T meta $I/zigzag.plot > "$T/zb.plot" && "$M" import "$T/zb.plot" -o "$T/zb.meta" && same_file "its binary form (plot -T meta): the same golden" "$T/zb.meta" $I/zigzag.meta
done_tests

#!/bin/sh
# t_diff_kinds.sh: locus-diff tells each kind of output from its content and says what changed:
# rasters of every reader, framebuffer dumps, HP-GL strokes, PostScript/PDF, meta statements.
. tests/lib.sh
D=$BIN/locus-diff
G=fixtures/raster/f-test.raster.png
F=fixtures/meta/f-test.meta
# the same picture in every raster format ImageMagick writes: equal to the PNG
convert $G "$T/a.pcx" && convert $G -type palette "$T/a8.pcx" && convert $G BMP3:"$T/a.bmp" &&
convert $G -type palette BMP3:"$T/a4.bmp" && convert $G -type palette PNG8:"$T/a8.png" &&
convert $G -depth 10 "$T/a.dpx" && convert $G -depth 16 "$T/a16.dpx" && convert $G -flip "$T/flip.png" &&
convert $G -flip -define bmp:top-down=true "$T/td.bmp" || notok "ImageMagick made the inputs"
for f in a.pcx a8.pcx a.bmp a4.bmp a8.png a.dpx a16.dpx; do
	"$D" $G "$T/$f" > "$T/out" && grep -q "0 of 19200 pixels differ" "$T/out" && ok "$f (ImageMagick) = the PNG" || notok "$f: $(cat "$T/out")"
done
"$D" "$T/flip.png" "$T/td.bmp" > /dev/null && ok "top-down BMP read top first" || notok "top-down BMP"
cp "$T/a.dpx" "$T/a.png.dpx"; "$D" "$T/a.png.dpx" $G > /dev/null && ok "the kind comes from the content, not the suffix" || notok "suffix"
# the film driver's DPX (both byte orders) and Cineon of one page: each equal to itself, they differ from each other (log codes vs linear)
$BIN/locus-film --size 160x120 -o "$T/f.dpx" $F && $BIN/locus-film --size 160x120 --endian little -o "$T/fl.dpx" $F &&
$BIN/locus-film --size 160x120 -f cineon -o "$T/f.cin" $F || notok "locus-film"
expect_exit 0 "DPX big-endian = little-endian" "$D" "$T/f.dpx" "$T/fl.dpx"
expect_exit 0 "DPX 10-bit = Cineon 10-bit (the same log codes)" "$D" "$T/f.dpx" "$T/f.cin"
# the film goldens: the planar file and each separation hold the RGB frame's codes
FG=fixtures/film
expect_exit 0 "planar DPX (R, G, B elements) = the RGB DPX" "$D" $FG/f-test.film.planar.dpx $FG/f-test.film.dpx
expect_exit 0 "red separation = the red channel (G, B ignored by --tolerance)" "$D" --tolerance 0,255,255 $FG/f-test.film.sep-r.dpx $FG/f-test.film.dpx
expect_exit 0 "green separation = the green channel" "$D" --tolerance 255,0,255 $FG/f-test.film.sep-g.dpx $FG/f-test.film.dpx
expect_exit 0 "blue separation = the blue channel" "$D" --tolerance 255,255,0 $FG/f-test.film.sep-b.dpx $FG/f-test.film.dpx
expect_exit 1 "a separation is not the colour frame" "$D" $FG/f-test.film.sep-r.dpx $FG/f-test.film.dpx
# framebuffer dumps (no header: told by their size) against the driver's PNG, PCX, BMP
for m in 13h 12h; do
	zcat fixtures/fb/f-test.$m.dump.gz > "$T/$m.dump"
	$BIN/locus-vga --mode $m -f png -o "$T/$m.png" $F
	"$D" "$T/$m.dump" "$T/$m.png" > "$T/out" && grep -q " 0 of " "$T/out" && ok "$m dump = locus-vga's indexed PNG" || notok "$m dump: $(cat "$T/out")"
done
zcat fixtures/fb/f-test.640x480x565.dump.gz > "$T/565.dump"
$BIN/locus-xga --mode 640x480x565 -f bmp -o "$T/565.bmp" $F
expect_exit 0 "640x480x565 dump = locus-xga's BMP" "$D" "$T/565.dump" "$T/565.bmp"
# one stroke changed: where, how much, the picture of it
sed 's/draw 100 92/draw 110 92/' $F > "$T/g.meta"
$BIN/locus-raster -o "$T/g.png" "$T/g.meta"
"$D" $G "$T/g.png" > "$T/out"; rc=$?
[ $rc = 1 ] && grep -q "160 of 19200 pixels differ, max channel difference 232, PSNR 23.31 dB, in 10x16 at (100,20)" "$T/out" && ok "changed stroke: count, PSNR, box" || notok "changed stroke: exit $rc: $(cat "$T/out")"
"$D" -v $G "$T/g.png" > "$T/out"
grep -q "pixel (100,20): #e8e8e8 vs #00c000" "$T/out" && grep -q "\.\.\. 150 more" "$T/out" && ok "-v: the first pixels" || notok "-v: $(cat "$T/out")"
"$D" --json $G "$T/g.png" > "$T/j"
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['differing']==160 and j['bbox']==[100,20,109,35] and not j['same'] and j['first'][0]=={'x':100,'y':20,'a':'#e8e8e8','b':'#00c000'}" "$T/j" && ok "--json parses, the same figures" || notok "--json: $(cat "$T/j")"
"$D" --diff-image "$T/d.png" $G "$T/g.png" > /dev/null; pngtopnm "$T/d.png" > "$T/d.ppm"
python3 - "$T/d.ppm" <<'PY' && ok "--diff-image: 160 red pixels in the box, the rest faded" || notok "--diff-image"
import sys
b = open(sys.argv[1], 'rb').read()
head = b.split(maxsplit=4)
w, h, px = int(head[1]), int(head[2]), head[4]
red = [(i % w, i // w) for i in range(w * h) if px[3 * i:3 * i + 3] == b'\xff\x00\x00']
assert len(red) == 160 and all(100 <= x <= 109 and 20 <= y <= 35 for x, y in red)
assert min(v for i in range(w * h) if px[3 * i:3 * i + 3] != b'\xff\x00\x00' for v in px[3 * i:3 * i + 3]) >= 191
PY
expect_exit 0 "--tolerance 232 ignores it" "$D" --tolerance 232 $G "$T/g.png"
expect_exit 1 "--tolerance 255,39,255 (green over) does not" "$D" --tolerance 255,39,255 $G "$T/g.png"
expect_exit 2 "--tolerance 1,2 refused" "$D" --tolerance 1,2 $G "$T/g.png"
# sizes: refused unless --scale
convert $G -scale 200% "$T/big.png"
"$D" $G "$T/big.png" > "$T/out"; rc=$?
[ $rc = 1 ] && grep -q "sizes differ: 160x120 vs 320x240 (compare them with --scale)" "$T/out" && ok "sizes differ: 1, --scale suggested" || notok "sizes: $rc $(cat "$T/out")"
expect_exit 0 "--scale: doubled picture = the original" "$D" --scale $G "$T/big.png"
expect_exit 0 "--scale: and the other way" "$D" --scale "$T/big.png" $G
# HP-GL: strokes in any order and direction
C=$CORPUS_DIR/hpgl
if need_corpus hpgl "each HP-GL corpus file told HP-GL and equal to itself"; then
n=0
for f in $C/*; do
	case $f in *.md) continue ;; esac
	if "$D" "$f" "$f" > "$T/out" 2>&1 && grep -q "HP-GL, .* 0 missing or changed, 0 extra" "$T/out"; then n=$((n + 1)); else notok "$(basename "$f") = itself: $(cat "$T/out")"; fi
done
[ $n -ge 17 ] && ok "each of the $n corpus files is told HP-GL and equals itself" || notok "corpus: $n"
fi
$BIN/locus-hpgl -o "$T/a.hpgl" $F && $BIN/locus-hpgl --no-optimize -o "$T/n.hpgl" $F && $BIN/locus-hpgl -o "$T/b.hpgl" "$T/g.meta"
"$D" "$T/a.hpgl" "$T/n.hpgl" > "$T/out" && grep -q "0 missing or changed, 0 extra" "$T/out" && ok "optimised = file order: the same strokes" || notok "order: $(cat "$T/out")"
expect_exit 1 "--strict-order: the orders differ" "$D" --strict-order "$T/a.hpgl" "$T/n.hpgl"
"$D" -v "$T/a.hpgl" "$T/b.hpgl" > "$T/out"; rc=$?
[ $rc = 1 ] && grep -q "missing: A's stroke (pen 3" "$T/out" && grep -q "plot time" "$T/out" && ok "changed stroke in HP-GL: pen, command, plot time" || notok "HP-GL: $rc $(cat "$T/out")"
printf 'IN;SP1;PU0,0;PD100,0;PU200,200;PD300,200;' > "$T/h1.hpgl"
printf 'IN;SP1;PU300,200;PD200,200;PU0,0;PD100,0;' > "$T/h2.hpgl"
printf 'IN;SP1;PU0,0;PD100,0;PU200,250;PD300,250;' > "$T/h3.hpgl"
expect_exit 0 "reversed and reordered strokes are the same" "$D" "$T/h1.hpgl" "$T/h2.hpgl"
"$D" -v "$T/h1.hpgl" "$T/h3.hpgl" > "$T/out"
grep -q "moved: A's stroke (pen 1, 2 points from (200,200) to (300,200), command 5 at byte 31) by (0.0,50.0) to B's command 5" "$T/out" && ok "a moved stroke: by how much, its commands" || notok "moved: $(cat "$T/out")"
printf 'IN;SP1;PU0,0;PD100,0;PU200,200;PD300' > "$T/bad.hpgl"
"$D" "$T/h1.hpgl" "$T/bad.hpgl" 2> "$T/err"; rc=$?
[ $rc = 2 ] && grep -q "bad.hpgl: byte" "$T/err" && ok "bad HP-GL: 2, the byte named" || notok "bad HP-GL: $rc $(cat "$T/err")"
# PDF and PostScript: dates and creator do not count; --render compares the pictures
$BIN/locus-ps -o "$T/a.pdf" $F && $BIN/locus-ps -o "$T/b.pdf" "$T/g.meta" && $BIN/locus-ps -f eps -o "$T/a.ps" $F || notok "locus-ps"
sed 's/^%%CreationDate:.*/%%CreationDate: (D:19990101000000)/; s/^%%Creator:.*/%%Creator: someone else/' "$T/a.ps" > "$T/a2.ps"
cmp -s "$T/a.ps" "$T/a2.ps" && notok "the PostScript has a date and a creator to change" || ok "the PostScript has a date and a creator to change"
expect_exit 0 "PostScript: another date and creator are the same" "$D" "$T/a.ps" "$T/a2.ps"
"$D" -v "$T/a.pdf" "$T/b.pdf" > "$T/out"; rc=$?
[ $rc = 1 ] && grep -q "PDF (qpdf's QDF form), 1 of [0-9]* normalised lines differ" "$T/out" && grep -q "A: .* 0 0 m 540 0 l S Q" "$T/out" &&
	grep -q "B: .* 0 0 m 640 0 l S Q" "$T/out" && ok "PDF: the changed stroke's operators, uncompressed by qpdf" || notok "PDF: $rc $(cat "$T/out")"
qpdf --object-streams=generate "$T/a.pdf" "$T/r.pdf"
cmp -s "$T/a.pdf" "$T/r.pdf" && notok "qpdf rewrote the PDF" || ok "qpdf rewrote the PDF (object streams, version 1.5)"
expect_exit 0 "PDF: restructured and renumbered by qpdf, the same" "$D" "$T/a.pdf" "$T/r.pdf"
"$D" --render "$T/a.pdf" "$T/b.pdf" > "$T/out"; rc=$?
[ $rc = 1 ] && grep -q "pixels differ" "$T/out" && ok "--render: Ghostscript's pictures compared" || notok "--render: $rc $(cat "$T/out")"
expect_exit 0 "--render: PDF = EPS of one page" "$D" --render "$T/a.pdf" "$T/a.ps"
expect_exit 2 "PDF against HP-GL: different kinds" "$D" "$T/a.pdf" "$T/a.hpgl"
# meta files: statement by statement, text against binary
$BIN/locus-meta convert --binary $F -o "$T/f.lmb"
if [ -s "$T/f.lmb" ]; then
	expect_exit 0 "--semantic: text = its binary form" "$D" --semantic $F "$T/f.lmb"
	"$D" --semantic -v "$T/f.lmb" "$T/g.meta" > "$T/out"; rc=$?
	[ $rc = 1 ] && grep -q "the first (number 19, page 1) at byte [0-9]* and line 20" "$T/out" && grep -q "A: draw f0=100 f1=92" "$T/out" && ok "--semantic: the first differing statement, byte and line" || notok "semantic: $rc $(cat "$T/out")"
else
	notok "locus-meta made a binary meta file"
fi
"$D" --semantic $F "$T/g.meta" > "$T/out"; rc=$?
[ $rc = 1 ] && grep -q "1 of 37 and 37 statements differ, the first (number 19, page 1) at line 20 and line 20" "$T/out" && ok "--semantic text: line of both" || notok "semantic text: $rc $(cat "$T/out")"
done_tests

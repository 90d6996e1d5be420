#!/bin/sh
# t_import.sh: locus-meta import turns HP-GL (the corpus) and plotutils metafiles (what graph and
# plot write, portable and binary) into valid meta files that draw what the originals draw.
. tests/lib.sh
M=$BIN/locus-meta
C=../shared/corpus/hpgl
n=0
for f in $C/*; do
	case $f in *.md) continue ;; esac
	b=$(basename "$f")
	if "$M" import "$f" -o "$T/$b.meta" 2> "$T/err" && "$M" check "$T/$b.meta" > /dev/null &&
			$BIN/locus-raster -o "$T/$b.png" "$T/$b.meta" 2>> "$T/err"; then
		n=$((n + 1))
	else
		notok "import $b: $(cat "$T/err")"
	fi
done
[ $n -ge 17 ] && ok "all $n corpus files import to valid meta files that render" || notok "only $n corpus files imported"
# one known stroke: pen 2 (red), plotter units to millimetres, the page the extent plus 2 %
printf 'IN;SP2;PU0,0;PD4000,0,4000,2000;' > "$T/k.hpgl"
"$M" import "$T/k.hpgl" > "$T/k.meta"
grep -q "^page 416 216$" "$T/k.meta" && grep -q "^size 104 54$" "$T/k.meta" && grep -q "^colour #ff0000$" "$T/k.meta" &&
	grep -q "^move 8 8$" "$T/k.meta" && grep -q "^draw 408 8$" "$T/k.meta" && grep -q "^draw 408 208$" "$T/k.meta" &&
	ok "HP-GL: a red stroke at 4 pixels a millimetre with the margin" || notok "known stroke: $(cat "$T/k.meta")"
# the reader's errors carry through: byte offset, 65, no output file
printf 'IN;SP1;PD100,' > "$T/bad.hpgl"
"$M" import "$T/bad.hpgl" -o "$T/bad.meta" 2> "$T/err"; rc=$?
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
# goldens (fixtures/import/, looked at; fixtures/README.md): two corpus files and graph's zigzag
I=fixtures/import
for f in hp2xx-arcs.hp inkscape-hpgl_output-shapes.hpgl; do
	"$M" import $C/$f -o "$T/$f.meta" && same_file "golden: $f" "$T/$f.meta" $I/$f.meta
done
"$M" import $I/zigzag.plot -o "$T/z.meta" && same_file "golden: graph's portable zigzag" "$T/z.meta" $I/zigzag.meta
plot -T meta $I/zigzag.plot > "$T/zb.plot" && "$M" import "$T/zb.plot" -o "$T/zb.meta" && same_file "its binary form (plot -T meta): the same golden" "$T/zb.meta" $I/zigzag.meta
done_tests

# diff.sh (sourced by scripts/demo.sh): an HP-GL drawing of the corpus imported and previewed as
# PNG (out/import-*.png), and one stroke of the F changed, diffed as PNG, HP-GL and PDF
# (out/diff-*.txt, the difference picture out/diff-f.png).
diff_demo() {
	if ! [ -x "$BIN/locus-diff" ] || ! [ -x "$BIN/locus-meta" ]; then
		echo "demo: diff: locus-diff or locus-meta not built"
		return
	fi
	for f in hp2xx-acad.hp kicad-laser-B_Cu.plt; do
		if [ -f "../shared/corpus/hpgl/$f" ] && "$BIN/locus-meta" import "../shared/corpus/hpgl/$f" -o "out/import-$f.meta"; then
			"$BIN/locus-raster" "out/import-$f.meta" -o "out/import-$f.png" && echo "demo: diff: out/import-$f.png"
		fi
	done
	sed 's/draw 100 92/draw 110 92/' fixtures/meta/f-test.meta > out/diff-f-b.meta
	# (exit 1 is the answer expected here: they differ; demo.sh runs under set -e)
	"$BIN/locus-diff" --diff-image out/diff-f.png fixtures/meta/f-test.meta out/diff-f-b.meta > out/diff-png.txt || [ $? = 1 ]
	for d in hpgl ps; do
		[ -x "$BIN/locus-$d" ] || continue
		x=$d; [ $d = ps ] && x=pdf
		"$BIN/locus-$d" fixtures/meta/f-test.meta -o "out/diff-f-a.$x" 2> /dev/null
		"$BIN/locus-$d" out/diff-f-b.meta -o "out/diff-f-b.$x" 2> /dev/null
		"$BIN/locus-diff" -v "out/diff-f-a.$x" "out/diff-f-b.$x" > "out/diff-$x.txt" || [ $? = 1 ]
	done
	for t in out/diff-png.txt out/diff-hpgl.txt out/diff-pdf.txt; do
		[ -f "$t" ] && echo "demo: diff: $(head -1 "$t")"
	done
}
diff_demo

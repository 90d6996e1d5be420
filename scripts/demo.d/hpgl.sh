# hpgl.sh (sourced by scripts/demo.sh): the default scene's wireframe and a contour plate to HP-GL,
# with hp2xx's pictures of them beside locus-raster's (out/*.hpgl.png, out/*.raster.png).
hpgl_demo() {
	if ! [ -x "$BIN/locus-hpgl" ] || ! [ -x "$BIN/locus-render" ]; then
		echo "demo: hpgl: locus-hpgl or locus-render not built"
		return
	fi
	for s in wireframe-trifocal contour-sum; do
		if ! "$BIN/locus-render" --quiet "fixtures/scenes/$s.scene" -o "out/$s.meta"; then
			echo "demo: hpgl: cannot render fixtures/scenes/$s.scene"
			continue
		fi
		"$BIN/locus-raster" "out/$s.meta" -o "out/$s.raster.png"
		"$BIN/locus-hpgl" --fit yes --stats "out/$s.meta" -o "out/$s.hpgl" 2> "out/$s.hpgl.stats"
		"$BIN/locus-hpgl" --fit yes --profile hpgl2 "out/$s.meta" -o "out/$s.hpgl2.hpgl" 2> /dev/null
		"$BIN/locus-hpgl" --fit yes --estimate "out/$s.meta" > "out/$s.hpgl.estimate" 2> /dev/null
		# lines only: the raster under the contours left out, as a pen plotter plate is usually drawn
		"$BIN/locus-hpgl" --fit yes --raster skip "out/$s.meta" -o "out/$s.lines.hpgl" 2> /dev/null
		sed -n 's/^locus-hpgl: \(page [0-9]*\) ([a-z0-9]*): \(.*\), box.*/demo: hpgl: '"$s"' \1: \2/p' "out/$s.hpgl.stats"
		sed 's/^/demo: hpgl: '"$s"' /' "out/$s.hpgl.estimate" | grep total
		command -v hp2xx > /dev/null 2>&1 || continue
		# one file per page: out/NAME.hpgl, or out/NAME-001.hpgl ... for several pages
		for f in "out/$s.hpgl" "out/$s"-[0-9][0-9][0-9].hpgl "out/$s.lines.hpgl" "out/$s.lines"-[0-9][0-9][0-9].hpgl; do
			[ -f "$f" ] || continue
			hp2xx -q -m png -c 12345671 -d 100 -f "${f%.hpgl}.hpgl.png" "$f" &&
				echo "demo: hpgl: hp2xx's picture of $f: ${f%.hpgl}.hpgl.png (locus-raster's: out/$s.raster*.png)"
		done
	done
}
hpgl_demo

# ps.sh: make demo, PostScript and PDF (sourced by scripts/demo.sh: $BIN set, out/default.meta
# exists): the default scene and the contour plate as EPS and PDF, and Ghostscript's renderings
# of them beside locus-raster's pictures, to look at.
if [ -x "$BIN/locus-ps" ]; then
	"$BIN/locus-ps" out/default.meta -o out/default.eps
	"$BIN/locus-ps" out/default.meta -o out/default.pdf
	if [ -x "$BIN/locus-render" ]; then
		"$BIN/locus-render" --quiet fixtures/scenes/contour-sum.scene -o out/contour-sum.meta
	else
		cp fixtures/render/sum-contour.meta out/contour-sum.meta
	fi
	"$BIN/locus-raster" out/contour-sum.meta -o out/contour-sum.png
	"$BIN/locus-ps" out/contour-sum.meta -o out/contour-sum.eps
	"$BIN/locus-ps" out/contour-sum.meta -o out/contour-sum.pdf
	for f in default contour-sum; do
		if command -v gs > /dev/null; then
			gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -dEPSCrop -sOutputFile="out/$f.eps.gs.png" "out/$f.eps"
			gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -sOutputFile="out/$f.pdf.gs.png" "out/$f.pdf"
			ref=out/$f.png
			[ $f = default ] && ref=out/default.png.png
			# and with Ghostscript's centre-of-pixel rule, the meta-language's (docs/postscript.md)
			gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -sOutputFile="out/$f.pdf.gs-centre.png" \
				-c "0 0 .setfilladjust2" -f "out/$f.pdf"
			echo "demo: ps: out/$f.eps ($(wc -c < "out/$f.eps") bytes), out/$f.pdf ($(wc -c < "out/$f.pdf") bytes);" \
				"Ghostscript's renderings out/$f.eps.gs.png, out/$f.pdf.gs.png against $ref:" \
				"$("$BIN/locus-diff" "$ref" "out/$f.pdf.gs.png" 2>&1 | sed 's/.*: //');" \
				"with the centre rule: $("$BIN/locus-diff" "$ref" "out/$f.pdf.gs-centre.png" 2>&1 | sed 's/.*: //')"
		else
			echo "demo: ps: out/$f.eps, out/$f.pdf (no gs to render them)"
		fi
	done
fi

# film.sh: demo outputs of locus-film (sourced by scripts/demo.sh: $BIN set, out/default.meta
# there): the default scene as a 4096x2730 slide in DPX (demo.sh's loop already wrote it through
# locus-play -d film as out/default.film.dpx; locus-film writes the same bytes), converted back
# to PNG to look at.
if [ -x "$BIN/locus-film" ]; then
	"$BIN/locus-film" out/default.meta -o out/default.film.dpx
	echo "demo: locus-film -> out/default.film.dpx (4096x2730 slide, DPX 10-bit printing density)"
	if command -v oiiotool > /dev/null 2>&1; then
		oiiotool --info out/default.film.dpx | sed 's/^/demo: oiiotool reads /'
	fi
	if command -v convert > /dev/null 2>&1; then
		# ImageMagick decodes the printing-density codes to sRGB; a quarter size to look at
		convert out/default.film.dpx -resize 25% out/default.film.png &&
			echo "demo: film -> out/default.film.png (ImageMagick's decoding, 1024x683)"
	fi
fi

# film.sh: demo outputs of locus-film (sourced by scripts/demo.sh: $BIN set, out/default.meta
# there): the default scene as a 4096x2730 slide in DPX. demo.sh's loop already wrote it through
# locus-play -d film as out/default.film.dpx; locus-film must write the same bytes. The frame is
# read back by Locus's own DPX reader (locus-diff, drivers/rd-film.c), not by an outside tool the
# demo did not install: a DPX that reads whole and equals itself pixel for pixel.
if [ -x "$BIN/locus-film" ]; then
	"$BIN/locus-film" out/default.meta -o out/default.film.direct.dpx
	if cmp -s out/default.film.dpx out/default.film.direct.dpx; then
		same="the same bytes as locus-play -d film"
	else
		same="DIFFERS from locus-play -d film's out/default.film.dpx"
	fi
	mv out/default.film.direct.dpx out/default.film.dpx
	echo "demo: locus-film -> out/default.film.dpx (4096x2730 slide, DPX 10-bit printing density; $same)"
	if r=$("$BIN/locus-diff" out/default.film.dpx out/default.film.dpx 2>&1); then
		echo "demo: film: Locus's DPX reader reads it back: ${r#* * }"
	else
		echo "demo: film: Locus's DPX reader cannot read out/default.film.dpx: $r"
	fi
fi

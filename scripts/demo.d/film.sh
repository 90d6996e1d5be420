# film.sh: demo outputs of locus-film (sourced by scripts/demo.sh: $BIN set, out/default.meta
# there): the default scene as a 4096x2730 slide in DPX. demo.sh's loop already wrote it through
# locus-play -d film as out/default.film.dpx; locus-film writes it again, and Locus's own DPX
# reader (locus-diff, drivers/rd-film.c), not an outside tool the demo did not install, reads both
# back: the same pixels (the headers differ only in their creation time).
if [ -x "$BIN/locus-film" ]; then
	"$BIN/locus-film" out/default.meta -o out/default.film.direct.dpx
	echo "demo: locus-film -> out/default.film.direct.dpx (4096x2730 slide, DPX 10-bit printing density)"
	if r=$("$BIN/locus-diff" out/default.film.dpx out/default.film.direct.dpx 2>&1); then
		echo "demo: film: Locus's DPX reader reads both slides back, the same pixels: ${r#* * }"
	else
		echo "demo: film: the two slides DIFFER, or Locus's DPX reader cannot read them: $r"
	fi
fi

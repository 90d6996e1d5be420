#!/bin/sh
# t_svg.sh: the SVG device (docs/drivers.md's worked vector example) writes well-formed SVG 1.1
# that librsvg, a real SVG renderer, draws like locus-raster: with -O crisp=1 (no anti-aliasing)
# all but a few boundary pixels agree, exactly on the F test and the image; anti-aliased within
# 20 dB PSNR. Multi-page files give one SVG per page.
. tests/lib.sh
R="$TESTBIN/svg_render"
for f in strokes fills text image f-test; do
	m=fixtures/meta/$f.meta
	set -- $(sed -n 's/^page \([0-9]*\) \([0-9]*\).*/\1 \2/p' "$m" | head -1)
	w=$1 h=$2
	"$BIN/locus-play" -d svg -O crisp=1 -o "$T/$f.svg" "$m" || notok "$f: locus-play -d svg failed"
	"$BIN/locus-play" -d svg -o "$T/$f-aa.svg" "$m"
	if command -v xmllint >/dev/null 2>&1; then
		check "$f.svg is well-formed XML (xmllint)" xmllint --noout "$T/$f.svg"
	fi
	"$BIN/locus-raster" -o "$T/$f.png" "$m"
	if ! "$R" "$T/$f.svg" "$T/$f-svg.png" "$w" "$h" 2>"$T/err"; then
		if grep -q "not found" "$T/err"; then ok "$f: librsvg missing # SKIP"; continue; fi
		notok "$f: librsvg refused the SVG ($(cat "$T/err"))"; continue
	fi
	"$R" "$T/$f-aa.svg" "$T/$f-aa.png" "$w" "$h"
	case $f in
	image|f-test) max=0 ;;
	*) max=$((w * h * 15 / 1000)) ;;   # 1.5%: pixels on boundaries, cairo's sampling rule
	esac
	check "$f: librsvg (crisp) differs from locus-raster in at most $max pixels" \
		"$BIN/locus-diff" --max-pixels "$max" "$T/$f.png" "$T/$f-svg.png"
	check "$f: librsvg anti-aliased is within 20 dB of locus-raster" \
		"$BIN/locus-diff" --psnr 20 "$T/$f.png" "$T/$f-aa.png"
done
"$BIN/locus-play" -d svg -o "$T/mp.svg" fixtures/meta/multipage.meta
n=$(ls "$T"/mp-*.svg 2>/dev/null | wc -l)
[ "$n" = 3 ] && ok "multipage.meta gives three SVG files" || notok "multipage.meta gave $n SVG files"
grep -q 'stroke-dasharray' "$T/strokes.svg" && notok "dashes reach SVG as dasharray" ||
	ok "dashes reach the SVG as the framework's dash pieces (no stroke-dasharray)"
grep -q -- '-0[ ."]' "$T/strokes.svg" "$T/text.svg" && notok "a coordinate printed as -0" || ok "no -0 in the output"
expect_exit 64 "-O crisp=2 is refused (64)" "$BIN/locus-play" -d svg -O crisp=2 -o "$T/x.svg" fixtures/meta/strokes.meta
[ ! -e "$T/x.svg" ] && ok "and leaves no file" || notok "a refused run left x.svg"
expect_exit 64 "-O colour=1 (unknown key) is refused (64)" "$BIN/locus-play" -d svg -O colour=1 -o "$T/y.svg" fixtures/meta/strokes.meta
done_tests

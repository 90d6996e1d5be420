#!/bin/sh
# import_agree.sh BIN RESVG_DIR OUTDIR: each resvg case imported by locus-meta and drawn by
# locus-raster, and drawn by rsvg-convert, both at the reference's size (500 px wide), then all
# three scaled the same way to the meta page's size (200 px), blurred by 1 px and compared with
# ImageMagick: a picture agrees when at most 0.5 % of its pixels differ by more than 15 %.
# Prints "CASE CATEGORY LOCUS_AGREES RSVG_AGREES plain|other" per case (plain: geometry and
# solid paint only, no gradient, pattern, filter, mask, clip path, image, text or outside file).
BIN=$1; R=$2; D=$3
mkdir -p "$D"
measure() {   # measure A B SIZE: pixels that differ
	convert "$1" -resize "$3!" -blur 0x1 "$D/1.png" && convert "$2" -resize "$3!" -blur 0x1 "$D/2.png" &&
		compare -metric AE -fuzz 15% "$D/1.png" "$D/2.png" null: 2>&1 | cut -d' ' -f1
}
for f in $(find "$R" -name '*.svg' | sort); do
	rel=${f#"$R"/}; cat=${rel%%/*}; b=$(echo "${rel%.svg}" | tr / _)
	ref=${f%.svg}.png
	kind=plain
	grep -Eq 'Gradient|pattern|filter|mask|clip|<image|<text|tspan|marker|@import|ENTITY|href="[^#]|icc-color' "$f" && kind=other
	l=0; r=0
	convert "$ref" -background white -alpha remove -alpha off "$D/ref.png" 2> /dev/null
	rw=$(identify -format '%w' "$D/ref.png")
	if "$BIN/locus-meta" import "$f" -o "$D/$b.meta" 2> /dev/null; then
		sz=$(sed -n 's/^page \([0-9]*\) \([0-9]*\)$/\1x\2/p' "$D/$b.meta")
		dpi=$(awk -v a="$rw" -v b="${sz%x*}" 'BEGIN { printf "%.6f", 96 * a / b }')
		if "$BIN/locus-meta" import --dpi "$dpi" "$f" -o "$D/big.meta" 2> /dev/null &&
				"$BIN/locus-raster" -o "$D/$b.locus.png" "$D/big.meta" 2> /dev/null; then
			bw=$(identify -format '%wx%h' "$D/$b.locus.png")
			px=$(( ${sz%x*} * ${sz#*x} ))
			d=$(measure "$D/$b.locus.png" "$D/ref.png" "$sz")
			[ -n "$d" ] && [ "$d" -le $((px / 200)) ] 2> /dev/null && l=1
			if rsvg-convert -w "${bw%x*}" -h "${bw#*x}" -b white "$f" -o "$D/$b.rsvg.png" 2> /dev/null; then
				d=$(measure "$D/$b.rsvg.png" "$D/ref.png" "$sz")
				[ -n "$d" ] && [ "$d" -le $((px / 200)) ] 2> /dev/null && r=1
			fi
		fi
	fi
	echo "$b $cat $l $r $kind"
done

#!/bin/sh
# demo.sh: render the bundled default scene into out/default.meta and replay it
# through every driver that locus-play lists, one output file per driver.
set -eu
: "${BIN:=bin}"
mkdir -p out
if [ -x "$BIN/locus-render" ] && [ -f fixtures/scenes/default.scene ]; then
	echo "demo: rendering fixtures/scenes/default.scene"
	"$BIN/locus-render" fixtures/scenes/default.scene -o out/default.meta
else
	echo "demo: no renderer yet; using the bundled fixtures/meta/f-test.meta"
	cp fixtures/meta/f-test.meta out/default.meta
fi
"$BIN/locus-meta" info out/default.meta > out/default.info
"$BIN/locus-play" -l | while read -r dev ext rest; do
	[ -n "$dev" ] || continue
	if [ "$ext" = - ]; then
		"$BIN/locus-play" -d "$dev" out/default.meta
		echo "demo: $dev: replayed, writes nothing ($rest)"
		continue
	fi
	"$BIN/locus-play" -d "$dev" out/default.meta -o "out/default.$dev.$ext"
	# every raster output at the model's size must hold the same pixels as the reference PNG;
	# the other devices (vector files, rasters of their own size) are checked by their own
	# demo lines below and by their tests
	case $dev in
	png|ppm|rle)
		if [ "$dev" = png ]; then
			same="the reference"
		elif "$BIN/locus-diff" out/default.png.png "out/default.$dev.$ext" > /dev/null 2>&1; then
			same="same pixels as the PNG"
		else
			same="DIFFERS from the PNG (see locus-diff)"
		fi ;;
	*) same="written" ;;
	esac
	echo "demo: $dev -> out/default.$dev.$ext ($same)"
done
# Each driver adds its own demo outputs in scripts/demo.d/NAME.sh (sourced: $BIN is set and
# out/default.meta exists).
for f in scripts/demo.d/*.sh; do
	[ -f "$f" ] && . "./$f"
done
echo "demo: done; pictures are in out/"
ls -l out

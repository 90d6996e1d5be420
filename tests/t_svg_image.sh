#!/bin/sh
# t_svg_image.sh: the SVG device writes image rows as embedded PNG <image>s (docs/svg.md, issue
# 22 item 5), so raster-heavy and dash-heavy files give small SVG that real readers draw pixel
# for pixel like locus-raster:
#  - the default scene (one 640x480 image): at most 100 KB (measured 47,805 bytes; one <rect> a
#    run made 2,220,257), one <image>, and rsvg-convert's picture equals locus-raster's PNG;
#  - fixtures/dash/long.meta: at most 4 KB (measured 1,483);
#  - an image of incompressible pixels taller than a strip (4 MiB of samples) is cut into
#    strips of whole rows, each attribute under libxml2's 10 MB limit (xmllint reads the file
#    without --huge), and rsvg-convert draws it exactly; a 4000x3000 image takes at most 32 MB
#    of memory (one strip, not the 36 MB image);
#  - the image fixture (images, spans and a clear in paint order) exactly in rsvg-convert, and
#    where Chromium is installed, exactly also at 4x zoom (image-rendering pixelated keeps
#    each sample a square).
. tests/lib.sh
P="$BIN/locus-play"
have_rsvg=0
command -v rsvg-convert >/dev/null 2>&1 && have_rsvg=1
[ "$have_rsvg" = 1 ] || skip "rsvg-convert missing (Debian librsvg2-bin): no pictures compared"
# same_picture DESC META SVG: rsvg-convert's picture of SVG equals locus-raster's of META
same_picture() {
	[ "$have_rsvg" = 1 ] || return 0
	"$BIN/locus-raster" -o "$T/ref.png" "$2"
	if ! bounded 60 "$1" rsvg-convert "$3" -o "$T/rsvg.png" 2> "$T/err"; then
		notok "$1: rsvg-convert refused $3: $(head -1 "$T/err")"
		return
	fi
	check "$1" "$BIN/locus-diff" --max-pixels 0 "$T/ref.png" "$T/rsvg.png"
}

# the default scene
"$BIN/locus-render" fixtures/scenes/default.scene -o "$T/default.meta" || notok "locus-render default.scene failed"
"$P" -d svg -o "$T/default.svg" "$T/default.meta" || notok "locus-play -d svg on the default scene failed"
n=$(wc -c < "$T/default.svg")
[ "$n" -le 100000 ] && ok "default scene's SVG is $n bytes (at most 100 KB)" || notok "default scene's SVG is $n bytes (over 100 KB)"
i=$(grep -c '<image ' "$T/default.svg"); r=$(grep -c '<rect ' "$T/default.svg")
[ "$i" = 1 ] && [ "$r" = 1 ] && ok "its image is one <image> (and the page one <rect>)" ||
	notok "default scene's SVG has $i <image> and $r <rect>"
grep -q 'image-rendering:pixelated' "$T/default.svg" && grep -q 'image-rendering="optimizeSpeed"' "$T/default.svg" &&
	ok "the <image> asks for pixelated (CSS) and optimizeSpeed (SVG 1.1)" || notok "no image-rendering on the <image>"
check "default scene's SVG is well-formed (xmllint)" xmllint --noout "$T/default.svg"
same_picture "rsvg-convert draws the default scene's SVG exactly like locus-raster" "$T/default.meta" "$T/default.svg"

# dash-heavy
"$P" -d svg -o "$T/long.svg" fixtures/dash/long.meta || notok "locus-play -d svg on long.meta failed"
n=$(wc -c < "$T/long.svg")
[ "$n" -le 4096 ] && ok "long.meta's SVG is $n bytes (at most 4 KB)" || notok "long.meta's SVG is $n bytes (over 4 KB)"

# strips: 1400x1000 pseudo-random samples are 4.2 MB, one row over a strip
python3 - "$T/noise.meta" <<'PY'
import sys, random
random.seed(22)
w, h = 1400, 1000
with open(sys.argv[1], 'w') as f:
    f.write('LOCUS-META 1\npage %d %d\nimage 0 0 %d %d\n' % (w, h, w, h))
    for y in range(h):
        f.write('row ' + ' '.join('1 #%06x' % random.getrandbits(24) for _ in range(w)) + '\n')
    f.write('end-page\n')
PY
"$P" -d svg -o "$T/noise.svg" "$T/noise.meta" || notok "locus-play -d svg on the noise image failed"
set -- $(grep -o '<image [^>]*height="[0-9]*"' "$T/noise.svg" | sed 's/.*height="\([0-9]*\)"/\1/')
[ "$*" = "998 2" ] && ok "a 4.2 MB image is two strips of whole rows (998 + 2)" || notok "noise strips: '$*'"
big=$(awk '{ if (length($0) > m) m = length($0) } END { print m }' "$T/noise.svg")
[ "$big" -lt 10000000 ] && ok "its longest line (one <image>) is $big bytes, under libxml2's 10 MB" ||
	notok "an <image> line of $big bytes"
check "xmllint reads the strips without --huge" xmllint --noout "$T/noise.svg"
same_picture "rsvg-convert draws the strips exactly like locus-raster" "$T/noise.meta" "$T/noise.svg"

# memory: one strip, not the image
if [ "${SANITIZE:-}" != 1 ] && [ -x /usr/bin/time ]; then
	awk 'BEGIN { print "LOCUS-META 1"; print "page 4000 3000"; print "image 0 0 4000 3000"
		for (y = 0; y < 3000; y++) printf "row 1000 #%06x 3000 #%06x\n", (y * 2654435761) % 16777216, (y * 40503) % 16777216
		print "end-page" }' > "$T/tall.meta"
	/usr/bin/time -f %M -o "$T/rss" "$P" -d svg -o "$T/tall.svg" "$T/tall.meta" 2> "$T/err" ||
		notok "locus-play -d svg on 4000x3000 failed: $(head -1 "$T/err")"
	kb=$(tail -1 "$T/rss")
	[ "$kb" -le 32768 ] && ok "a 4000x3000 image (36 MB of samples) takes $kb KB (at most 32 MB)" ||
		notok "a 4000x3000 image took $kb KB"
	same_picture "rsvg-convert draws the 4000x3000 image's 9 strips exactly" "$T/tall.meta" "$T/tall.svg"
else
	skip "memory bound: needs /usr/bin/time and no sanitizer"
fi

# paint order and clipping: images, spans, clear
"$P" -d svg -o "$T/image.svg" fixtures/meta/image.meta
same_picture "rsvg-convert draws image.meta's SVG exactly like locus-raster" fixtures/meta/image.meta "$T/image.svg"
C=$(command -v chromium || command -v chromium-browser || true)
if [ -n "$C" ] && command -v convert >/dev/null 2>&1 && convert -version 2>/dev/null | grep -q ImageMagick; then
	"$BIN/locus-raster" -o "$T/img1.png" fixtures/meta/image.meta
	convert "$T/img1.png" -scale 400% "$T/img4.png"
	for z in 1 4; do
		w=$((64 * z))
		bounded 60 "chromium at ${z}x" "$C" --headless --no-sandbox --disable-gpu --hide-scrollbars \
			--force-device-scale-factor=$z --window-size=64,64 --screenshot="$T/c$z.png" \
			"file://$(cd "$T" && pwd)/image.svg" > /dev/null 2>&1
		[ "$z" = 1 ] && ref="$T/img1.png" || ref="$T/img4.png"
		check "Chromium draws image.meta's SVG at ${z}x exactly like locus-raster (${w}x$w)" \
			"$BIN/locus-diff" --max-pixels 0 "$ref" "$T/c$z.png"
	done
else
	skip "Chromium (or ImageMagick) not installed: the zoomed pixelated check did not run"
fi
done_tests

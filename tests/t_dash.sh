#!/bin/sh
# t_dash.sh: dashes bounded by what the page can show (spec §5.3, §6): a pattern finer than a
# pixel is drawn solid at once, and a dashed segment millions of pixels long costs only its
# part near the page, in one-row bands as in the whole page.
. tests/lib.sh
D=fixtures/dash
# before the closed-form walk: fine.meta took 27 s whole and long.meta 3.8 s at one row a band
check "dash 0.001 along a 2,000,000-pixel segment renders within 5 s" \
	timeout 5 "$BIN/locus-raster" -o "$T/fine.ppm" "$D/fine.meta"
"$BIN/locus-raster" -o "$T/fine-solid.ppm" "$D/fine-solid.meta"
same_file "a pattern finer than a pixel is the solid line" "$T/fine.ppm" "$T/fine-solid.ppm"
check "the same at one row a band within 5 s" \
	timeout 5 "$BIN/locus-raster" --band-rows 1 -o "$T/fine-1.ppm" "$D/fine.meta"
same_file "fine.meta at one row a band equals the whole page" "$T/fine-1.ppm" "$T/fine.ppm"
check "dash 3 2 along a 2,800,000-pixel segment, one row a band, within 5 s" \
	timeout 5 "$BIN/locus-raster" --band-rows 1 -o "$T/long-1.ppm" "$D/long.meta"
"$BIN/locus-raster" -o "$T/long.ppm" "$D/long.meta"
"$BIN/locus-raster" --band-rows 7 -o "$T/long-7.ppm" "$D/long.meta"
same_file "long.meta: one-row bands equal the whole page" "$T/long-1.ppm" "$T/long.ppm"
same_file "long.meta: 7-row bands equal the whole page" "$T/long-7.ppm" "$T/long.ppm"
"$BIN/locus-raster" -o "$T/long.png" "$D/long.meta"
same_file "long.meta matches its golden (recorded with the walk before the closed form)" \
	"$T/long.png" "$D/long.raster.png"
done_tests

#!/bin/sh
# t_antialias.sh: the framework's anti-aliased mode (-O antialias=K on any raster device):
# edges get partial coverage, pixel-aligned content stays exact, bands agree with the whole
# page, the exact mode stays the default, and bad factors are refused in one line.
. tests/lib.sh
P="$BIN/locus-play"
M=fixtures/meta
"$BIN/locus-raster" -o "$T/exact.png" $M/strokes.meta
"$P" -d png -O antialias=0 -o "$T/zero.png" $M/strokes.meta
same_file "antialias=0 is the exact rendering" "$T/zero.png" "$T/exact.png"
"$P" -d png -O antialias=4 -o "$T/aa.png" $M/strokes.meta
if "$BIN/locus-diff" "$T/exact.png" "$T/aa.png" >/dev/null 2>&1; then notok "antialias=4 changes edge pixels"
else ok "antialias=4 changes edge pixels"; fi
check "antialias=4 stays within 20 dB PSNR of the exact rendering" "$BIN/locus-diff" --psnr 20 "$T/exact.png" "$T/aa.png"
"$P" -d png -O antialias=4 --band-rows 1 -o "$T/aa1.png" $M/strokes.meta
"$P" -d png -O antialias=4 --band-rows 7 -o "$T/aa7.png" $M/strokes.meta
same_file "antialias=4 in bands of 1 sample row equals the whole page" "$T/aa1.png" "$T/aa.png"
same_file "antialias=4 in bands of 7 sample rows equals the whole page" "$T/aa7.png" "$T/aa.png"
"$BIN/locus-raster" -o "$T/img.png" $M/image.meta
"$P" -d png -O antialias=3 -o "$T/img-aa.png" $M/image.meta
check "pixel-aligned images and spans stay exact under antialias=3" "$BIN/locus-diff" "$T/img.png" "$T/img-aa.png"
expect_exit 64 "antialias=17 is refused (64)" "$P" -d png -O antialias=17 -o "$T/bad.png" $M/strokes.meta
expect_exit 64 "antialias=x is refused (64)" "$P" -d png -O antialias=x -o "$T/bad.png" $M/strokes.meta
[ ! -e "$T/bad.png" ] && ok "a refused run leaves no file" || notok "a refused run left bad.png"
msg=$("$P" -d png -O antialias=x -o "$T/bad.png" $M/strokes.meta 2>&1)
case $msg in *"antialias must be"*) ok "one clear line: $msg" ;; *) notok "message: $msg" ;; esac
done_tests

#!/bin/sh
# t_diff.sh: locus-diff compares PNG/PPM/RLE/meta pictures; exit 0 same, 1 differs, 2 trouble (bad, missing).
. tests/lib.sh
D=$BIN/locus-diff
G=fixtures/raster
check "--help" "$D" --help
"$D" --version | grep -q "^locus-diff [0-9]" && ok "--version" || notok "--version"
"$D" $G/f-test.raster.png $G/f-test.raster.ppm > "$T/out"
[ $? = 0 ] && grep -q "0 of 19200 pixels differ, max channel difference 0, PSNR inf dB" "$T/out" && ok "PNG = PPM, report line" || notok "PNG vs PPM: $(cat "$T/out")"
expect_exit 0 "PNG = RLE" "$D" $G/f-test.raster.png $G/f-test.raster.rle
expect_exit 0 "meta file rendered = its golden" "$D" fixtures/meta/f-test.meta $G/f-test.raster.png
expect_exit 0 "page 2 of a meta file = its golden" "$D" --page 2 fixtures/meta/multipage.meta $G/multipage.raster-002.png
expect_exit 2 "no page 4" "$D" --page 4 fixtures/meta/multipage.meta $G/multipage.raster-002.png
# change 3 pixels of the PPM by hand: 3 differ, max difference and PSNR reported
cp $G/f-test.raster.ppm "$T/m.ppm"
printf '\000\000\000\000\000\000\000\000\000' | dd of="$T/m.ppm" bs=1 seek=15 conv=notrunc 2>/dev/null
"$D" $G/f-test.raster.ppm "$T/m.ppm" > "$T/out"
rc=$?
[ $rc = 1 ] && grep -q "3 of 19200 pixels differ, max channel difference 232, PSNR 38.88 dB" "$T/out" && ok "3 changed pixels: exit 1, counted" || notok "changed pixels: exit $rc: $(cat "$T/out")"
expect_exit 0 "--max-pixels 3 accepts them" "$D" --max-pixels 3 $G/f-test.raster.ppm "$T/m.ppm"
expect_exit 1 "--max-pixels 2 does not" "$D" --max-pixels 2 $G/f-test.raster.ppm "$T/m.ppm"
expect_exit 0 "--psnr 38 accepts them" "$D" --psnr 38 $G/f-test.raster.ppm "$T/m.ppm"
expect_exit 1 "--psnr 40 does not" "$D" --psnr 40 $G/f-test.raster.ppm "$T/m.ppm"
expect_exit 0 "--max-diff 232 ignores them" "$D" --max-diff 232 $G/f-test.raster.ppm "$T/m.ppm"
expect_exit 1 "different sizes differ" "$D" $G/f-test.raster.png $G/fills.raster.png
head -c 100 $G/f-test.raster.rle > "$T/t.rle"
"$D" "$T/t.rle" $G/f-test.raster.png 2> "$T/err"
[ $? = 2 ] && grep -q "byte [0-9]*: truncated RLE data" "$T/err" && ok "truncated RLE: 2 with byte offset" || notok "truncated RLE: $(cat "$T/err")"
echo "hello" > "$T/x.txt"
expect_exit 2 "not a picture: 2" "$D" "$T/x.txt" $G/f-test.raster.png
expect_exit 2 "bad meta: 2" "$D" fixtures/bad/bad-colour.meta $G/f-test.raster.png
expect_exit 2 "missing file: 2" "$D" "$T/none.png" $G/f-test.raster.png
expect_exit 2 "one file: 2" "$D" $G/f-test.raster.png
done_tests

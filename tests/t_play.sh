#!/bin/sh
# t_play.sh: locus-play runs any registered device in-process; the raster ones match locus-raster.
. tests/lib.sh
P=$BIN/locus-play
check "--help" "$P" --help
"$P" --version | grep -q "^locus-play [0-9]" && ok "--version" || notok "--version"
"$P" -l > "$T/list"
for d in png:png ppm:ppm rle:rle null:-; do
	grep -q "^${d%:*}  *${d#*:}  *[A-Za-z0-9]" "$T/list" && ok "-l lists ${d%:*}, its suffix and a description" || notok "-l lacks $d"
done
"$P" -d png fixtures/meta/f-test.meta -o "$T/f.png"
same_file "-d png = the locus-raster golden" fixtures/raster/f-test.raster.png "$T/f.png"
"$P" -d ppm -o "$T/f.ppm" < fixtures/meta/f-test.meta
same_file "-d ppm from stdin" fixtures/raster/f-test.raster.ppm "$T/f.ppm"
"$P" -d rle fixtures/meta/f-test.meta > "$T/f.rle"
same_file "-d rle to stdout" fixtures/raster/f-test.raster.rle "$T/f.rle"
"$P" -d png --band-rows 3 fixtures/meta/f-test.meta -o "$T/f3.png"
same_file "-d png --band-rows 3" fixtures/raster/f-test.raster.png "$T/f3.png"
"$P" -d png fixtures/meta/multipage.meta -o "$T/m.png"
ok_pages=1
for k in 001 002 003; do cmp -s "$T/m-$k.png" "fixtures/raster/multipage.raster-$k.png" || ok_pages=0; done
[ $ok_pages = 1 ] && [ ! -f "$T/m.png" ] && ok "multi-page: one file per page, -NNN before the suffix" || notok "multi-page outputs: $(ls "$T")"
expect_exit 0 "-d null renders and discards" "$P" -d null fixtures/meta/strokes.meta
expect_exit 65 "-d null still reports bad input" "$P" -d null fixtures/bad/bad-colour.meta
"$P" -d frob fixtures/meta/f-test.meta 2> "$T/err"
[ $? = 64 ] && grep -q "unknown device 'frob'" "$T/err" && ok "unknown device: exit 64, named" || notok "unknown device: $(cat "$T/err")"
expect_exit 64 "no device: exit 64" "$P" fixtures/meta/f-test.meta
expect_exit 66 "missing input: exit 66" "$P" -d png "$T/none.meta" -o "$T/x.png"
[ ! -f "$T/x.png" ] && ok "no output after a missing input" || notok "output left"
done_tests

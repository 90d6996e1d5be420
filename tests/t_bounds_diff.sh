#!/bin/sh
# t_bounds_diff.sh: locus-diff reads its inputs in memory bounded by a row (a band for meta
# files), whatever their headers promise, and reports a lost report with exit 2 (the trouble status of cmp and diff).
. tests/lib.sh
D=$BIN/locus-diff
# limited CMD...: run under a 300 MB address-space limit (not under ASan, whose shadow memory
# needs terabytes of address space)
limited() { if [ "${SANITIZE:-}" = 1 ]; then "$@"; else (ulimit -v 300000; exec "$@"); fi; }
# headers promising 65536 x 47000 pixels (9.2 GB) followed by a few bytes of data
printf 'LRLE\001\000\001\000\000\000\000\267\230\000\000\000\000' > "$T/huge.rle"
limited "$D" "$T/huge.rle" "$T/huge.rle" 2> "$T/err"
[ $? = 2 ] && grep -q "huge.rle: byte 17: truncated RLE data" "$T/err" && ok "RLE header of 9.2 GB: truncated data found in bounded memory" || notok "huge RLE: $(cat "$T/err")"
printf 'P6\n65536 47000\n255\nabcdef' > "$T/huge.ppm"
limited "$D" "$T/huge.ppm" "$T/huge.ppm" 2> "$T/err"
[ $? = 2 ] && grep -q "huge.ppm: byte 25: truncated PPM pixel data" "$T/err" && ok "PPM header of 9.2 GB: truncated data found in bounded memory" || notok "huge PPM: $(cat "$T/err")"
python3 - "$T/huge.png" <<'PY'
import struct, sys, zlib
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
ihdr = struct.pack('>IIBBBBB', 65536, 47000, 8, 2, 0, 0, 0)
rows = zlib.compress(b'\0' * (1 + 65536 * 3) * 2)
open(sys.argv[1], 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', rows) + chunk(b'IEND', b''))
PY
limited "$D" "$T/huge.png" "$T/huge.png" 2> "$T/err"
[ $? = 2 ] && grep -q "huge.png: byte [0-9]*: bad PNG: " "$T/err" && ! grep -q "too large" "$T/err" && ok "PNG header of 9.2 GB: short data found in bounded memory" || notok "huge PNG: $(cat "$T/err")"
printf 'LRLE\001\000\001\000\001\000\000\000\001' > "$T/wide.rle"
"$D" "$T/wide.rle" "$T/wide.rle" 2> "$T/err"
[ $? = 2 ] && grep -q "wide.rle: byte 5: bad or too large RLE size" "$T/err" && ok "RLE wider than 65536: refused from the header" || notok "wide RLE: $(cat "$T/err")"
# a meta page of 6000 x 6000 (108 MB, above the 64 MiB band budget) against a PPM of the same
# size streamed from /dev/zero on standard input: equal, in bounded memory and without reading on
printf 'LOCUS-META 1\npage 6000 6000\nclear #000000\nend-page\n' > "$T/black.meta"
(printf 'P6 6000 6000 255\n'; cat /dev/zero) | limited timeout 30 "$D" - "$T/black.meta" > "$T/out" 2> "$T/err"
[ $? = 0 ] && grep -q "0 of 36000000 pixels differ" "$T/out" && ok "stdin from /dev/zero streams (PPM header + zeros = black meta page)" || notok "streamed stdin: $(cat "$T/err" "$T/out")"
limited timeout 30 "$D" - fixtures/raster/f-test.raster.png < /dev/zero 2> "$T/err"
[ $? = 2 ] && grep -q "<stdin>: byte 0: not a PNG" "$T/err" && ok "stdin from /dev/zero alone: refused at byte 0" || notok "zero stdin: $(cat "$T/err")"
# two meta files, each replayed by a thread of its own, a band at a time
"$D" --band-rows 7 fixtures/meta/f-test.meta --mem-budget 1 fixtures/raster/f-test.raster.png > "$T/out" && grep -q "0 of 19200 pixels differ" "$T/out" && ok "meta in bands of 7 rows = its golden" || notok "banded meta: $(cat "$T/out")"
"$D" --band-rows 5 "$T/black.meta" "$T/black.meta" > "$T/out" && grep -q "0 of 36000000 pixels differ" "$T/out" && ok "meta = meta, each in bands of 5 rows by a thread of its own" || notok "meta = meta: $(cat "$T/out")"
"$D" --mem-budget 1 fixtures/meta/multipage.meta --page 3 fixtures/raster/multipage.raster-003.png > /dev/null && ok "page 3, banded" || notok "page 3 banded"
# the report through -o: a file written whole, none on failure, one line for a missing directory
"$D" fixtures/raster/f-test.raster.png fixtures/raster/f-test.raster.ppm -o "$T/report.txt"
[ $? = 0 ] && grep -q "0 of 19200 pixels differ" "$T/report.txt" && ok "-o OUT holds the report" || notok "-o OUT"
rm -f "$T/r2.txt"
expect_exit 2 "bad input with -o: 2" "$D" "$T/huge.rle" "$T/huge.rle" -o "$T/r2.txt"
[ ! -e "$T/r2.txt" ] && [ -z "$(ls "$T" | grep '^r2')" ] && ok "bad input with -o: no report file, no temporary" || notok "left: $(ls "$T" | grep '^r2')"
"$D" fixtures/raster/f-test.raster.png fixtures/raster/f-test.raster.ppm -o "$T/no/such/dir/r.txt" 2> "$T/err"
rc=$?
[ $rc = 2 ] && [ "$(wc -l < "$T/err")" = 1 ] && grep -q "no/such/dir/r.txt" "$T/err" && ok "-o into a missing directory: one line naming it, 2" || notok "missing dir: exit $rc: $(cat "$T/err")"
expect_exit 2 "-O refused (no device options)" "$D" -O a=1 fixtures/raster/f-test.raster.png fixtures/raster/f-test.raster.ppm
expect_exit 2 "--max-diff 256 refused" "$D" --max-diff 256 fixtures/raster/f-test.raster.png fixtures/raster/f-test.raster.ppm
expect_exit 2 "standard input twice: 2" "$D" - -
# the report lost to a full disk: one line, exit 74
"$D" fixtures/raster/f-test.raster.png fixtures/raster/f-test.raster.ppm > /dev/full 2> "$T/err"
rc=$?
[ $rc = 2 ] && [ "$(wc -l < "$T/err")" = 1 ] && grep -q "locus-diff: <stdout>: .*No space left on device" "$T/err" && ok "report to /dev/full: one line, 2" || notok "/dev/full: exit $rc: $(cat "$T/err")"
# a meta file truncated after its wanted page is still bad input
head -c -9 fixtures/meta/multipage.meta > "$T/cut.meta"
expect_exit 2 "meta file cut after page 1: 2" "$D" "$T/cut.meta" fixtures/raster/multipage.raster-001.png
done_tests

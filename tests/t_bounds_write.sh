#!/bin/sh
# t_bounds_write.sh: an image write that fails (standard output on a full disk) says which output
# and why (the transport's message with strerror) for PNG, PPM and RLE, small (the failure at the
# final flush) and large (inside libpng's writes), and exits 74.
. tests/lib.sh
python3 -c "
import random
random.seed(1)
print('LOCUS-META 1\npage 300 300\nimage 0 0 300 300')
for y in range(300): print('row ' + ' '.join('1 #%06x' % random.randrange(1 << 24) for x in range(300)))
print('end-page')" > "$T/noise.meta"
for f in png ppm rle; do
	for m in fixtures/meta/f-test.meta "$T/noise.meta"; do
		"$BIN/locus-raster" -f $f "$m" -o - > /dev/full 2> "$T/err"
		rc=$?
		[ $rc = 74 ] && [ "$(wc -l < "$T/err")" = 1 ] && grep -q "stdout.*No space left on device" "$T/err" && ok "$f of $(basename "$m") to a full disk: output and cause named, 74" || notok "$f $(basename "$m"): exit $rc: $(cat "$T/err")"
	done
done
done_tests

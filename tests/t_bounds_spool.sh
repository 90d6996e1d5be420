#!/bin/sh
# t_bounds_spool.sh: a banded page whose spool passes LOCUS_SPOOL_MAX_MB is refused (74), with
# no output file, instead of filling the temporary disk.
. tests/lib.sh
python3 -c "
print('LOCUS-META 1\npage 400 400\nstroke')
for i in range(30000): print('move %d 0\ndraw %d 399' % (i % 400, (i * 7) % 400))
print('end\nend-page')" > "$T/many.meta"
rm -f "$T/many.png"
LOCUS_SPOOL_MAX_MB=1 $BIN/locus-raster --band-rows 10 "$T/many.meta" -o "$T/many.png" 2> "$T/err"
rc=$?
[ $rc = 74 ] && [ ! -e "$T/many.png" ] && [ "$(wc -l < "$T/err")" = 1 ] && ok "spool over 1 MiB: 74, one line, no file" || notok "spool limit: exit $rc: $(cat "$T/err")"
LOCUS_SPOOL_MAX_MB=8 $BIN/locus-raster --band-rows 10 "$T/many.meta" -o "$T/many.png" && \
	$BIN/locus-diff "$T/many.png" "$T/many.meta" > /dev/null && ok "the same page within 8 MiB: drawn as unbanded" || notok "spool within its limit"
# the spool costs the path and a few dozen bytes a stroke (its dash list only as long as it is):
# 30000 two-point strokes (1 MB of text) spool within 4 MiB (they took 11 MiB with a whole dash
# array in every record), and draw the pixels of the unbanded page
python3 -c "
print('LOCUS-META 1\npage 400 400')
for i in range(30000): print('stroke\nmove %d 0\ndraw %d 399\nend' % (i % 400, (i * 7) % 400))
print('end-page')" > "$T/strokes.meta"
LOCUS_SPOOL_MAX_MB=4 $BIN/locus-raster --band-rows 10 "$T/strokes.meta" -o "$T/s.png" && \
	$BIN/locus-diff "$T/s.png" "$T/strokes.meta" > /dev/null && ok "30000 strokes spool within 4 MiB" || notok "30000 strokes over 4 MiB of spool"
done_tests

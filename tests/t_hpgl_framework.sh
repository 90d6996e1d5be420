#!/bin/sh
# t_hpgl_framework.sh: the HP-GL device on the framework (issue 21, item 3). Its dashes are the
# framework's pieces, windowed to the page: fixtures/dash/long.meta (dash 3 2 along a line
# 2.8 million pixels long across a 200-pixel page) gives a small file whose pieces are each a
# dash long (3 px at the page's scale) and all on the paper; -O dash=solid (an instance that
# claims dashes and ignores them) draws the line whole. Fills reach the device's hatch op unless
# fill=native claims them: hatch lines, outlines only, nothing, or FP.
. tests/lib.sh
H=$BIN/locus-hpgl
SEG=$TESTBIN/hpgl-segments
: "${T:?T (a scratch directory) must be set: run through tests/run.sh}"
"$H" fixtures/dash/long.meta -o "$T/long.hpgl" 2> /dev/null
"$SEG" "$T/long.hpgl" > "$T/long.seg"
# the page: 200 px at 96 per inch (52.9 mm) centred on A4's clip limits, 10.583 units a pixel:
# the box --stats prints (4462,2802,6578,4919)
box=$("$H" --stats fixtures/dash/long.meta -o /dev/null 2>&1 | sed -n 's/.* box \([0-9,]*\)$/\1/p')
n=$(wc -l < "$T/long.seg") bytes=$(wc -c < "$T/long.hpgl")
awk -v box="$box" 'BEGIN { split(box, c, ",") }
	{ split($2, a, ","); split($3, b, ","); L = sqrt((b[1] - a[1])^2 + (b[2] - a[2])^2)
	if (L < 31.75 - 1.5 || L > 31.75 + 1.5) bad++
	for (i = 1; i <= 2; i++) { x = i == 1 ? a[1] : b[1]; y = i == 1 ? a[2] : b[2]
		if (x < c[1] || x > c[3] || y < c[2] || y > c[4]) off++ } }
	END { exit !(bad + 0 <= 2 && off + 0 == 0) }' "$T/long.seg" \
	&& [ "$box" = 4462,2802,6578,4919 ] && [ "$n" -gt 40 ] && [ "$bytes" -lt 2000 ] \
	&& ok "long.meta: $n dash pieces in $bytes bytes, each 3 px (31.75 units) long but the two cut by the page, all on the page" \
	|| notok "long.meta: $n pieces, $bytes bytes: $(head -3 "$T/long.seg")"
"$H" -O dash=solid fixtures/dash/long.meta -o "$T/solid.hpgl" 2> /dev/null
"$SEG" "$T/solid.hpgl" > "$T/solid.seg"
# (the line crosses the page from (0, 100) to (100, 200) pixels: 141 px, 1,497 units)
awk '{ split($2, a, ","); split($3, b, ","); L = sqrt((b[1] - a[1])^2 + (b[2] - a[2])^2); if (L < 1450) bad++ }
	END { exit !(NR == 2 && bad + 0 == 0) }' "$T/solid.seg" \
	&& ok "dash=solid: the width-2 line as its two passes, each across the page, undashed" \
	|| notok "dash=solid: $(cat "$T/solid.seg")"
for f in hatch outline none; do
	"$H" --fill $f fixtures/meta/fills.meta -o "$T/f-$f.hpgl" 2> /dev/null
	eval "n_$f=\$(\"\$SEG\" \"\$T/f-$f.hpgl\" | wc -l)"
done
"$H" --profile hpgl2 --fill native fixtures/meta/fills.meta -o "$T/f-native.hpgl" 2> /dev/null
fp=$(grep -o 'FP[01]' "$T/f-native.hpgl" | wc -l)
[ "$n_hatch" -gt "$n_outline" ] && [ "$n_outline" -gt 0 ] && [ "$n_none" = 0 ] && [ "$fp" -gt 0 ] \
	&& ok "fills through the hatch op: hatched $n_hatch segments, outlined $n_outline, none 0; fill=native claims fills: $fp FP" \
	|| notok "fills: hatch $n_hatch outline $n_outline none $n_none FP $fp"
done_tests

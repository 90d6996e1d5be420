#!/bin/sh
# t_meta_spec.sh: the decisions that closed the spec's gaps (issue 6), each shown on a fixture of
# fixtures/spec/ (see fixtures/README.md): delta reference per page, close after close, the
# flattened-points limit, the physical size rule and the UTF-8 rule.
. tests/lib.sh
M=$BIN/locus-meta
S=fixtures/spec
# §3: the delta reference resets at every page: page 2 converted alone ends the two-page binary
"$M" convert $S/delta-pages.meta -o "$T/two.lmb"
same_file "delta-pages.meta converts to its recorded .lmb" "$T/two.lmb" $S/delta-pages.lmb
{ echo 'LOCUS-META 1'; sed -n '/^page/{x;s/^/x/;x;};x;/^xx/{x;p;x;};x' $S/delta-pages.meta; } > "$T/p2.meta"
"$M" convert "$T/p2.meta" -o "$T/p2.lmb"
n=$(($(wc -c < "$T/p2.lmb") - 9))
tail -c "$n" "$T/p2.lmb" > "$T/p2.tail"
tail -c "$n" "$T/two.lmb" > "$T/two.tail"
same_file "page 2's bytes do not depend on page 1 (reference reset at 'page')" "$T/p2.tail" "$T/two.tail"
# §4: close right after close changes nothing (a new subpath would add a round dot)
"$BIN/locus-diff" $S/close-twice.meta $S/close-once.meta > "$T/out"
[ $? = 0 ] && grep -q "0 of 1600 pixels differ" "$T/out" && ok "close after close: the pixels of one close" || notok "close twice: $(cat "$T/out")"
# §6: the flattened-points limit is the reader's: check and the raster device stop at the same
# statement, at once (before: 2^25 points were flattened first)
"$M" check fixtures/bad/flat-points.meta 2> "$T/e1"
rm -f "$T/f.png"
"$BIN/locus-raster" fixtures/bad/flat-points.meta -o "$T/f.png" 2> "$T/e2"
rc=$?
grep -q ":3781:1: expected at most 33554432 points" "$T/e1" && [ $rc = 65 ] && grep -q "3781" "$T/e2" && [ ! -e "$T/f.png" ] && ok "flattened points: refused by the reader at line 3781, 65, no file" || notok "flat points: $rc $(cat "$T/e1" "$T/e2")"
head -n 3780 fixtures/bad/flat-points.meta > "$T/ok.meta"; printf 'end\nend-page\n' >> "$T/ok.meta"
check "3776 circles of radius 10^6 (33553536 points): valid" "$M" check "$T/ok.meta"
# §4 size: pixels stay square, so a PNG's pHYs has one resolution for both axes, read back by
# ImageMagick: 100 x 50 pixels in 100 x 100 mm is 1 mm a pixel, 10 pixels per centimetre
"$BIN/locus-raster" $S/size-aspect.meta -o "$T/sa.png"
res=$(identify -format '%x %y %U' "$T/sa.png" 2>&1)
[ "$res" = "10 10 PixelsPerCentimeter" ] && ok "size of another aspect: square pHYs ($res)" || notok "size-aspect pHYs: '$res'"
res=$(identify -format '%x %y' fixtures/raster/f-test.raster.png 2>&1)
"$BIN/locus-raster" fixtures/meta/f-test.meta -o "$T/f.png"
same_file "a size of the page's own aspect: the golden's bytes (pHYs $res) unchanged" "$T/f.png" fixtures/raster/f-test.raster.png
# §2/§5.5: one UTF-8 rule. The recorded counts are a standard decoder's (Python's), and the font
# draws by them: utf8-text.meta paints the pixels of utf8-glyphs.meta (one replacement per count)
python3 - $S/utf8-cases.txt > "$T/u8" <<'PY'
import sys
bad = 0
for line in open(sys.argv[1]):
    if line.startswith('#'): continue
    h, n = line.split()
    if len(bytes.fromhex(h).decode('utf-8', 'replace')) != int(n): bad += 1
print(bad)
PY
[ "$(cat "$T/u8")" = 0 ] && ok "utf8-cases.txt holds Python's decoder counts" || notok "utf8-cases.txt: $(cat "$T/u8") counts differ from Python's"
"$BIN/locus-diff" $S/utf8-text.meta $S/utf8-glyphs.meta > "$T/out"
[ $? = 0 ] && ok "text: surrogate 3 glyphs, truncated 1, euro 1, overlong 2, stray 1" || notok "UTF-8 glyphs: $(cat "$T/out")"
"$M" fmt $S/utf8-text.meta -o "$T/u8.meta" && grep -qF "text 4 32 10 0 \"a$(printf '\342\202\254')b\"" "$T/u8.meta" && grep -q 'a\\xed\\xa0\\x80b' "$T/u8.meta" && ok "fmt keeps the euro sign raw and escapes the surrogate" || notok "fmt escaping: $(grep text "$T/u8.meta")"
done_tests

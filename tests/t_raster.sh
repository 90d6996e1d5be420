#!/bin/sh
# t_raster.sh: locus-raster goldens (byte for byte), banding, formats, stdin/stdout, bad input.
. tests/lib.sh
R=$BIN/locus-raster
check "--help" "$R" --help
"$R" --version | grep -q "^locus-raster [0-9]" && ok "--version" || notok "--version"

# Every fixture meta file against its recorded golden, whole page and in bands of 7 and 1 rows.
for f in fixtures/meta/*.meta fixtures/raster/inputs/*.meta; do
	[ -f "$f" ] || continue
	c=$(basename "$f" .meta)
	if [ ! -f "fixtures/raster/$c.raster.png" ] && [ ! -f "fixtures/raster/$c.raster-001.png" ]; then
		ok "$c: no golden recorded yet (fixtures/raster/record.sh) # SKIP"
		continue
	fi
	for mode in whole 7 1; do
		rm -rf "$T/g" && mkdir -p "$T/g"
		if [ $mode = whole ]; then "$R" "$f" -o "$T/g/$c.raster.png" 2> "$T/err"
		else "$R" --band-rows $mode "$f" -o "$T/g/$c.raster.png" 2> "$T/err"; fi
		rc=$?
		same=1
		for g in "fixtures/raster/$c.raster.png" fixtures/raster/"$c".raster-[0-9][0-9][0-9].png; do
			[ -f "$g" ] || continue
			cmp -s "$g" "$T/g/$(basename "$g")" || same=0
		done
		n_gold=$(ls fixtures/raster/"$c".raster*.png | wc -l)
		n_out=$(ls "$T/g" | wc -l)
		if [ $rc = 0 ] && [ $same = 1 ] && [ "$n_gold" = "$n_out" ]; then ok "$c ($mode): identical to the golden"
		else notok "$c ($mode): exit $rc, differs from fixtures/raster/$c.raster*.png ($n_out files): $(cat "$T/err")"; fi
	done
	# RLE round trip: write RLE, read it back in locus-diff = identical to the PNG golden
	g=fixtures/raster/$c.raster.png
	[ -f "$g" ] || g=fixtures/raster/$c.raster-001.png
	rm -rf "$T/g" && mkdir -p "$T/g"
	"$R" -f rle "$f" -o "$T/g/x.rle" 2>/dev/null
	x=$T/g/x.rle
	[ -f "$x" ] || x=$T/g/x-001.rle
	if "$BIN/locus-diff" "$x" "$g" > "$T/d" 2>&1; then ok "$c: RLE round trip identical"
	else notok "$c: RLE round trip: $(cat "$T/d")"; fi
done

# Other formats of the asymmetric F, by suffix, by -f, through stdin/stdout, from binary meta.
same_file "f-test PPM golden" fixtures/raster/f-test.raster.ppm "$(cd "$T" && "$OLDPWD/$R" "$OLDPWD/fixtures/meta/f-test.meta" -o f.ppm && echo "$T/f.ppm")"
"$R" -f rle < fixtures/meta/f-test.meta > "$T/f.rle"
same_file "f-test RLE golden (stdin to stdout)" fixtures/raster/f-test.raster.rle "$T/f.rle"
"$R" -f ppm - < fixtures/meta/f-test.meta > "$T/f2.ppm"
same_file "f-test PPM via '-'" fixtures/raster/f-test.raster.ppm "$T/f2.ppm"
"$R" fixtures/meta/f-test.meta > "$T/f.png"
same_file "default format to stdout is PNG" fixtures/raster/f-test.raster.png "$T/f.png"
if "$BIN/locus-meta" convert --binary fixtures/meta/f-test.meta -o "$T/f.lmb" 2>/dev/null; then
	"$R" "$T/f.lmb" -o "$T/fb.png"
	same_file "binary meta renders the same" fixtures/raster/f-test.raster.png "$T/fb.png"
fi
head -c 4 fixtures/raster/f-test.raster.rle | grep -q LRLE && ok "RLE magic" || notok "RLE magic"

# Automatic banding under a small memory budget equals the whole page.
cat > "$T/big.meta" <<'M'
LOCUS-META 1
page 1500 900
clear #e0f0ff
colour #c02000
width 9
join round
stroke
move 10 10
draw 1490 880
draw 1400 20
draw 30 870
end
fill-rule even-odd
colour #2040c0
fill
circle 750 450 400
circle 750 450 200
end
text 100 450 60 20 "BANDS"
end-page
M
"$R" "$T/big.meta" -o "$T/big1.png"
"$R" --mem-budget 1 "$T/big.meta" -o "$T/big2.png"
same_file "--mem-budget 1 (bands of 116 rows, two at a time) equals the whole page" "$T/big1.png" "$T/big2.png"
"$R" --band-rows 64 "$T/big.meta" -o "$T/big3.png"
same_file "--band-rows 64 equals the whole page" "$T/big1.png" "$T/big3.png"

# Bad input: one line naming file and place, exit 65, no output (not even a temporary) left.
n=0
for f in fixtures/bad/*.meta fixtures/bad/*.lmb; do
	[ -f "$f" ] || continue
	n=$((n + 1)); [ $n -gt 12 ] && break
	rm -rf "$T/b" && mkdir -p "$T/b"
	"$R" "$f" -o "$T/b/out.png" 2> "$T/err"
	rc=$?
	lines=$(wc -l < "$T/err")
	left=$(ls "$T/b" | wc -l)
	if [ $rc = 65 ] && [ "$lines" = 1 ] && [ "$left" = 0 ] && grep -q "^fixtures/bad/[^ ]*: " "$T/err"; then
		ok "bad $(basename "$f"): exit 65, one line, no output"
	else
		notok "bad $(basename "$f"): exit $rc, $lines lines, $left files left: $(head -2 "$T/err")"
	fi
done
# a bad second page leaves no first page behind
printf 'LOCUS-META 1\npage 8 8\nend-page\npage 8 8\nwidth x\nend-page\n' > "$T/two.meta"
rm -rf "$T/b" && mkdir -p "$T/b"
expect_exit 65 "error on page 2" "$R" "$T/two.meta" -o "$T/b/p.png"
[ "$(ls "$T/b" | wc -l)" = 0 ] && ok "error on page 2 leaves no page 1" || notok "files left: $(ls "$T/b")"
expect_exit 66 "missing input: exit 66" "$R" "$T/nope.meta" -o "$T/n.png"
expect_exit 64 "unknown option: exit 64" "$R" --frobnicate
expect_exit 64 "unknown format: exit 64" "$R" -f gif fixtures/meta/f-test.meta
expect_exit 64 "bad --band-rows: exit 64" "$R" --band-rows 0 fixtures/meta/f-test.meta
expect_exit 74 "unwritable output: exit 74" "$R" fixtures/meta/f-test.meta -o "$T/no/such/dir/x.png"
# a serial line that is not there: one line saying so, exit 74, nothing written (never a real
# line here: /dev/ttyS0 may be the machine's console)
"$R" fixtures/meta/f-test.meta -o "serial:$T/no-such-tty" 2> "$T/err"
[ $? = 74 ] && [ "$(wc -l < "$T/err")" = 1 ] && grep -q "no-such-tty" "$T/err" && [ ! -e "$T/no-such-tty" ] &&
	ok "serial: an absent line is one clear error" || notok "serial: $(cat "$T/err")"
done_tests

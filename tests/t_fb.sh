#!/bin/sh
# t_fb.sh: locus-vga and locus-xga: dump goldens for every mode on fixtures/meta/*.meta (whole
# page and 7-row bands), the F picture in every mode (flips, channel order, 6-bit DAC), PNG, PCX
# and BMP read back by ImageMagick and netpbm to exactly the dump's colours, palettes, and bad input.
# FB_RECORD=1 records missing goldens into fixtures/fb/ (look at them before committing).
. tests/lib.sh
CHK="python3 tests/fbdev/fbcheck.py"
MODES="13h 12h 1024x768x256 640x480x565"
prog() { case $1 in 13h|12h) echo "$BIN/locus-vga" ;; *) echo "$BIN/locus-xga" ;; esac; }

# ---- goldens: every fixture meta in every mode, byte for byte ------------------------------
for m in fixtures/meta/*.meta; do
	c=$(basename "$m" .meta)
	for mode in $MODES; do
		P=$(prog $mode)
		rm -f "$T"/g.* "$T"/g-* "$T"/g7*
		if ! $P --mode $mode "$m" -o "$T/g.dump"; then
			notok "$c $mode: replay failed"
			continue
		fi
		$P --mode $mode --band-rows 7 "$m" -o "$T/g7.dump" || notok "$c $mode: 7-row bands failed"
		for out in "$T"/g.dump "$T"/g-[0-9][0-9][0-9].dump; do
			[ -f "$out" ] || continue
			sfx=${out#"$T"/g}; sfx=${sfx%.dump}          # "" or -001 ...
			gold="fixtures/fb/$c.$mode$sfx.dump.gz"
			same_file "$c $mode$sfx: 7-row bands give the same bytes" "$out" "$T/g7$sfx.dump"
			if [ ! -f "$gold" ]; then
				if [ "${FB_RECORD:-0}" = 1 ]; then
					gzip -9n < "$out" > "$gold" && ok "$c $mode$sfx: golden recorded"
				else
					notok "$c $mode$sfx: no golden $gold (FB_RECORD=1 records it)"
				fi
				continue
			fi
			gzip -dc "$gold" > "$T/gold.dump"
			same_file "$c $mode$sfx: dump equals $gold" "$out" "$T/gold.dump"
		done
	done
done

# ---- the F picture in every mode, and the picture formats read back ------------------------
F=fixtures/meta/f-test.meta
for mode in $MODES; do
	P=$(prog $mode)
	$P --mode $mode $F -o "$T/f.dump" && $CHK f "$T/f.dump" $mode
	$CHK expect "$T/f.dump" $mode "$T/f.rgb"
	for fmt in png pcx bmp; do
		if ! $P --mode $mode $F -o "$T/f.$fmt"; then
			notok "F $mode $fmt: replay failed"
			continue
		fi
		$CHK header "$T/f.$fmt" $fmt $mode
		convert "$T/f.$fmt" -depth 8 "rgb:$T/f.$fmt.rgb" 2>/dev/null
		same_file "F $mode $fmt: ImageMagick reads exactly the dump's colours" "$T/f.rgb" "$T/f.$fmt.rgb"
		# and netpbm, a second reader: its P6 pixels after the header
		case $fmt in png) np=pngtopnm ;; pcx) np=pcxtoppm ;; bmp) np=bmptopnm ;; esac
		$np "$T/f.$fmt" 2>/dev/null | tail -c "$(wc -c < "$T/f.rgb")" > "$T/f.$fmt.pnm.rgb"
		same_file "F $mode $fmt: netpbm $np reads exactly the dump's colours" "$T/f.rgb" "$T/f.$fmt.pnm.rgb"
	done
done
# 12h PCX is a PCX 16-colour file: four 1-bit planes (plane k = bit k of the index), the 16
# EGA colours in the header. Sixteen bars, one of each EGA colour (every bit of every plane),
# read back by ImageMagick and pcxtoppm to exactly the dump's colours
{ echo "LOCUS-META 1"; echo "page 160 120"; echo "clear #000000"
  k=0; for c in 000000 0000aa 00aa00 00aaaa aa0000 aa00aa aa5500 aaaaaa 555555 5555ff 55ff55 55ffff ff5555 ff55ff ffff55 ffffff; do
	y=$((k * 7)); r=0; while [ $r -lt 7 ]; do echo "span 0 $((y + r)) 160 #$c"; r=$((r + 1)); done; k=$((k + 1)); done
  echo "end-page"; } > "$T/ega16.meta"
$BIN/locus-vga --mode 12h --palette ega --dither none "$T/ega16.meta" -o "$T/ega16.dump"
$BIN/locus-vga --mode 12h --palette ega --dither none "$T/ega16.meta" -o "$T/ega16.pcx"
$CHK expect "$T/ega16.dump" 12h "$T/ega16.rgb"
n=$(od -An -tu1 -v -w3 "$T/ega16.rgb" | sort -u | wc -l)
[ "$n" = 16 ] && ok "12h pcx: the bar picture uses all 16 EGA colours" || notok "12h pcx: the bar picture has $n colours"
convert "$T/ega16.pcx" -depth 8 "rgb:$T/ega16.im.rgb" 2>/dev/null
same_file "12h pcx, 16 colours: ImageMagick reads exactly the dump's colours" "$T/ega16.rgb" "$T/ega16.im.rgb"
pcxtoppm "$T/ega16.pcx" 2>/dev/null | tail -c "$(wc -c < "$T/ega16.rgb")" > "$T/ega16.np.rgb"
same_file "12h pcx, 16 colours: pcxtoppm reads exactly the dump's colours" "$T/ega16.rgb" "$T/ega16.np.rgb"
# the header's 48 palette bytes are the dump's 16 DAC entries at 8 bits
od -An -tu1 -v -j16 -N48 "$T/ega16.pcx" | xargs echo > "$T/ega16.hp"
tail -c 48 "$T/ega16.dump" | od -An -tu1 -v | xargs -n1 | awk '{printf("%s%d", (NR > 1 ? " " : ""), $1 * 4 + int($1 / 16))} END {print ""}' > "$T/ega16.dp"
same_file "12h pcx: the EGA palette in the header (bytes 16-63)" "$T/ega16.dp" "$T/ega16.hp"
# -f wins over the suffix; stdin to stdout
$BIN/locus-vga -f pcx $F -o "$T/fpcx.png" && cmp -s "$T/fpcx.png" "$T/f.pcx" 2>/dev/null || true
$BIN/locus-vga $F -o "$T/f13.pcx"
$BIN/locus-vga -f pcx -o "$T/fpcx.png" $F
same_file "-f pcx beats the .png suffix" "$T/f13.pcx" "$T/fpcx.png"
$BIN/locus-vga -f dump < $F > "$T/stdout.dump"
$BIN/locus-vga $F -o "$T/f13.dump"
same_file "stdin to stdout" "$T/f13.dump" "$T/stdout.dump"
$BIN/locus-play -d vga -O mode=12h,format=dump $F -o "$T/play.dump"
$BIN/locus-vga --mode 12h $F -o "$T/vga12.dump"
same_file "locus-play -d vga -O mode=12h is locus-vga --mode 12h" "$T/vga12.dump" "$T/play.dump"
n=$($BIN/locus-vga --list-modes | grep -c 'colours'); [ "$n" = 2 ] && ok "locus-vga --list-modes: 2 modes" || notok "locus-vga --list-modes: $n modes"
n=$($BIN/locus-xga --list-modes | grep -c 'colours'); [ "$n" = 2 ] && ok "locus-xga --list-modes: 2 modes" || notok "locus-xga --list-modes: $n modes"
check "locus-vga --help" $BIN/locus-vga --help
check "locus-xga --version" $BIN/locus-xga --version

# ---- palettes -----------------------------------------------------------------------------
# 12h with the EGA palette: the 48 palette bytes are the 16 EGA colours
$BIN/locus-vga --mode 12h --palette ega $F -o "$T/ega.dump"
tail -c 48 "$T/ega.dump" | od -An -tu1 | xargs echo > "$T/ega.txt"
echo "0 0 0 0 0 42 0 42 0 0 42 42 42 0 0 42 0 42 42 21 0 42 42 42 21 21 21 21 21 63 21 63 21 21 63 63 63 21 21 63 21 63 63 63 21 63 63 63" > "$T/ega.want"
same_file "--palette ega: the dump ends with the 16 EGA colours" "$T/ega.want" "$T/ega.txt"
# a palette file of #rrggbb lines is used as given (rounded to the DAC)
printf '#000000\n#ff0000\n#00c000\n#0000ff\n#e8e8e8\n#ffff00\n#00ffff\n' > "$T/pal.txt"
$BIN/locus-vga --palette "$T/pal.txt" $F -o "$T/pal.dump"
tail -c 768 "$T/pal.dump" | head -c 21 | od -An -tu1 | xargs echo > "$T/pal.got"
echo "0 0 0 63 0 0 0 47 0 0 0 63 57 57 57 63 63 0 0 63 63" > "$T/pal.want"
same_file "--palette FILE: the DAC holds the file's colours" "$T/pal.want" "$T/pal.got"
# and a 768-byte raw DAC dump taken from a dump is accepted and gives the same picture
tail -c 768 "$T/f13.dump" > "$T/raw.dac"
$BIN/locus-vga --palette "$T/raw.dac" $F -o "$T/raw.dump"
same_file "--palette RAW-DAC of the picture's own palette gives the same dump" "$T/f13.dump" "$T/raw.dump"
# shared: one palette for every page
$BIN/locus-vga --palette shared fixtures/meta/multipage.meta -o "$T/sh.dump"
tail -c 768 "$T/sh-001.dump" > "$T/sh1.pal"; tail -c 768 "$T/sh-003.dump" > "$T/sh3.pal"
same_file "--palette shared: page 3 has page 1's palette" "$T/sh1.pal" "$T/sh3.pal"
# made from every page: page 1's red (63,0,0) and page 3's yellow (63,63,0) are both in it
od -An -tu1 -w3 -v "$T/sh1.pal" | xargs -L1 echo > "$T/sh1.txt"
if grep -qx "63 0 0" "$T/sh1.txt" && grep -qx "63 63 0" "$T/sh1.txt"; then ok "--palette shared: one palette made from all pages"; else notok "--palette shared: one palette made from all pages"; fi
$BIN/locus-vga -f dump --palette shared < fixtures/meta/multipage.meta > "$T/shstd.dump"
cat "$T/sh-001.dump" "$T/sh-002.dump" "$T/sh-003.dump" > "$T/sh-all.dump"
same_file "--palette shared from stdin (spooled for the two passes)" "$T/sh-all.dump" "$T/shstd.dump"
$BIN/locus-play -d vga -O palette=shared,format=dump fixtures/meta/multipage.meta -o "$T/plsh.dump"
tail -c 768 "$T/plsh-001.dump" > "$T/plsh1.pal"; tail -c 768 "$T/plsh-003.dump" > "$T/plsh3.pal"
same_file "locus-play -O palette=shared: the first page's palette for all" "$T/plsh1.pal" "$T/plsh3.pal"
$BIN/locus-vga fixtures/meta/multipage.meta -o "$T/pp.dump"
tail -c 768 "$T/pp-003.dump" > "$T/pp3.pal"
if cmp -s "$T/sh1.pal" "$T/pp3.pal"; then notok "per-page palettes differ from page to page"; else ok "per-page palettes differ from page to page"; fi

# ---- bad input: one line, sysexits status, no partial output ------------------------------
bad() {   # bad STATUS DESC PATTERN CMD... (the output $T/bad.* must not exist afterwards)
	st=$1 d=$2 pat=$3; shift 3
	rm -f "$T"/bad.*
	"$@" 2> "$T/err" > /dev/null; r=$?
	lines=$(wc -l < "$T/err")
	if [ "$r" = "$st" ] && [ "$lines" = 1 ] && grep -q -- "$pat" "$T/err" && ! ls "$T"/bad.* > /dev/null 2>&1; then
		ok "$d"
	else
		notok "$d (exit $r, $lines lines: $(head -c 200 "$T/err"))"
	fi
}
bad 64 "unknown mode" "unknown mode '14h'" $BIN/locus-vga --mode 14h $F -o "$T/bad.png"
bad 64 "unknown XGA mode" "unknown mode '800x600'" $BIN/locus-xga --mode 800x600 $F -o "$T/bad.png"
bad 64 "unknown format" "unknown format 'gif'" $BIN/locus-vga -f gif $F -o "$T/bad.png"
bad 64 "unknown dither" "unknown dither" $BIN/locus-vga --dither blue $F -o "$T/bad.png"
bad 64 "unknown device option" "unknown" $BIN/locus-play -d vga -O colour=1 $F -o "$T/bad.png"
printf '#000000\n#ff00zz\n' > "$T/badpal.txt"
bad 65 "malformed palette file: file:line:col" "badpal.txt:2:1: expected #rrggbb" $BIN/locus-vga --palette "$T/badpal.txt" $F -o "$T/bad.png"
head -c 700 "$T/raw.dac" > "$T/short.dac"
bad 65 "short raw DAC file" "768 bytes" $BIN/locus-vga --palette "$T/short.dac" $F -o "$T/bad.png"
bad 66 "missing palette file" "cannot open palette file" $BIN/locus-vga --palette "$T/none.pal" $F -o "$T/bad.png"
bad 64 "16-colour mode refuses the 256-colour VGA palette" "does not fit" $BIN/locus-vga --mode 12h --palette vga $F -o "$T/bad.png"
bad 64 "direct colour takes no palette" "direct colour" $BIN/locus-xga --mode 640x480 --palette cube $F -o "$T/bad.png"
printf 'LOCUS-META 1\npage 10 10\nclear #ff0000\nspan 1 2\n' > "$T/broken.meta"
bad 65 "bad meta file: named with line" "broken.meta:4" $BIN/locus-vga "$T/broken.meta" -o "$T/bad.pcx"
bad 64 "dac=8 has no dump" "beyond the hardware" $BIN/locus-vga --dac 8 $F -o "$T/bad.dump"
bad 64 "dac wants 6 or 8" "dac wants 6 or 8" $BIN/locus-vga --dac 7 $F -o "$T/bad.png"
bad 74 "an fbdev node that is not a framebuffer" "not a framebuffer" $BIN/locus-vga $F -o fb:/dev/null
bad 74 "a missing fbdev node" "cannot open framebuffer" $BIN/locus-vga $F -o fb:"$T/nofb"
done_tests

#!/bin/sh
# t_film.sh: locus-film: goldens byte for byte, banding, readers (ImageMagick, OpenImageIO),
# decoding back to locus-raster's picture, header fields, memory of a slide8k frame, bad input.
. tests/lib.sh
F=$BIN/locus-film
export SOURCE_DATE_EPOCH=1700000000
FD=fixtures/film
check "--help" "$F" --help
"$F" --version | grep -q "^locus-film [0-9]" && ok "--version" || notok "--version"
"$F" --list-presets > "$T/p"
if [ "$(wc -l < "$T/p")" = 5 ] && grep -q "^slide4k  *4096x2730" "$T/p" && grep -q "^slide8k  *8192x5460" "$T/p" &&
	grep -q "^2k  *2048x1556" "$T/p" && grep -q "^4k  *4096x3112" "$T/p" && grep -q "^6x7  *4096x3300" "$T/p"
then ok "--list-presets: the five presets"; else notok "--list-presets: $(cat "$T/p")"; fi

# u32 FILE OFFSET [le]: a 32-bit number of a header
u32() { od -An -tu1 -j"$2" -N4 "$1" | awk -v le="${3:-}" '{print le ? $1 + 256 * ($2 + 256 * ($3 + 256 * $4)) : $4 + 256 * ($3 + 256 * ($2 + 256 * $1))}'; }

# ---- goldens: the cases of fixtures/film/record.sh, whole frame and in bands of 1 and 7 rows
S="--size 66x44"
gold() {   # gold NAME ARGS...: write into $T/g/NAME and compare with fixtures/film/NAME
	g_n=$1; shift
	for mode in whole 7 1; do
		rm -rf "$T/g" && mkdir -p "$T/g"
		if [ $mode = whole ]; then "$F" $S "$@" -o "$T/g/$g_n" 2> "$T/err"
		else "$F" $S --band-rows $mode "$@" -o "$T/g/$g_n" 2> "$T/err"; fi
		rc=$?
		same=1 n=0
		for o in "$T"/g/*; do
			n=$((n + 1))
			cmp -s "$o" "$FD/$(basename "$o")" || same=0
		done
		if [ $rc = 0 ] && [ $same = 1 ] && [ $n -ge 1 ]; then ok "golden $g_n ($mode, $n file(s))"
		else notok "golden $g_n ($mode): exit $rc, $n file(s), differs from $FD: $(cat "$T/err")"; fi
		[ "${SANITIZE:-}" = 1 ] && break   # bands are covered natively; keep the sanitizer run short
	done
}
gold f-test.film.dpx fixtures/meta/f-test.meta
gold f-test.film.le.dpx fixtures/meta/f-test.meta --endian little
gold f-test.film.dpx16.dpx fixtures/meta/f-test.meta -f dpx16
gold f-test.film.cin fixtures/meta/f-test.meta
gold f-test.film.rle fixtures/meta/f-test.meta
gold f-test.film.sep.dpx fixtures/meta/f-test.meta --separations
gold f-test.film.planar.dpx fixtures/meta/f-test.meta --separations=planar
gold f-test.film.cal.dpx fixtures/meta/f-test.meta --calibration $FD/recorder.cal
gold f-test.film.params.dpx fixtures/meta/f-test.meta --letterbox '#3050a0' --white 700 --black 80
gold multipage.film.dpx fixtures/meta/multipage.meta
[ -f "$T/g/multipage.film-003.dpx" ] && [ ! -f "$T/g/multipage.film.dpx" ] && ok "three pages: three numbered frames" ||
	notok "three pages: $(ls "$T/g")"

# the same jobs through locus-play, stdin and stdout
"$BIN/locus-play" -d film -O size=66x44,format=cineon fixtures/meta/f-test.meta -o "$T/p.cin" 2>/dev/null
same_file "locus-play -d film -O format=cineon: the Cineon golden" "$T/p.cin" $FD/f-test.film.cin
"$F" $S -f dpx16 < fixtures/meta/f-test.meta > "$T/s.dpx" 2>/dev/null
same_file "stdin to stdout, -f dpx16" "$T/s.dpx" $FD/f-test.film.dpx16.dpx
"$BIN/locus-meta" convert fixtures/meta/f-test.meta -o "$T/f.lmb" && "$F" $S "$T/f.lmb" -o "$T/b.dpx" 2>/dev/null
same_file "binary meta input: the same frame" "$T/b.dpx" $FD/f-test.film.dpx
"$F" $S -O format=dpx16 fixtures/meta/f-test.meta -o "$T/o.dpx" 2>/dev/null
same_file "-O format=dpx16 wins over the .dpx suffix" "$T/o.dpx" $FD/f-test.film.dpx16.dpx
"$BIN/locus-play" -d film -O size=66x44 fixtures/meta/f-test.meta -o "$T/p.cin" 2>/dev/null
same_file "locus-play: format from the .cin suffix" "$T/p.cin" $FD/f-test.film.cin
[ "$(u32 $FD/f-test.film.rle 5)" = 66 ] && ok "RLE frame is 66 wide (film size, not the page's 160)" ||
	notok "RLE width $(u32 $FD/f-test.film.rle 5)"

# ---- header fields at the documented offsets (docs/film.md), and the size field is the size
for f in $FD/*.dpx $FD/*.cin; do
	le=; case $f in *.le.dpx) le=1 ;; esac
	sz=$(wc -c < "$f")
	case $f in *.cin) field=20 ;; *) field=16 ;; esac
	if [ "$(u32 "$f" $field $le)" = "$sz" ] && [ "$(u32 "$f" 4 $le)" = 2048 ]; then ok "$(basename "$f"): file size $sz and image offset 2048 in the header"
	else notok "$(basename "$f"): header says size $(u32 "$f" $field $le), offset $(u32 "$f" 4 $le); file has $sz"; fi
done
h=$FD/f-test.film.dpx
if [ "$(head -c 4 $h)" = SDPX ] && [ "$(head -c 4 $FD/f-test.film.le.dpx)" = XPDS ] &&
	[ "$(dd if=$h bs=1 skip=8 count=4 2>/dev/null)" = V2.0 ] && [ "$(u32 $h 772)" = 66 ] && [ "$(u32 $h 776)" = 44 ] &&
	[ "$(od -An -tu1 -j800 -N5 $h | tr -s ' ')" = " 50 1 1 10 0" ] && [ "$(u32 $h 808)" = 2048 ] &&
	[ "$(dd if=$h bs=1 skip=136 count=20 2>/dev/null)" = "2023:11:14:22:13:20Z" ] &&
	dd if=$h bs=1 skip=160 count=100 2>/dev/null | grep -q "^Locus film recorder"
then ok "DPX fields: magic, version, 772/776 size, 800 descriptor 50, 801 transfer 1, 803 depth 10, 804 method A, 808 offset, 136 SOURCE_DATE_EPOCH time, 160 creator"
else notok "DPX header fields (od -tu1 -j768 -N48 $h)"; fi
[ "$(od -An -tu1 -j768 -N2 $h | tr -s ' ')" = " 0 0" ] && ok "DPX orientation 0 (left to right, top to bottom)" || notok "orientation"
SOURCE_DATE_EPOCH=1 "$F" $S fixtures/meta/f-test.meta -o "$T/t.dpx"
[ "$(dd if="$T/t.dpx" bs=1 skip=136 count=20 2>/dev/null)" = "1970:01:01:00:00:01Z" ] && ok "time stamp follows SOURCE_DATE_EPOCH" ||
	notok "time stamp: $(dd if="$T/t.dpx" bs=1 skip=136 count=20 2>/dev/null)"
"$F" fixtures/meta/f-test.meta 2>/dev/null | head -c 2048 > "$T/h"
[ "$(u32 "$T/h" 772)" = 4096 ] && [ "$(u32 "$T/h" 776)" = 2730 ] && ok "default frame: slide4k 4096x2730" ||
	notok "default frame $(u32 "$T/h" 772)x$(u32 "$T/h" 776)"
for p in "2k 2048 1556" "4k 4096 3112" "6x7 4096 3300"; do
	set -- $p
	"$F" --preset "$1" fixtures/meta/f-test.meta 2>/dev/null | head -c 2048 > "$T/h"
	[ "$(u32 "$T/h" 772)" = "$2" ] && [ "$(u32 "$T/h" 776)" = "$3" ] && ok "preset $1: $2x$3" || notok "preset $1"
done

# ---- other programs read every output: size, depth, descriptor, byte order
im() {   # im FILE WANT...: identify -verbose holds every WANT line
	identify -verbose "$1" > "$T/iv" 2>&1
	i_f=$1; shift
	for w in "$@"; do grep -q "^ *$w" "$T/iv" || { notok "ImageMagick $(basename "$i_f"): no '$w' ($(grep -m1 -i error "$T/iv"))"; return; }; done
	ok "ImageMagick reads $(basename "$i_f"): $*"
}
im $FD/f-test.film.dpx "Geometry: 66x44+0+0" "Endianness: MSB" "Depth: 10" "Colorspace: Log" "dpx:image.element\[0\].transfer-characteristic: PrintingDensity"
im $FD/f-test.film.le.dpx "Geometry: 66x44+0+0" "Endianness: LSB" "Depth: 10" "Colorspace: Log"
im $FD/f-test.film.dpx16.dpx "Geometry: 66x44+0+0" "Endianness: MSB" "Depth: 16" "dpx:image.element\[0\].transfer-characteristic: Linear"
im $FD/f-test.film.cin "Geometry: 66x44+0+0" "Endianness: MSB" "Depth: 10" "Colorspace: Log"
im $FD/f-test.film.sep-g.dpx "Geometry: 66x44+0+0" "Type: Grayscale" "Depth: 10"
# ImageMagick 6.9 reads only the first element of a planar file, and only without -verbose
identify "$FD/f-test.film.planar.dpx[0]" 2>&1 | grep -q "DPX 66x44 " && ok "ImageMagick reads the first element of the planar file" ||
	notok "ImageMagick planar: $(identify "$FD/f-test.film.planar.dpx[0]" 2>&1)"
oi() {   # oi FILE WANT...: oiiotool --info -v holds every WANT
	oiiotool --info -v "$1" > "$T/ov" 2>&1
	o_f=$1; shift
	for w in "$@"; do grep -q -- "$w" "$T/ov" || { notok "OpenImageIO $(basename "$o_f"): no '$w' ($(head -2 "$T/ov" | tr '\n' ' '))"; return; }; done
	ok "OpenImageIO reads $(basename "$o_f"): $*"
}
oi $FD/f-test.film.dpx "66 x   44, 3 channel, uint10 dpx" 'dpx:ImageDescriptor: "RGB"' 'dpx:Transfer: "Printing density"' 'dpx:Packing: "Filled, method A"' 'DateTime: "2023:11:14 22:13:20"'
oi $FD/f-test.film.le.dpx "66 x   44, 3 channel, uint10 dpx" 'dpx:ImageDescriptor: "RGB"'
oi $FD/f-test.film.dpx16.dpx "66 x   44, 3 channel, uint16 dpx" 'dpx:Transfer: "Linear"'
oi $FD/f-test.film.cin "66 x   44, 3 channel, uint10 cineon" 'cineon:Version: "V4.5"'
oi $FD/f-test.film.sep-b.dpx "66 x   44, 1 channel, uint10 dpx" 'dpx:ImageDescriptor: "Blue"'
oi $FD/f-test.film.planar.dpx "3 subimages" 'dpx:ImageDescriptor: "Red"'
oi $FD/multipage.film-002.dpx "66 x   44, 3 channel" "dpx:FramePosition: 2"

# ---- decoding back to linear = locus-raster's picture (a 66x44 page on a 66x44 frame)
cat > "$T/sq.meta" <<'EOM'
LOCUS-META 1
# every 8-bit level on the green and blue ramps, primaries, black, white
page 66 44
clear #e8e8e8
image 0 0 64 4
EOM
awk 'BEGIN { for (r = 0; r < 4; r++) { s = "row"; for (x = 0; x < 64; x++) { v = r * 64 + x; s = s sprintf(" 1 #%02x%02x%02x", (v * 37) % 256, v, 255 - v) } print s } }' >> "$T/sq.meta"
cat >> "$T/sq.meta" <<'EOM'
colour #ff0000
fill
move 10 8
draw 20 8
draw 20 40
draw 10 40
close
end
colour #00c000
width 5
stroke
move 20 36
draw 50 36
end
span 2 42 60 #000000
span 2 41 60 #ffffff
end-page
EOM
"$BIN/locus-raster" "$T/sq.meta" -o "$T/sq.ppm" 2> "$T/err" || notok "ramp page: $(cat "$T/err")"
dec() {   # dec FILE KIND READER [CHANNELS]
	if python3 tests/film/check.py "${REF:-$T/sq.ppm}" "$@" > "$T/dec" 2>&1; then ok "decoded: $(cat "$T/dec")"
	else notok "decoded: $(cat "$T/dec")"; fi
}
Q="--size 66x44 $T/sq.meta"
"$F" $Q -o "$T/q.dpx" && dec "$T/q.dpx" log oiio && dec "$T/q.dpx" log im
"$F" $Q --endian little -o "$T/ql.dpx" && dec "$T/ql.dpx" log oiio && dec "$T/ql.dpx" log im
"$F" $Q -f dpx16 -o "$T/q16.dpx" && dec "$T/q16.dpx" lin16 oiio && dec "$T/q16.dpx" lin16 im
"$F" $Q --endian little -f dpx16 -o "$T/ql16.dpx" && dec "$T/ql16.dpx" lin16 oiio && dec "$T/ql16.dpx" lin16 im
"$F" $Q -o "$T/q.cin" && dec "$T/q.cin" log oiio && dec "$T/q.cin" log im
"$F" $Q --separations -o "$T/qs.dpx" && for c in r g b; do dec "$T/qs-$c.dpx" log oiio $c; dec "$T/qs-$c.dpx" log im $c; done
"$F" $Q --separations --endian little -o "$T/qsl.dpx" && dec "$T/qsl-g.dpx" log oiio g
"$F" $Q --separations -o "$T/qs.cin" && dec "$T/qs-g.cin" log im g
"$F" $Q --separations=planar -o "$T/qp.dpx" && dec "$T/qp.dpx" log oiio planar
# an odd width: 16-bit rows are not padded, 10-bit RGB rows are whole words anyway
sed 's/^page 66 44/page 65 44/' "$T/sq.meta" > "$T/sq65.meta"
"$BIN/locus-raster" "$T/sq65.meta" -o "$T/sq65.ppm"
"$F" --size 65x44 -f dpx16 "$T/sq65.meta" -o "$T/q65.dpx" && REF=$T/sq65.ppm dec "$T/q65.dpx" lin16 oiio &&
	REF=$T/sq65.ppm dec "$T/q65.dpx" lin16 im
"$F" --size 65x44 "$T/sq65.meta" -o "$T/q65l.dpx" --endian little && REF=$T/sq65.ppm dec "$T/q65l.dpx" log oiio
"$F" $Q -f rle -o "$T/q.rle" && "$BIN/locus-diff" "$T/q.rle" "$T/sq.ppm" > "$T/dd" 2>&1 && ok "RLE frame = locus-raster's picture" ||
	notok "RLE frame: $(cat "$T/dd")"
"$F" $Q --calibration $FD/recorder.cal -o "$T/qc.dpx"
if ! python3 tests/film/check.py "$T/sq.ppm" "$T/qc.dpx" log oiio > "$T/dec" 2>&1; then ok "a calibration curve changes the codes ($(cat "$T/dec"))"
else notok "calibration had no effect"; fi
printf 'locus-film-calibration 1\n0 0 0 0\n1 1 1 1\n' > "$T/id.cal"
"$F" $Q --calibration "$T/id.cal" -o "$T/qi.dpx"
same_file "an identity calibration curve changes nothing" "$T/qi.dpx" "$T/q.dpx"

# ---- thin lines at film size: a 1-pixel model line is drawn at the frame's scale
printf 'LOCUS-META 1\npage 100 75\nclear #ffffff\ncolour #000000\nwidth 1\nstroke\nmove 0 37.5\ndraw 100 37.5\nend\nend-page\n' > "$T/thin.meta"
"$BIN/locus-film" --size 400x300 -f dpx16 "$T/thin.meta" -o "$T/thin.dpx"
dark=$(oiiotool --dumpdata "$T/thin.dpx" | awk '/Pixel \(200, / { if ($4 + 0 < 30000) n++ } END { print n + 0 }')
[ "$dark" -ge 3 ] && [ "$dark" -le 5 ] && ok "a 1-pixel model line at 4x is $dark device rows thick (mapped, not a 1-row line)" ||
	notok "thin line: $dark dark rows in column 200"
# a diagonal at 4x: its top edge climbs one device row per column (scan-converted at the frame's
# pixels), where an upscaled model raster would climb 4 rows every 4 columns
printf 'LOCUS-META 1\npage 100 75\nclear #ffffff\ncolour #000000\nwidth 1\nstroke\nmove 10 10\ndraw 60 60\nend\nend-page\n' > "$T/diag.meta"
"$BIN/locus-film" --size 400x300 -f dpx16 "$T/diag.meta" -o "$T/diag.dpx"
steps=$(oiiotool --dumpdata "$T/diag.dpx" | awk -F'[(), :]+' '/Pixel/ && $5 + 0 < 30000 { if (!($3 in top)) top[$3] = $4 }
	END { for (x = 60; x < 220; x++) { d = top[x] - top[x + 1]; if (d == 1) one++; else if (d > 1) big++ } print one + 0, big + 0 }')
set -- $steps
[ "$1" -ge 150 ] && [ "$2" = 0 ] && ok "a diagonal at 4x climbs one device row per column ($1 of 160 columns)" ||
	notok "diagonal at 4x: $1 one-row steps, $2 bigger ones in 160 columns"

# anti-aliasing is the framework's: --antialias 4 gives edge pixels of partial coverage
grey() { oiiotool --dumpdata "$1" | awk '/Pixel/ { v = $4 + 0; if (v > 3000 && v < 62000) n++ } END { print n + 0 }'; }
"$BIN/locus-film" --size 400x300 -f dpx16 --antialias 4 "$T/diag.meta" -o "$T/diag-aa.dpx"
ge=$(grey "$T/diag.dpx") ga=$(grey "$T/diag-aa.dpx")
[ "$ge" = 0 ] && [ "$ga" -gt 300 ] && ok "--antialias 4: $ga edge pixels of partial coverage (exact: $ge)" ||
	notok "--antialias 4: $ga grey pixels, exact $ge"

# ---- memory: an 8192x5460 frame in bands, peak RSS under 64 MiB
if [ "${SANITIZE:-}" != 1 ] && [ -x /usr/bin/time ]; then
	/usr/bin/time -f %M -o "$T/rss" "$F" --preset slide8k fixtures/meta/f-test.meta -o "$T/big.dpx" 2> "$T/err"
	kib=$(tail -1 "$T/rss")
	sz=$(wc -c < "$T/big.dpx")
	[ "$sz" = $((2048 + 8192 * 5460 * 4)) ] && [ "$kib" -lt 65536 ] && ok "slide8k frame ($sz bytes) with peak RSS $((kib / 1024)) MiB" ||
		notok "slide8k: $sz bytes, peak RSS $kib KiB: $(cat "$T/err")"
	rm -f "$T/big.dpx"
fi

# ---- bad input: one line, the right exit status, no output left behind
bad() {   # bad CODE DESC PATTERN ARGS...
	b_c=$1 b_d=$2 b_p=$3; shift 3
	rm -rf "$T/b" && mkdir -p "$T/b"
	"$F" "$@" > "$T/b.out" 2> "$T/b.err"
	rc=$?
	if [ $rc = "$b_c" ] && [ "$(wc -l < "$T/b.err")" = 1 ] && grep -q -- "$b_p" "$T/b.err" && [ -z "$(ls "$T/b")" ]; then
		ok "$b_d: exit $rc, '$(cat "$T/b.err")'"
	else notok "$b_d: exit $rc (wanted $b_c), files: $(ls "$T/b" | tr '\n' ' '), message: $(cat "$T/b.err")"; fi
}
printf 'locus-film-calibration 1\n0 0 0 0\n0.5 0.6 0.4 x\n1 1 1 1\n' > "$T/bad.cal"
printf 'locus-film-calibration 1\n0 0 0 0\n0.5 0.6 0.4 0.5\n0.7 0.5 0.5 0.5\n1 1 1 1\n' > "$T/dec.cal"
bad 65 "bad meta" "bad-keyword.meta:" $S fixtures/bad/bad-keyword.meta -o "$T/b/x.dpx"
bad 65 "meta truncated inside a page" "truncated" $S fixtures/bad/truncated.meta -o "$T/b/x.dpx"
bad 65 "unterminated page" "unterminated-page.meta" $S fixtures/bad/unterminated-page.meta -o "$T/b/x.dpx"
printf 'LOCUS-META 1\npage 66 44\nclear #ff0000\nend-page\npage 66 44\nclear #00ff00\ncolour #zz0000\nend-page\n' > "$T/set.meta"
bad 65 "a slide set whose second page is bad: no frame at all" "set.meta:7:" $S "$T/set.meta" -o "$T/b/x.dpx"
bad 65 "separations of a bad slide set: no frame at all" "set.meta:7:" $S --separations "$T/set.meta" -o "$T/b/x.dpx"
bad 66 "missing input" "nonexistent" $S "$T/nonexistent.meta" -o "$T/b/x.dpx"
bad 65 "bad number in a calibration file" "bad.cal:3:13: expected a number for blue, found 'x'" $S --calibration "$T/bad.cal" fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 65 "decreasing calibration curve" "dec.cal:4:1: the red correction must not decrease" $S --calibration "$T/dec.cal" fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 66 "missing calibration file" "cannot open calibration file" $S --calibration "$T/none.cal" fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 65 "an image as calibration file" "expected 'locus-film-calibration 1'" $S --calibration fixtures/raster/f-test.raster.ppm fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "size 0x44" "--size needs WxH" --size 0x44 fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "size 40000x10" "--size needs WxH" --size 40000x10 fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "size 64" "--size needs WxH" --size 64 fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "a 16-bit frame over 4 GiB" "a 32768x32768 frame does not fit the 4 GiB a DPX file can hold" --size 32768x32768 -f dpx16 fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "a frame over 4 GiB, format from the suffix" "does not fit the 4 GiB a Cineon file" --size 32768x32768 fixtures/meta/f-test.meta -o "$T/b/x.cin"
bad 64 "unknown format" "unknown format 'tiff'" -f tiff fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "unknown preset" "unknown preset 'imax'" --preset imax fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "bad endian" "endian must be big or little" $S --endian middle fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "little-endian Cineon" "Cineon files are big-endian only" $S --endian little fixtures/meta/f-test.meta -o "$T/b/x.cin"
bad 64 "bad log parameters" "reference black must" $S --black 700 fixtures/meta/f-test.meta -o "$T/b/x.dpx"
bad 64 "separations to stdout" "needs -o OUT" $S --separations fixtures/meta/f-test.meta
bad 64 "planar Cineon" "planar separations are written as DPX only" $S --separations=planar fixtures/meta/f-test.meta -o "$T/b/x.cin"
bad 64 "RLE separations" "not separations" $S -f rle --separations=planar fixtures/meta/f-test.meta -o "$T/b/x.rle"
SOURCE_DATE_EPOCH=yesterday bad 64 "bad SOURCE_DATE_EPOCH" "SOURCE_DATE_EPOCH must be" $S fixtures/meta/f-test.meta -o "$T/b/x.dpx"
"$BIN/locus-play" -d film -O calibration="$T/bad.cal" fixtures/meta/f-test.meta -o "$T/b/x.dpx" 2> "$T/b.err"
rc=$?
[ $rc = 65 ] && [ "$(cat "$T/b.err")" = "$T/bad.cal:3:13: expected a number for blue, found 'x'" ] && [ ! -f "$T/b/x.dpx" ] &&
	ok "locus-play -d film -O calibration=BAD: exit 65, the file's own message" || notok "locus-play bad calibration: exit $rc, $(cat "$T/b.err")"
expect_exit 64 "locus-play -d film -O size=1x" "$BIN/locus-play" -d film -O size=1x fixtures/meta/f-test.meta -o "$T/b/x.dpx"
expect_exit 64 "locus-play -d film -O colour=red (unknown key)" "$BIN/locus-play" -d film -O colour=red fixtures/meta/f-test.meta -o "$T/b/x.dpx"
done_tests

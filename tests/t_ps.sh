#!/bin/sh
# t_ps.sh: locus-ps: every fixture as EPS, PS and PDF rendered by Ghostscript (and pdftoppm)
# against locus-raster's picture, the "F" pixel-exact, DSC, embedding, bbox, goldens, bad input.
. tests/lib.sh
P=$BIN/locus-ps
check "--help" "$P" --help
"$P" --version | grep -q "^locus-ps [0-9]" && ok "--version" || notok "--version"
if ! command -v gs > /dev/null || ! command -v compare > /dev/null; then
	ok "ghostscript or imagemagick missing # SKIP"
	done_tests
fi
GS="gs -q -dSAFER -dBATCH -dNOPAUSE"
# Ghostscript's default scan rule paints every pixel a shape touches, which fattens each edge
# by up to a pixel at the page's own resolution; fill adjustment 0 is the centre-of-pixel rule
# of the meta-language (spec 5.1), so that the comparison is of geometry, not of scan rules.
CENTRE="-c 0 0 .setfilladjust2 -f"

# psnr A B: PSNR in dB of two pictures of one size ("inf" when identical)
psnr() { compare -metric PSNR "$1" "$2" null: 2>&1 | awk '{print $1}'; }
# atleast V MIN: V >= MIN, "inf" passes anything, "exact" needs inf
atleast() { awk -v v="$1" -v m="$2" 'BEGIN {if (v == "inf") exit 0; if (m == "exact" || v !~ /^[0-9.]+$/) exit 1; exit !(v + 0 >= m + 0)}'; }
# the lowest PSNR (gs, pdftoppm) accepted per fixture: chosen by looking at the pictures, a
# little below what this machine's Ghostscript 10 and poppler 22 give (docs/postscript.md)
floors() {
	case $1 in
	f-test) echo "exact 33" ;;
	image) echo "exact 19.5" ;;    # pdftoppm resamples images: the checkerboard blurs
	trifocal-raytrace) echo "exact 30" ;;
	fills) echo "25 18.5" ;;
	strokes) echo "28.5 17" ;;
	text) echo "22 13.5" ;;
	coverage) echo "27.5 13.5" ;;
	extreme) echo "13 14" ;;       # gs dashes lines that start 10^6 pixels away in floats
	font) echo "19 13.5" ;;
	joins) echo "21.5 15" ;;
	sum-contour) echo "25 12" ;;
	*) echo "exact exact" ;;
	esac
}

# ---- every fixture in each form ------------------------------------------------------------
# Ghostscript runs once per form over all fixtures (page k is fixture k), at 96 dpi, the
# natural resolution of a page without a size statement (f-test's 42.333 mm are 96.0007 dpi,
# close enough not to move an edge). PS is written with --media so that each page has its size.
LIST=""
for f in fixtures/meta/*.meta fixtures/raster/inputs/*.meta fixtures/render/sum-contour.meta \
		fixtures/render/trifocal-raytrace.meta; do
	c=$(basename "$f" .meta)
	[ "$c" = multipage ] && continue
	if [ ! -f "fixtures/raster/$c.raster.png" ]; then
		"$BIN/locus-raster" "$f" -o "$T/$c.ref.png" || { notok "$c: locus-raster failed"; continue; }
	fi
	"$P" "$f" -o "$T/$c.eps" 2> "$T/err" && "$P" --media "$f" -o "$T/$c.ps" 2>> "$T/err" &&
		"$P" "$f" -o "$T/$c.pdf" 2>> "$T/err" || { notok "$c: locus-ps failed: $(cat "$T/err")"; continue; }
	LIST="$LIST $c"
done
files() { for c in $LIST; do printf '%s ' "$T/$c.$1"; done; }
# shellcheck disable=SC2046
{
	$GS -sDEVICE=png16m -r96 -sOutputFile="$T/ps-%02d.png" $CENTRE $(files ps)
	$GS -sDEVICE=png16m -r96 -sOutputFile="$T/pdf-%02d.png" $CENTRE $(files pdf)
	$GS -sDEVICE=png16m -r96 -dEPSCrop -sOutputFile="$T/eps-%02d.png" $CENTRE $(files eps)
	$GS -sDEVICE=bbox $(files eps) 2>&1 | sed -n 's/^%%HiResBoundingBox: //p' > "$T/bbox.eps"
	$GS -sDEVICE=bbox $(files ps) 2>&1 | sed -n 's/^%%HiResBoundingBox: //p' > "$T/bbox.ps"
} 2> "$T/gs.err"
k=0
for c in $LIST; do
	k=$((k + 1))
	kk=$(printf %02d $k)
	ref=fixtures/raster/$c.raster.png
	[ -f "$ref" ] || ref=$T/$c.ref.png
	set -- $(floors "$c")
	fgs=$1 fpp=$2
	H=$(identify -format %h "$ref")
	# EPS: compare with the same crop of the reference (the box is in whole pixels)
	crop=$(sed -n 's/^%%HiResBoundingBox: //p' "$T/$c.eps" | awk -v h="$H" '{
		x0 = int($1 / .75 + .5); y0 = int($2 / .75 + .5); x1 = int($3 / .75 + .5); y1 = int($4 / .75 + .5)
		printf "%dx%d+%d+%d", x1 - x0, y1 - y0, x0, h - y1 }')
	convert "$ref" -crop "$crop" +repage "$T/$c.crop.png"
	for form in ps pdf eps; do
		want=$ref
		[ $form = eps ] && want=$T/$c.crop.png
		v=$(psnr "$want" "$T/$form-$kk.png")
		if atleast "$v" "$fgs"; then ok "$c.$form: Ghostscript renders it like locus-raster (PSNR $v, floor $fgs)"
		else notok "$c.$form: Ghostscript's rendering has PSNR $v against locus-raster (floor $fgs) $(head -c 300 "$T/gs.err")"; fi
	done
	if command -v qpdf > /dev/null; then
		check "$c.pdf: qpdf --check" qpdf --check "$T/$c.pdf"
	fi
	if command -v pdftoppm > /dev/null; then
		pdftoppm -r 96 -aa no -aaVector no -png -singlefile "$T/$c.pdf" "$T/$c.pp" 2> "$T/err"
		v=$(psnr "$ref" "$T/$c.pp.png")
		if atleast "$v" "$fpp"; then ok "$c.pdf: pdftoppm renders it (PSNR $v, floor $fpp)"
		else notok "$c.pdf: pdftoppm's rendering has PSNR $v (floor $fpp) $(head -c 200 "$T/err")"; fi
	fi
	# Ghostscript's bbox device: its box lies within ours, and (unless the page is cleared
	# white, which the bbox device does not count as marking) ours within a pixel of its box
	white=0
	grep -q '^clear #ffffff' "fixtures/meta/$c.meta" "fixtures/raster/inputs/$c.meta" "fixtures/render/$c.meta" 2> /dev/null && white=1
	for form in eps ps; do
		ours=$(grep '^%%HiResBoundingBox: [0-9]' "$T/$c.$form" | tail -1 | cut -d' ' -f2-)
		theirs=$(sed -n "${k}p" "$T/bbox.$form")
		if echo "$ours $theirs" | awk -v w=$white '{d = w ? 1e9 : 1.6; if (NF != 8) exit 1;
				for (k = 1; k <= 2; k++) if ($(k+4) < $k - 0.2 || $(k+4) > $k + d) exit 1;
				for (k = 3; k <= 4; k++) if ($(k+4) > $k + 0.2 || $(k+4) < $k - d) exit 1; exit 0}'; then
			ok "$c.$form: gs bbox [$theirs] agrees with [$ours]"
		else notok "$c.$form: gs bbox [$theirs] disagrees with our box [$ours]"; fi
	done
done

# ---- the "F": every filled rectangle pixel-exact, with Ghostscript's own scan rule too -------
for form in eps ps pdf; do
	o=$T/F.$form
	"$P" fixtures/meta/f-test.meta -o "$o"
	case $form in
	eps) $GS -sDEVICE=png16m -r96.00072 -dEPSCrop -sOutputFile="$o.png" "$o" ;;
	ps) $GS -sDEVICE=png16m -r96.00072 -g160x120 -dFIXEDMEDIA -sOutputFile="$o.png" "$o" ;;
	pdf) $GS -sDEVICE=png16m -r96.00072 -sOutputFile="$o.png" "$o" ;;
	esac
	ae=$(compare -metric AE fixtures/raster/f-test.raster.png "$o.png" null: 2>&1)
	[ "$ae" = 0 ] && ok "F.$form: gs's default rendering is pixel-exact" || notok "F.$form: $ae pixels differ"
done

# ---- DSC structure ---------------------------------------------------------------------------
dsc() {   # dsc FILE PAGES EPS(0|1): prints what is wrong, nothing when all is right
	awk -v pages="$2" -v eps="$3" '
		NR == 1 { if (eps && $0 != "%!PS-Adobe-3.0 EPSF-3.0") print "first line " $0;
			if (!eps && $0 != "%!PS-Adobe-3.0") print "first line " $0 }
		length($0) > 255 { print "line " NR " longer than 255" }
		/^%%BoundingBox: [0-9-]/ { bb++ } /^%%HiResBoundingBox: [0-9-]/ { hb++ }
		/^%%EndComments$/ { ec++ } /^%%EndProlog$/ { ep++ } /^%%Trailer$/ { tr++ }
		/^%%LanguageLevel: [123]$/ { ll++ } /^%%Page: / { pg++ } /^%%PageTrailer$/ { pt++ }
		/^%%PageBoundingBox: [0-9-]/ { pb++ } /^%%CreationDate/ { print "a date by default" }
		/^%%Pages: [0-9]/ { np = $2 } /showpage/ { sp++ }
		eps && /(setpagedevice|initgraphics|erasepage|initmatrix|initclip|copypage|exitserver| quit)/ { print "EPS uses " $0 }
		{ last = $0 }
		END { if (bb != 1 || hb != 1) print "bounding boxes " bb " " hb; if (ec != 1 || ep != 1 || tr != 1) print "sections";
			if (ll != 1) print "LanguageLevel"; if (pg != pages || pt != pages || np != pages || sp != pages) print "pages " pg " " pt " " np " " sp;
			if (!eps && pb != pages) print "PageBoundingBox " pb; if (last != "%%EOF") print "last line " last }' "$1"
}
"$P" fixtures/meta/multipage.meta -o "$T/mp.ps"
"$P" fixtures/meta/strokes.meta -o "$T/s.eps"
"$P" --level 1 fixtures/meta/image.meta -o "$T/i1.ps"
"$P" --level 3 --paper a4 --media fixtures/meta/text.meta -o "$T/t3.ps"
for x in "mp.ps 3 0" "s.eps 1 1" "i1.ps 1 0" "t3.ps 1 0"; do
	set -- $x
	e=$(dsc "$T/$1" "$2" "$3")
	[ -z "$e" ] && ok "$1: DSC 3.0 comments and structure" || notok "$1: DSC: $e"
done
grep -q "^<< /PageSize \[595.2756 841.8898\] >> setpagedevice$" "$T/t3.ps" && ok "--media asks for A4" || notok "--media: no setpagedevice"
! grep -q 'setpagedevice' "$T/mp.ps" && ok "no setpagedevice unless asked" || notok "setpagedevice without --media"
if ! grep -Eq '<<|filter|setcolorspace' "$T/i1.ps" && grep -q 'readhexstring' "$T/i1.ps"; then ok "level 1: hex colorimage, no level 2 operators"
else notok "level 1 output uses level 2 operators"; fi

# ---- levels and grey: the same pixels from every image encoding ----------------------------
for lv in 1 2 3; do
	"$P" -f ps --level $lv fixtures/render/trifocal-raytrace.meta -o "$T/rt$lv.ps"
	$GS -sDEVICE=png16m -r96 -g96x72 -dFIXEDMEDIA -sOutputFile="$T/rt$lv.png" "$T/rt$lv.ps"
	"$BIN/locus-raster" fixtures/render/trifocal-raytrace.meta -o "$T/rt.png"
	ae=$(compare -metric AE "$T/rt.png" "$T/rt$lv.png" null: 2>&1)
	[ "$ae" = 0 ] && ok "level $lv image: pixel-exact ($(wc -c < "$T/rt$lv.ps") bytes)" || notok "level $lv image: $ae pixels differ"
done
s1=$(wc -c < "$T/rt1.ps") s2=$(wc -c < "$T/rt2.ps") s3=$(wc -c < "$T/rt3.ps")
[ "$s3" -lt "$s2" ] && [ "$s2" -lt "$s1" ] && ok "each level is smaller: $s1 > $s2 > $s3 bytes" || notok "level sizes $s1 $s2 $s3"
grep -q FlateDecode "$T/rt3.ps" && ! grep -q FlateDecode "$T/rt2.ps" && ok "Flate only at level 3" || notok "Flate at the wrong level"
"$P" --grey fixtures/meta/image.meta -o "$T/g.pdf"
$GS -sDEVICE=pnggray -r96 -sOutputFile="$T/g.png" "$T/g.pdf"
convert fixtures/raster/image.raster.png -colorspace Gray -fx '(0.299*r.r+0.587*r.g+0.114*r.b)' "$T/gref.png" 2> /dev/null ||
	convert fixtures/raster/image.raster.png -fx '0.299*r+0.587*g+0.114*b' -colorspace Gray "$T/gref.png"
v=$(psnr "$T/gref.png" "$T/g.png")
atleast "$v" 45 && ok "--grey: luminance picture (PSNR $v against BT.601 luma)" || notok "--grey: PSNR $v"
grep -aq 'DeviceRGB' "$T/g.pdf" && notok "--grey PDF still uses RGB" || ok "--grey PDF has no RGB"
for lv in 1 2 3; do
	"$P" --grey --level $lv -f eps fixtures/meta/image.meta -o "$T/g$lv.eps"
	$GS -sDEVICE=pnggray -r96 -dEPSCrop -sOutputFile="$T/g$lv.png" "$T/g$lv.eps"
	v=$(psnr "$T/gref.png" "$T/g$lv.png")
	atleast "$v" 45 && ok "--grey level $lv EPS: luminance picture (PSNR $v)" || notok "--grey level $lv: PSNR $v"
done

# an ordered dither at 288 dpi (3 x 3 dots a pixel): only black and white, and averaged over
# each pixel's dots the luminance picture again
"$P" --dither 288 -f eps fixtures/render/trifocal-raytrace.meta -o "$T/dith.eps"
$GS -sDEVICE=pnggray -r288 -dEPSCrop -sOutputFile="$T/dith.png" "$T/dith.eps"
"$BIN/locus-raster" fixtures/render/trifocal-raytrace.meta -o "$T/rt.png"
convert "$T/rt.png" -fx '0.299*r+0.587*g+0.114*b' -colorspace Gray "$T/rtg.png"
convert "$T/dith.png" -filter box -resize 96x72 "$T/dith-avg.png"
levels=$(convert "$T/dith.png" -format %c histogram:info:- | wc -l)
v=$(psnr "$T/rtg.png" "$T/dith-avg.png")
[ "$levels" = 2 ] && atleast "$v" 22 && ok "--dither 288: two levels, averages to the luminance (PSNR $v)" ||
	notok "--dither: $levels levels, PSNR $v"

# ---- spans and rows merge into images, never a rectangle per pixel ---------------------------
awk 'BEGIN { print "LOCUS-META 1"; print "page 40 30";
	for (y = 29; y >= 10; y--) for (x = 5; x < 35; x += 3) printf "span %d %d 3 #%02x%02x40\n", x, y, x * 6, y * 8;
	for (y = 0; y < 6; y++) printf "span 2 %d 20 #%02x0000\n", y, 40 * y; print "end-page" }' > "$T/spans.meta"
"$P" -f pdf "$T/spans.meta" -o "$T/spans.pdf"
"$P" -f ps --level 2 "$T/spans.meta" -o "$T/spans.ps"
n=$(grep -c ' image$' "$T/spans.ps")
[ "$n" = 2 ] && ok "200 spans downwards and 6 upwards make 2 images" || notok "spans made $n images"
"$BIN/locus-raster" "$T/spans.meta" -o "$T/spans.ref.png"
$GS -sDEVICE=png16m -r96 -sOutputFile="$T/spans.png" "$T/spans.pdf"
ae=$(compare -metric AE "$T/spans.ref.png" "$T/spans.png" null: 2>&1)
[ "$ae" = 0 ] && ok "merged spans: pixel-exact" || notok "merged spans: $ae pixels differ"

# ---- an EPS inside another page leaves the graphics state and dictionaries as it found them --
{
	printf '%%!PS\n/showpage {} def\n'
	printf '0.2 0.4 0.6 setrgbcolor 3 setlinewidth 1 setlinecap 2 setlinejoin [4 2] 1 setdash 100 200 translate\n'
	printf '/probe { [ currentrgbcolor currentlinewidth currentlinecap currentlinejoin currentmiterlimit currentdash pop aload pop matrix currentmatrix aload pop count countdictstack ] } def\n'
	printf '/before probe def\n%%%%BeginDocument: s.eps\n'
	cat "$T/s.eps"
	printf '%%%%EndDocument\n/after probe def\n0 0 moveto 50 50 lineto stroke\n'
	printf '(state ) print before length after length eq { true 0 1 before length 1 sub { dup before exch get exch after exch get ne { pop false } if } for } { false } ifelse { (same) } { (changed) } ifelse =\n'
	printf '(names ) print userdict /M known userdict /L known or { (leaked) } { (clean) } ifelse =\n'
	printf 'systemdict /showpage get exec\n'
} > "$T/host.ps"
res=$($GS -dNODISPLAY "$T/host.ps" 2>&1 | tr '\n' ' ')
case $res in
*"state same"*"names clean"*) ok "EPS embedded in a page: state and dictionaries as found" ;;
*) notok "EPS embedded in a page: $res" ;;
esac
$GS -sDEVICE=png16m -r72 -g300x400 -sOutputFile="$T/host.png" "$T/host.ps" > /dev/null 2> "$T/err" && [ -s "$T/host.png" ] &&
	ok "the host page with the EPS renders" || notok "host page: $(cat "$T/err")"

# ---- multi-page PS (with --media) and PDF: every page at its own size ------------------------
"$P" --media fixtures/meta/multipage.meta -o "$T/mpm.ps"
"$P" fixtures/meta/multipage.meta -o "$T/mp.pdf"
for form in mpm.ps mp.pdf; do
	rm -f "$T"/pg-*.png
	$GS -sDEVICE=png16m -r96 -sOutputFile="$T/pg-%d.png" $CENTRE "$T/$form"
	good=0
	for k in 1 2 3; do
		v=$(psnr fixtures/raster/multipage.raster-00$k.png "$T/pg-$k.png")
		atleast "$v" 25 && good=$((good + 1))
	done
	[ "$good" = 3 ] && [ ! -f "$T/pg-4.png" ] && ok "$form: three pages, each like its raster" || notok "$form: $good of 3 pages match"
done
rm -rf "$T/eps" && mkdir "$T/eps"
"$P" fixtures/meta/multipage.meta -o "$T/eps/mp.eps"
[ "$(ls "$T/eps")" = "mp-001.eps
mp-002.eps
mp-003.eps" ] && ok "EPS: one file per page" || notok "EPS pages: $(ls "$T/eps" | tr '\n' ' ')"
good=0
for k in 1 2 3; do
	$GS -sDEVICE=png16m -r96 -dEPSCrop -sOutputFile="$T/eps/pg.png" $CENTRE "$T/eps/mp-00$k.eps"
	# pages 1 and 2 are not cleared: their boxes are the strokes; page 3 is the whole page
	set -- $(sed -n 's/^%%HiResBoundingBox: //p' "$T/eps/mp-00$k.eps")
	H=$(identify -format %h fixtures/raster/multipage.raster-00$k.png)
	crop=$(echo "$1 $2 $3 $4" | awk -v h="$H" '{x0 = int($1 / .75 + .5); y0 = int($2 / .75 + .5); x1 = int($3 / .75 + .5); y1 = int($4 / .75 + .5)
		printf "%dx%d+%d+%d", x1 - x0, y1 - y0, x0, h - y1 }')
	convert fixtures/raster/multipage.raster-00$k.png -crop "$crop" +repage "$T/eps/ref.png"
	v=$(psnr "$T/eps/ref.png" "$T/eps/pg.png")
	atleast "$v" 25 && good=$((good + 1))
done
[ "$good" = 3 ] && ok "EPS pages render like their rasters" || notok "EPS pages: $good of 3 match"
expect_exit 65 "EPS of several pages to stdout is refused" sh -c "'$P' -f eps fixtures/meta/multipage.meta > /dev/null"

# ---- paper, orientation, placement ----------------------------------------------------------
"$P" --paper a4 --orientation landscape --margin 20 fixtures/meta/f-test.meta -o "$T/a4l.pdf"
grep -aq 'MediaBox \[0 0 841.8898 595.2756\]' "$T/a4l.pdf" && ok "A4 landscape MediaBox" || notok "A4 landscape MediaBox"
bb=$($GS -sDEVICE=bbox "$T/a4l.pdf" 2>&1 | sed -n 's/^%%HiResBoundingBox: //p')
echo "$bb" | awk '{m = 20 * 72 / 25.4; exit !($1 >= m - 1 && $2 >= m - 1 && $3 <= 841.89 - m + 1 && $4 <= 595.28 - m + 1 && $4 - $2 > 595.28 - 2 * m - 2)}' &&
	ok "fitted inside 20 mm margins, full height [$bb]" || notok "fit: [$bb]"
"$P" --paper 100x50mm --place centre -f ps fixtures/meta/f-test.meta -o "$T/c.ps"
grep -q '^%%PageBoundingBox: 81 25 202 116$' "$T/c.ps" && ok "custom paper, natural size centred" || notok "centre: $(grep PageBound "$T/c.ps" | tail -1)"
"$P" --scale 2 -f eps fixtures/meta/f-test.meta -o "$T/x2.eps"
grep -q '^%%HiResBoundingBox: 0.0000 0.0000 239.9981 180.0000$' "$T/x2.eps" && ok "--scale 2" || notok "--scale: $(grep HiRes "$T/x2.eps")"

# ---- goldens, byte for byte; stdin and stdout; dates ----------------------------------------
while read -r golden args; do
	[ -n "$golden" ] || continue
	# shellcheck disable=SC2086
	"$P" $args -o "$T/$golden" 2> "$T/err"
	same_file "golden fixtures/ps/$golden" "fixtures/ps/$golden" "$T/$golden"
done < fixtures/ps/goldens.txt
"$P" -f pdf < fixtures/meta/f-test.meta > "$T/stdout.pdf"
same_file "stdin to stdout" fixtures/ps/f-test.pdf "$T/stdout.pdf"
SOURCE_DATE_EPOCH=86400 "$P" fixtures/meta/f-test.meta -o "$T/nd.ps"
grep -q CreationDate "$T/nd.ps" && notok "a date without --date" || ok "no date unless asked"
SOURCE_DATE_EPOCH=86400 "$P" --date fixtures/meta/f-test.meta -o "$T/d.ps"
SOURCE_DATE_EPOCH=86400 "$P" --date fixtures/meta/f-test.meta -o "$T/d.pdf"
grep -q '^%%CreationDate: (1970-01-02T00:00:00Z)$' "$T/d.ps" && grep -aq '/CreationDate (D:19700102000000Z)' "$T/d.pdf" &&
	ok "--date honours SOURCE_DATE_EPOCH" || notok "--date with SOURCE_DATE_EPOCH"
"$BIN/locus-play" -d pdf fixtures/meta/f-test.meta -o "$T/play.pdf"
same_file "locus-play -d pdf = locus-ps -f pdf" fixtures/ps/f-test.pdf "$T/play.pdf"

# ---- bad input and bad options: one line, sysexits status, no output file ------------------
bad=0 n=0
for f in fixtures/bad/*.meta fixtures/bad/*.lmb; do
	[ -f "$f" ] || continue
	for form in eps pdf; do
		n=$((n + 1))
		rm -f "$T/bad.$form"
		"$P" "$f" -o "$T/bad.$form" 2> "$T/err"
		rc=$?
		if [ $rc != 65 ] || [ -e "$T/bad.$form" ] || [ "$(wc -l < "$T/err")" != 1 ] || ! grep -q "$(basename "$f")" "$T/err"; then
			bad=$((bad + 1))
			echo "# $f ($form): exit $rc: $(cat "$T/err")"
		fi
	done
done
[ $bad = 0 ] && ok "bad inputs ($n runs): exit 65, one line naming the file, no output" || notok "$bad of $n bad-input runs misbehaved"
expect_exit 64 "unknown form" "$P" -f svg fixtures/meta/f-test.meta
expect_exit 64 "level 4" "$P" --level 4 fixtures/meta/f-test.meta -o "$T/x.ps"
expect_exit 64 "unknown paper" "$P" --paper b5 fixtures/meta/f-test.meta -o "$T/x.ps"
expect_exit 64 "unknown -O key" "$P" -O colour=red fixtures/meta/f-test.meta -o "$T/x.ps"
expect_exit 64 "paper on EPS" "$P" -f eps --paper a4 fixtures/meta/f-test.meta -o "$T/x.eps"
expect_exit 66 "missing input" "$P" "$T/nothing.meta" -o "$T/x.ps"
[ ! -e "$T/x.ps" ] && [ ! -e "$T/x.eps" ] && ok "no output file after a usage error" || notok "a usage error left a file"
# ---- round 2 encodings: level 3's binary draws and PDF's one line per path -------------------
# level 3 writes runs of deltas as binary number strings (H), level 2 as text (L): the same pixels
grep -q '^/H {aload length 2 idiv {rlineto} repeat} bind def$' "$T/sum-contour.ps" && ! grep -q '^/H ' "$T/i1.ps" &&
	ok "level 3 defines H for binary draws, level 1 does not" || notok "the H procedure"
for c in strokes sum-contour extreme text; do
	f=fixtures/meta/$c.meta
	[ -f "$f" ] || f=fixtures/raster/inputs/$c.meta
	[ -f "$f" ] || f=fixtures/render/$c.meta
	"$P" --level 2 "$f" -o "$T/$c.l2.eps" && "$P" --level 3 "$f" -o "$T/$c.l3.eps"
	$GS -sDEVICE=png16m -r96 -dEPSCrop -sOutputFile="$T/$c.l2.png" "$T/$c.l2.eps" 2> /dev/null
	$GS -sDEVICE=png16m -r96 -dEPSCrop -sOutputFile="$T/$c.l3.png" "$T/$c.l3.eps" 2> /dev/null
	ae=$(compare -metric AE "$T/$c.l2.png" "$T/$c.l3.png" null: 2>&1)
	[ "$ae" = 0 ] && ok "$c: level 3 (binary draws) renders the pixels of level 2 (text draws)" || notok "$c: levels 2 and 3 differ by $ae pixels"
done
# PDF: in a plain content stream a path is one line, its origin translated: a stroke in q 1 0 0 1
# X Y cm ... S Q, fills chained, the first of a group by q 1 0 0 1 X Y cm, each next one from the
# one before (1 0 0 1 DX DY cm), at most 32 a group
if command -v qpdf > /dev/null; then
	qpdf --qdf --object-streams=disable "$T/fills.pdf" "$T/fl.qdf.pdf" && qpdf --qdf --object-streams=disable "$T/strokes.pdf" "$T/st.qdf.pdf" && cat "$T/fl.qdf.pdf" >> "$T/st.qdf.pdf"
	bad=$(awk '/^stream$/ {s = 1; next} /^endstream$/ {s = 0} s && / m / && !/^(.* )?(q )?1 0 0 1 -?[0-9]+ -?[0-9]+ cm .* (S Q|f|f\*)$/' "$T/st.qdf.pdf" | wc -l)
	paths=$(awk '/^stream$/ {s = 1; next} /^endstream$/ {s = 0} s && / m / {n++} END {print n + 0}' "$T/st.qdf.pdf")
	[ "$bad" = 0 ] && [ "$paths" -gt 3 ] && ok "PDF: each of $paths paths is one content line" || notok "PDF: $bad path lines broken ($paths whole)"
	awk 'BEGIN { print "LOCUS-META 1"; print "page 200 100"
		for (k = 0; k < 100; k++) printf "colour #%06x\nfill\nmove %d %d\ndraw %d %d\ndraw %d %d\nend\n", k * 997, k * 2, 3 + k % 7, k * 2 + 5, 90 - k % 11, k * 2 + 1, 50
		print "end-page" }' > "$T/chain.meta" && "$P" "$T/chain.meta" -o "$T/chain.pdf" && qpdf --qdf --object-streams=disable "$T/chain.pdf" "$T/chain.qdf.pdf"
	q=$(grep -ac ' q 1 0 0 1 ' "$T/chain.qdf.pdf") rel=$(grep -ac '^[^q]* 1 0 0 1 -\?[0-9]* -\?[0-9]* cm' "$T/chain.qdf.pdf")
	# the same pixels as the PostScript (absolute origins, no matrix chain) and like locus-raster
	"$P" --level 2 --media "$T/chain.meta" -o "$T/chain.ps"
	"$BIN/locus-raster" "$T/chain.meta" -o "$T/chain.ref.png"
	$GS -sDEVICE=png16m -r96 -sOutputFile="$T/chain.png" $CENTRE "$T/chain.pdf"
	$GS -sDEVICE=png16m -r96 -sOutputFile="$T/chain.ps.png" $CENTRE "$T/chain.ps"
	v=$(psnr "$T/chain.ref.png" "$T/chain.png") e=$(compare -metric AE "$T/chain.ps.png" "$T/chain.png" null: 2>&1)
	[ "$q" = 4 ] && [ "$rel" = 96 ] && [ "$e" = 0 ] && atleast "$v" 24.5 &&
		ok "100 fills: 4 groups of q ... Q, 96 relative origins, the pixels of the PS, like locus-raster (PSNR $v)" ||
		notok "origin chain: $q groups, $rel relative origins, $e pixels from the PS, PSNR $v (floor 24.5)"
fi
# ---- points that draw nothing --------------------------------------------------------------
# A point equal to the one before it on the output grid, and a point on the straight way between
# its neighbours, are dropped: idle.meta has both kinds (in a stroke, a dot of round caps, a fill
# and a dashed line) and must give the very bytes of clean.meta, the same paths without them, in
# every form and level. A draw that turns back is kept, and so is a dot's draw of no length.
cat > "$T/idle.meta" << 'EOF'
LOCUS-META 1
page 96 64
width 4
stroke
move 8 8
draw 24 8
draw 40 8
draw 40.02 8
draw 56 8
draw 56 24
end
stroke
move 8 32
draw 40 32
draw 24 32
end
cap round
width 8
stroke
move 70 44
draw 70 44
draw 70.01 44
end
colour #c00000
fill
move 60 28
draw 70 28
draw 80 28
draw 80 36
draw 80 36
draw 60 36
end
dash 4 4
width 2
colour #0000c0
stroke
move 8 52
draw 20 52
draw 32 52
draw 44 52
end
end-page
EOF
sed -e '/^draw 24 8$/d' -e '/^draw 40 8$/d' -e '/^draw 40.02 8$/d' -e '/^draw 70.01 44$/d' \
	-e '/^draw 70 28$/d' -e '/^draw 20 52$/d' -e '/^draw 32 52$/d' "$T/idle.meta" |
	awk '!($0 == "draw 80 36" && seen++)' > "$T/clean.meta"
differ=""
for m in idle clean; do
	for l in 1 2 3; do
		"$P" --level $l "$T/$m.meta" -o "$T/$m.l$l.ps" && "$P" --level $l "$T/$m.meta" -o "$T/$m.l$l.eps" ||
			differ="$differ $m-failed"
	done
	"$P" "$T/$m.meta" -o "$T/$m.pdf" || differ="$differ $m-failed"
done
for f in l1.ps l2.ps l3.ps l1.eps l2.eps l3.eps pdf; do cmp -s "$T/idle.$f" "$T/clean.$f" || differ="$differ $f"; done
[ -z "$differ" ] && [ "$(grep -c '^draw' "$T/clean.meta")" = 9 ] &&
	ok "points that draw nothing are dropped: idle.meta's PS, EPS and PDF are clean.meta's bytes" ||
	notok "idle points: differs from the clean paths in$differ"
grep -q '80 80 M 480 0 l 0 160 l S$' "$T/idle.l2.ps" && grep -q '80 320 M 320 0 l -160 0 l S$' "$T/idle.l2.ps" &&
	grep -q '700 440 M 0 0 l S$' "$T/idle.l2.ps" && grep -q '80 520 M 360 0 l S$' "$T/idle.l2.ps" &&
	ok "idle points: the straight run is one draw, the turn back and the dot's draw stay" ||
	notok "idle points: level 2 paths $(grep ' M ' "$T/idle.l2.ps" | head -5 | tr '\n' '|')"
"$BIN/locus-raster" "$T/idle.meta" -o "$T/idle.ref.png"
"$P" --media "$T/idle.meta" -o "$T/idle.media.ps"
for f in media.ps pdf; do
	$GS -sDEVICE=png16m -r96 -sOutputFile="$T/idle.$f.png" $CENTRE "$T/idle.$f"
	v=$(psnr "$T/idle.ref.png" "$T/idle.$f.png")
	atleast "$v" 40 && ok "idle points $f: Ghostscript draws locus-raster's picture (PSNR $v)" ||
		notok "idle points $f: PSNR $v (floor 40)"
done
# ---- PDF contour plates: points as predicted samples of the Flate filter --------------------
# A contour plate's long lattice paths go into a content stream with /DecodeParms << /Predictor
# 2 /Colors 12 /Columns 1024 >> (TIFF predictor, one point a 12-byte sample): Ghostscript and
# pdftoppm must render it pixel for pixel as the same PDF with its streams decoded by qpdf (no
# filter at all), and like locus-raster within the floors.
if command -v qpdf > /dev/null && command -v pdftoppm > /dev/null; then
	"$BIN/locus-render" --quiet fixtures/scenes/contour-sum.scene -o "$T/cs.meta" && "$P" "$T/cs.meta" -o "$T/cs.pdf" &&
		"$P" --level 2 --media "$T/cs.meta" -o "$T/cs.ps"
	check "contour plate PDF: qpdf --check" qpdf --check "$T/cs.pdf"
	grep -aq '/DecodeParms << /Predictor 2 /Colors 12 /Columns 1024 >>' "$T/cs.pdf" && ok "contour plate PDF uses the TIFF predictor" ||
		notok "contour plate PDF without the predictor"
	qpdf --stream-data=uncompress "$T/cs.pdf" "$T/cs.plain.pdf"
	! grep -aq 'Predictor\|FlateDecode' "$T/cs.plain.pdf" && ok "qpdf decodes the predicted stream" || notok "qpdf left filters in place"
	for v in cs cs.plain; do
		$GS -sDEVICE=png16m -r96 -sOutputFile="$T/$v.gs.png" $CENTRE "$T/$v.pdf"
		$GS -sDEVICE=png16m -r96 -sOutputFile="$T/$v.gsd.png" "$T/$v.pdf"
		pdftoppm -r 96 -aa no -aaVector no -png -singlefile "$T/$v.pdf" "$T/$v.pp"
	done
	for r in gs gsd pp; do
		ae=$(compare -metric AE "$T/cs.$r.png" "$T/cs.plain.$r.png" null: 2>&1)
		[ "$ae" = 0 ] && ok "contour plate: $r renders the predicted PDF pixel for pixel as the decoded one" || notok "contour plate: $r: $ae pixels differ"
	done
	"$BIN/locus-raster" "$T/cs.meta" -o "$T/cs.ref.png"
	$GS -sDEVICE=png16m -r96 -sOutputFile="$T/cs.ps.png" $CENTRE "$T/cs.ps"
	v=$(psnr "$T/cs.ref.png" "$T/cs.gs.png") w=$(psnr "$T/cs.ref.png" "$T/cs.pp.png") e=$(compare -metric AE "$T/cs.ps.png" "$T/cs.gs.png" null: 2>&1)
	atleast "$v" 30.5 && atleast "$w" 17 && [ "$e" = 0 ] &&
		ok "contour plate PDF like locus-raster (gs PSNR $v, pdftoppm $w) and gs gives the pixels of the level 2 PS" ||
		notok "contour plate PDF: gs PSNR $v (floor 26), pdftoppm $w (floor 16), $e pixels differ from the PS"
fi
# ---- the benchmark's cairo anchor builds clean and draws the same picture --------------------
if pkg-config --exists cairo 2> /dev/null; then
	LIBDIR=$(dirname "${TESTBIN:-build/native/tests}")
	SAN=""
	[ "${SANITIZE:-}" = 1 ] && SAN="-fsanitize=address,undefined -fno-omit-frame-pointer"
	# shellcheck disable=SC2046,SC2086
	if ${CC:-cc} -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -O1 -Wall -Wextra -Werror $SAN -Imeta \
			$(pkg-config --cflags cairo) tests/bench/cairo_anchor.c "$LIBDIR/libmeta.a" $(pkg-config --libs cairo) -lm \
			-o "$T/cairo_anchor" 2> "$T/ca.log"; then
		ok "cairo_anchor builds without warnings"
		"$T/cairo_anchor" -s image fixtures/meta/f-test.meta -o "$T/ca.png"
		v=$(psnr fixtures/raster/f-test.raster.png "$T/ca.png")
		atleast "$v" 30 && ok "cairo_anchor image surface draws the F (PSNR $v)" || notok "cairo_anchor F: PSNR $v"
		"$T/cairo_anchor" -s pdf fixtures/meta/f-test.meta -o "$T/ca.pdf" && "$T/cairo_anchor" -s ps fixtures/meta/f-test.meta -o "$T/ca.ps" &&
			$GS -sDEVICE=png16m -r96 -sOutputFile="$T/ca-pdf.png" "$T/ca.pdf" &&
			[ "$(identify -format %wx%h "$T/ca-pdf.png")" = 160x120 ] && grep -q '^%!PS' "$T/ca.ps" &&
			ok "cairo_anchor PS and PDF surfaces" || notok "cairo_anchor PS/PDF surfaces"
	else
		notok "cairo_anchor builds without warnings: $(head -3 "$T/ca.log")"
	fi
fi
done_tests

#!/bin/sh
# t_ps_readers.sh: locus-ps output read by consumers beside Ghostscript and pdftoppm (issue 22):
# MuPDF (mutool draw) and poppler's cairo back end (pdftocairo) render every fixture's PDF like
# locus-raster; images land one sample a pixel in both; every 8-bit colour comes back exact in
# readers that round (Ghostscript, pdftoppm), truncate (MuPDF) or go through cairo's 16 bits;
# a Level 1 document with colour images prints on a Level 1 interpreter without colorimage.
. tests/lib.sh
P=$BIN/locus-ps
if ! command -v compare > /dev/null; then
	ok "imagemagick missing # SKIP"
	done_tests
fi
psnr() { compare -metric PSNR "$1" "$2" null: 2>&1 | awk '{print $1}'; }
atleast() { awk -v v="$1" -v m="$2" 'BEGIN {if (v == "inf") exit 0; if (m == "exact" || v !~ /^[0-9.]+$/) exit 1; exit !(v + 0 >= m + 0)}'; }
HAVE_MU=0 HAVE_PC=0
command -v mutool > /dev/null && HAVE_MU=1 || ok "mutool (mupdf-tools) missing # SKIP"
command -v pdftocairo > /dev/null && HAVE_PC=1 || ok "pdftocairo (poppler-utils) missing # SKIP"
# mu: mutool draw with its default anti-aliasing (without it MuPDF fattens every edge by a
# pixel, like Ghostscript's default rule); pc: pdftocairo without anti-aliasing. Both at 96 dpi,
# the natural resolution of a page without a size statement.
mu() { mutool draw -q -r 96 -o "$2" "$1" 2> /dev/null; }
pc() { pdftocairo -png -r 96 -antialias none -singlefile "$1" "${2%.png}" 2> /dev/null; }

# ---- every fixture: PSNR against locus-raster ------------------------------------------------
# floors (MuPDF, pdftocairo), chosen by looking at the pictures side by side, a little below
# what mupdf 1.21 and poppler 22 give on this machine (docs/postscript.md): what remains are
# edge pixels (MuPDF's anti-aliasing bleeds a few percent into the pixel beside an edge that
# lies on a pixel boundary; cairo's non-AA rule differs from the centre rule at thin lines).
floors() {
	case $1 in
	image | trifocal-raytrace) echo "exact exact" ;;   # images and spans only: each sample on one pixel
	f-test) echo "36 exact" ;;    # its size makes 96.0007 dpi: MuPDF's edges bleed; cairo exact
	fills) echo "27 25" ;;
	strokes) echo "25.5 30" ;;
	text) echo "22 21.5" ;;
	coverage) echo "23 27.5" ;;
	extreme) echo "19.5 23" ;;
	font) echo "20 16" ;;
	joins) echo "21.5 21.5" ;;
	sum-contour) echo "21 21" ;;
	*) echo "exact exact" ;;
	esac
}
for f in fixtures/meta/*.meta fixtures/raster/inputs/*.meta fixtures/render/sum-contour.meta \
		fixtures/render/trifocal-raytrace.meta; do
	c=$(basename "$f" .meta)
	[ "$c" = multipage ] && continue
	ref=fixtures/raster/$c.raster.png
	[ -f "$ref" ] || { "$BIN/locus-raster" "$f" -o "$T/$c.ref.png" && ref=$T/$c.ref.png; }
	"$P" "$f" -o "$T/$c.pdf" 2> "$T/err" || { notok "$c: locus-ps failed: $(cat "$T/err")"; continue; }
	set -- $(floors "$c")
	if [ $HAVE_MU = 1 ]; then
		mu "$T/$c.pdf" "$T/$c.mu.png"
		v=$(psnr "$ref" "$T/$c.mu.png")
		if atleast "$v" "$1"; then ok "$c.pdf: MuPDF renders it like locus-raster (PSNR $v, floor $1)"
		else notok "$c.pdf: MuPDF's rendering has PSNR $v against locus-raster (floor $1)"; fi
	fi
	if [ $HAVE_PC = 1 ]; then
		pc "$T/$c.pdf" "$T/$c.pc.png"
		v=$(psnr "$ref" "$T/$c.pc.png")
		if atleast "$v" "$2"; then ok "$c.pdf: pdftocairo renders it like locus-raster (PSNR $v, floor $2)"
		else notok "$c.pdf: pdftocairo's rendering has PSNR $v against locus-raster (floor $2)"; fi
	fi
done

# ---- images: one sample a pixel (issue 22, item 1) -------------------------------------------
# image.meta's checkerboard went through the grid matrix (0.075 x 160): MuPDF found the product
# a little off 12 and blended pixel rows (64 pixels off by more than 64 levels). Also at level 2
# and with --grey, which take the same placement.
if [ $HAVE_MU = 1 ]; then
	for opt in "" "--grey"; do
		"$P" $opt fixtures/meta/image.meta -o "$T/img.pdf"
		mu "$T/img.pdf" "$T/img.mu.png"
		if [ -z "$opt" ]; then want=fixtures/raster/image.raster.png
		else
			gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -o "$T/img.gs.png" "$T/img.pdf" 2> /dev/null
			want=$T/img.gs.png
		fi
		ae=$(compare -metric AE "$want" "$T/img.mu.png" null: 2>&1)
		[ "$ae" = 0 ] && ok "image.meta $opt: MuPDF draws every image sample on its pixel" ||
			notok "image.meta $opt: MuPDF differs in $ae pixels"
	done
	# the point-unit image matrix: no image is placed through the grid matrix
	if command -v qpdf > /dev/null; then
		qpdf --qdf --stream-data=uncompress "$T/image.pdf" "$T/image.qdf.pdf"
		if grep -a 'Do Q' "$T/image.qdf.pdf" | grep -q '^q 12 0 0 12 6 30 cm /I1 Do Q$' &&
				! grep -a 'Do Q' "$T/image.qdf.pdf" | grep -q ' 160 0 0 160 '; then
			ok "image.pdf: images are placed in points (q 12 0 0 12 6 30 cm /I1 Do Q)"
		else notok "image.pdf: image matrices: $(grep -a 'Do Q' "$T/image.qdf.pdf" | head -3)"; fi
	fi
fi

# ---- colours: every byte back in every reader (issue 22, item 2) ------------------------------
# 256 squares of 8 x 8 pixels, colour k = (k, 255 - k, 37k mod 256): each channel takes every
# value. The centre pixel of each square is compared (edges are the readers' own business).
awk 'BEGIN { print "LOCUS-META 1"; print "page 128 128"
	for (k = 0; k < 256; k++) { x = (k % 16) * 8; y = int(k / 16) * 8
		printf "colour #%02x%02x%02x\nfill\nmove %d %d\ndraw %d %d\ndraw %d %d\ndraw %d %d\nclose\nend\n",
			k, 255 - k, (k * 37) % 256, x, y, x + 8, y, x + 8, y + 8, x, y + 8 }
	print "end-page" }' > "$T/col.meta"
"$BIN/locus-raster" "$T/col.meta" -o "$T/col.ref.png"
"$P" "$T/col.meta" -o "$T/col.pdf"
"$P" --grey "$T/col.meta" -o "$T/colg.pdf"
centres() { convert "$1" -define sample:offset=50 -sample 16x16 "$2" 2> /dev/null; }
centres "$T/col.ref.png" "$T/col.ref.s.png"
# grey: the luminance the device wrote, as Ghostscript reads it back from the --grey level 3 PS
"$P" --grey --media "$T/col.meta" -o "$T/colg.ps"
gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -o "$T/colg.ref.png" "$T/colg.ps" 2> /dev/null
centres "$T/colg.ref.png" "$T/colg.ref.s.png"
for r in mu pc pp gs; do
	case $r in
	mu) [ $HAVE_MU = 1 ] || continue; mu "$T/col.pdf" "$T/col.$r.png"; mu "$T/colg.pdf" "$T/colg.$r.png"; name=MuPDF ;;
	pc) [ $HAVE_PC = 1 ] || continue; pc "$T/col.pdf" "$T/col.$r.png"; pc "$T/colg.pdf" "$T/colg.$r.png"; name=pdftocairo ;;
	pp) command -v pdftoppm > /dev/null || continue; name=pdftoppm
		pdftoppm -png -r 96 -singlefile "$T/col.pdf" "$T/col.$r"; pdftoppm -png -r 96 -singlefile "$T/colg.pdf" "$T/colg.$r" ;;
	gs) command -v gs > /dev/null || continue; name=Ghostscript
		gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -o "$T/col.$r.png" "$T/col.pdf" 2> /dev/null
		gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -o "$T/colg.$r.png" "$T/colg.pdf" 2> /dev/null ;;
	esac
	centres "$T/col.$r.png" "$T/col.$r.s.png"
	centres "$T/colg.$r.png" "$T/colg.$r.s.png"
	ae=$(compare -metric AE "$T/col.ref.s.png" "$T/col.$r.s.png" null: 2>&1)
	ag=$(compare -metric AE "$T/colg.ref.s.png" "$T/colg.$r.s.png" null: 2>&1)
	[ "$ae" = 0 ] && [ "$ag" = 0 ] && ok "$name reads back all 256 values of each channel and of grey exactly" ||
		notok "$name: $ae of 256 colours and $ag of 256 greys differ from the bytes written"
done
if command -v qpdf > /dev/null; then
	! qpdf --qdf --stream-data=uncompress "$T/col.pdf" - 2> /dev/null | grep -aq ' \.188 ' &&
		ok "#30 is not written .188 (47.94 x 255: MuPDF truncated it to 47)" || notok "colour operands as before issue 22"
fi

# ---- Level 1 without the CMYK extension (issue 22, item 3) -----------------------------------
# A Level 1 interpreter without colorimage, made from Ghostscript: where finds no colorimage and
# calling it is an error. The colour images must then print as grey, the pixels of --grey.
if command -v gs > /dev/null; then
	NOCMYK='/where {dup /colorimage eq {pop false} {//systemdict /where get exec} ifelse} bind def /colorimage {colorimage_missing} def'
	GS="gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -dEPSCrop"
	for form in ps eps; do
		"$P" --level 1 fixtures/meta/image.meta -o "$T/l1.$form"
		"$P" --level 1 --grey fixtures/meta/image.meta -o "$T/l1g.$form"
		$GS -o "$T/l1nc.$form.png" -c "$NOCMYK" -f "$T/l1.$form" > "$T/l1.err" 2>&1
		$GS -o "$T/l1g.$form.png" "$T/l1g.$form" 2> /dev/null
		$GS -o "$T/l1.$form.png" "$T/l1.$form" 2> /dev/null
		if grep -q Error "$T/l1.err"; then notok "level 1 $form without colorimage: $(head -1 "$T/l1.err")"
		else
			ae=$(compare -metric AE "$T/l1g.$form.png" "$T/l1nc.$form.png" null: 2>&1)
			[ "$ae" = 0 ] && ok "level 1 $form without colorimage prints the images in grey, as --grey does" ||
				notok "level 1 $form without colorimage: $ae pixels differ from --grey"
		fi
		# with colorimage: the colour picture (EPS: cropped to the drawn box, the whole page here)
		if [ $form = eps ]; then
			ae=$(compare -metric AE fixtures/raster/image.raster.png "$T/l1.eps.png" null: 2>&1)
			[ "$ae" = 0 ] && ok "level 1 eps with colorimage: the colour picture" || notok "level 1 eps with colorimage: $ae pixels differ"
		fi
		grep -q '^%%Extensions: CMYK$' "$T/l1.$form" && ! grep -q '^%%Extensions' "$T/l1g.$form" &&
			! grep -q 'colorimage' "$T/l1g.$form" &&
			ok "level 1 $form: %%Extensions: CMYK in colour, nothing of it in grey" ||
			notok "level 1 $form: DSC extension comment"
	done
	# an EPS without colour images does not ask for the extension
	"$P" --level 1 fixtures/meta/strokes.meta -o "$T/l1s.eps"
	! grep -q '^%%Extensions' "$T/l1s.eps" && ok "level 1 EPS without images: no %%Extensions" ||
		notok "level 1 EPS without images declares an extension"
fi
done_tests

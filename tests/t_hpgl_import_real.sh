#!/bin/sh
# t_hpgl_import_real.sh: `locus-meta import` of HP-GL as real plotter files have it (issue 22,
# item 8), each behaviour with a small file written for the purpose: PG pages, RO, IP with only
# P1 and anisotropic SC (circles), tolerant reading with warnings naming the byte (and --strict
# refusing), polygon-mode outlines left open by EP; then every file of ../shared/corpus/hpgl
# reads tolerantly without a warning, to the same meta file as --strict.
. tests/lib.sh
M=$BIN/locus-meta
imp() { printf '%s' "$1" > "$T/t.hpgl"; "$M" import "$T/t.hpgl" -o "$T/t.meta" 2> "$T/t.err"; }
pages() { grep -c '^page ' "$1"; }

# ---- PG: each page advance after drawing starts a new meta page ------------------------------
imp 'IN;SP1;PU0,0;PD1000,0;PG;SP2;PU0,0;PD0,1000;PG1;SP3;PU0,0;PD500,500;PG;'
if [ "$(pages "$T/t.meta")" = 3 ] && [ "$(grep '^page ' "$T/t.meta" | tr '\n' ' ')" = "page 104 4 page 4 104 page 52 52 " ]; then
	ok "PG: three pages, each with its own drawing (a trailing PG adds none)"
else notok "PG: $(grep -E '^page ' "$T/t.meta" | tr '\n' ' ')"; fi
awk '/^page /{p++} /^colour/{c[p]=c[p] $2} END {exit !(c[1] == "" && c[2] == "#ff0000" && c[3] == "#00ff00")}' "$T/t.meta" &&
	ok "PG: pen 1 on page 1, pen 2 on page 2, pen 3 on page 3 only" || notok "PG: colours per page"
imp 'PG;IN;SP1;PU0,0;PD1000,0;PG;PG;'
[ "$(pages "$T/t.meta")" = 1 ] && ok "PG before drawing and repeated PG: one page" || notok "PG: $(pages "$T/t.meta") pages"

# ---- RO: the drawing turned counter-clockwise with the paper ---------------------------------
imp 'IN;SP1;PU0,0;PD4000,0,4000,500;'
cp "$T/t.meta" "$T/ro0.meta"
imp 'IN;RO90;SP1;PU0,0;PD4000,0,4000,500;'
# RO 0: page 416 x 66, the line to the right and the tick up; RO 90: 66 x 416, up and left
if grep -q '^page 416 66$' "$T/ro0.meta" && grep -q '^page 66 416$' "$T/t.meta" &&
		[ "$(grep -E '^(move|draw)' "$T/t.meta" | tr '\n' ' ')" = "move 58 8 draw 58 408 draw 8 408 " ]; then
	ok "RO 90: the page stands upright, the line runs up and its tick to the left (counter-clockwise, as hp2xx)"
else notok "RO 90: $(grep -E '^(page|move|draw)' "$T/t.meta" | tr '\n' ' ')"; fi
imp 'IN;RO180;SP1;PU0,0;PD4000,0,4000,500;'
grep -q '^page 416 66$' "$T/t.meta" && [ "$(grep -E '^(move|draw)' "$T/t.meta" | tr '\n' ' ')" = "move 408 58 draw 8 58 draw 8 8 " ] &&
	ok "RO 180: the line runs left, its tick down" || notok "RO 180: $(grep -E '^(page|move|draw)' "$T/t.meta" | tr '\n' ' ')"
# labels turn too: a label under RO 90 runs up the page
imp 'IN;RO90;SP1;PU0,0;LBHELLO'"$(printf '\003')"';'
awk '/^page/{w=$2; h=$3} END {exit !(h > 2 * w)}' "$T/t.meta" && ok "RO 90: a label runs up the page" || notok "RO 90 label: $(grep '^page' "$T/t.meta")"

# ---- IP with only P1, then SC: what the manual says, against hp2xx ---------------------------
# P2 keeps its offset from P1 (HP-GL/2 reference): a square in user units stays square.
imp 'IN;IP0,0,4000,4000;SC0,100,0,100;IP1000,2000;SP1;PU25,25;PD75,25,75,75,25,75,25,25;'
grep -q '^page 208 208$' "$T/t.meta" && ok "IP with only P1 after SC: P2 keeps its offset, the square stays square" ||
	notok "IP P1 only: $(grep '^page' "$T/t.meta")"
# with the default P2 (the 7475A's, 10000 x 7200 units from P1) SC 0,100,0,100 is anisotropic:
# CI is round in user units and so an ellipse on paper ("anisotropic scaling may produce an
# ellipse", HP's reference on CI), 1.39 times as wide as high; Locus drew it round before
imp 'IN;IP1000,2000;SC0,100,0,100;SP1;PU50,50;CI20;'
awk '/^page/{exit !($2 / $3 > 1.36 && $2 / $3 < 1.42)}' "$T/t.meta" &&
	ok "CI under anisotropic SC: an ellipse, $(grep '^page' "$T/t.meta")" || notok "CI under anisotropic SC: $(grep '^page' "$T/t.meta")"
if command -v hp2xx > /dev/null && command -v convert > /dev/null; then
	# hp2xx draws the same file elliptical too, and the IP square square (its default P2 is
	# portrait, so its ellipse stands upright: the default is a device's, not the manual's)
	printf 'IN;IP1000,2000;SC0,100,0,100;SP1;PU50,50;CI20;' > "$T/e.hpgl"
	printf 'IN;IP0,0,4000,4000;SC0,100,0,100;IP1000,2000;SP1;PU25,25;PD75,25,75,75,25,75,25,25;' > "$T/s.hpgl"
	hp2xx -q -m png -d 40 -f "$T/e.png" "$T/e.hpgl" > /dev/null 2>&1
	hp2xx -q -m png -d 40 -f "$T/s.png" "$T/s.hpgl" > /dev/null 2>&1
	e=$(convert "$T/e.png" -trim -format '%w %h' info: 2> /dev/null) s=$(convert "$T/s.png" -trim -format '%w %h' info: 2> /dev/null)
	echo "$e $s" | awk '{ exit !($1 / $2 < 0.9 && $3 == $4) }' && ok "hp2xx agrees: an ellipse ($e), the square square ($s)" ||
		notok "hp2xx: ellipse $e, square $s"
fi

# ---- tolerance: skipped with a warning naming the byte; --strict refuses ---------------------
# bytes: IN;SP1;PU0,0;PD1000,0; (0..21), ZZ1,2; (22), X0=0; (28), PD1000,1000; (33), PE (45) and
#        an 8-bit block of bytes no PE data has (0x80 at 47 and 48) and its ';' (49), PD0,1000; (50),
#        Q (59, trailing)
printf 'IN;SP1;PU0,0;PD1000,0;ZZ1,2;X0=0;PD1000,1000;PE\200\200;PD0,1000;Q' > "$T/junk.hpgl"
"$M" import "$T/junk.hpgl" -o "$T/junk.meta" 2> "$T/junk.err"; rc=$?
if [ $rc = 0 ] && grep -q 'junk.hpgl: byte 22: unknown command ZZ' "$T/junk.err" &&
		grep -q 'junk.hpgl: byte 28: skipped 5 bytes that are no HP-GL command (X0=0;)' "$T/junk.err" &&
		grep -q 'junk.hpgl: byte 47: bad byte 0x80 in PE data; skipped to byte 50' "$T/junk.err" &&
		grep -q 'junk.hpgl: byte 59: skipped 1 trailing bytes' "$T/junk.err" && [ "$(wc -l < "$T/junk.err")" = 4 ]; then
	ok "tolerant import: unknown command, junk, bad PE block and a trailing byte skipped, one warning each at its byte"
else notok "tolerant import: exit $rc, $(cat "$T/junk.err")"; fi
[ "$(grep -E '^(move|draw)' "$T/junk.meta" 2> /dev/null | tr '\n' ' ')" = "move 2 2 draw 102 2 draw 102 102 move 102 102 draw 2 102 " ] &&
	ok "tolerant import: everything readable is drawn (three sides, the line broken where the PE block was)" || notok "tolerant import drew: $(grep -E '^(move|draw)' "$T/junk.meta" | tr '\n' ' ')"
"$M" import --strict "$T/junk.hpgl" -o "$T/strict.meta" 2> "$T/strict.err"; rc=$?
[ $rc = 65 ] && grep -q 'junk.hpgl: byte 28: expected a two-letter HP-GL command' "$T/strict.err" && [ ! -e "$T/strict.meta" ] &&
	ok "--strict refuses the junk: 65, byte 28 named, no output" || notok "--strict: exit $rc, $(cat "$T/strict.err")"
printf 'IN;SP1;PD100,100;PE\200;' > "$T/pe.hpgl"
"$M" import --strict "$T/pe.hpgl" -o "$T/pe.meta" 2> "$T/pe.err"; rc=$?
[ $rc = 65 ] && grep -q 'pe.hpgl: byte 19: bad byte 0x80 in PE data' "$T/pe.err" && ok "--strict refuses a bad PE block (byte 19)" ||
	notok "--strict PE: exit $rc $(cat "$T/pe.err")"

# ---- polygon mode: EP leaves a contour the file did not close open; FP closes it -------------
imp 'IN;SP1;PU0,0;PM0;PD1000,0,1000,1000,0,1000;PM2;EP;'
[ "$(grep -cE '^draw' "$T/t.meta")" = 3 ] && ! grep -q '^close' "$T/t.meta" &&
	ok "EP: three sides drawn, the contour left open as in the file" || notok "EP: $(grep -E '^(move|draw|close)' "$T/t.meta" | tr '\n' ' ')"
imp 'IN;SP1;PU0,0;PM0;PD1000,0,1000,1000,0,1000,0,0;PM2;EP;'
[ "$(grep -cE '^draw' "$T/t.meta")" = 4 ] && ok "EP: a contour closed in the file is drawn closed" || notok "EP closed: $(grep -cE '^draw' "$T/t.meta") draws"
imp 'IN;SP1;PU0,0;PM0;PD1000,0,1000,1000,0,1000;PM2;FP;'
grep -q '^fill$' "$T/t.meta" && grep -q '^close$' "$T/t.meta" && ok "FP: the same contour filled closed" || notok "FP: $(tr '\n' ' ' < "$T/t.meta")"

# ---- character sets: CS / CA and SO / SI in labels --------------------------------------------
# CA7 (the Roman extension set, Roman-8's upper half on 0x21-0x7e): "A", SO "A" (0xc1 of Roman-8,
# e circumflex), SI "A" draws A, e, A (base letter, one warning); before, "AAA".
lb() { printf 'IN;SP1;PU0,0;%s' "$1" > "$T/l.hpgl"; "$M" import "$T/l.hpgl" -o "$T/$2.meta" 2> "$T/$2.err"; }
lb "CA7;LBA$(printf '\016')A$(printf '\017')A$(printf '\003');" cs7
lb "LBAeA$(printf '\003');" cs7ref
lb "LBAAA$(printf '\003');" cs7ascii
cmp -s "$T/cs7.meta" "$T/cs7ref.meta" && ! cmp -s "$T/cs7.meta" "$T/cs7ascii.meta" &&
	grep -q 'l.hpgl: byte 17: character set 7: accented letters drawn as their base letters' "$T/cs7.err" &&
	ok "CA7 + SO: Roman-8's e circumflex drawn as e, with a warning naming the label's byte" || notok "CA7: $(cat "$T/cs7.err")"
# CS277 (HP-GL/2's number for Roman-8): 8-bit 0xc1 0xe2 (e circumflex, a tilde) as "ea"
lb "CS277;LB$(printf '\301\342\003');" r8
lb "LBea$(printf '\003');" r8ref
cmp -s "$T/r8.meta" "$T/r8ref.meta" && ok "CS277 (Roman-8): 8-bit accented letters as their base letters" || notok "CS277"
# a symbol the stroke font has no glyph for (Roman extension 0x3b, the pound sign): the box, warned
lb "CS7;LB$(printf ';\003');" box
grep -q 'character set 7: a character the stroke font cannot draw, drawn as the replacement box' "$T/box.err" &&
	ok "CS7: the pound sign drawn as the replacement box, with a warning" || notok "CS7 box: $(cat "$T/box.err")"
# a set the import does not know (5): drawn as ASCII, with a warning
lb "CS5;LBABC$(printf '\003');" cs5
grep -q 'character set 5: not a set the import knows' "$T/cs5.err" && ok "CS5: unknown set drawn as ASCII with a warning" || notok "CS5: $(cat "$T/cs5.err")"

# ---- the shared corpus: tolerant and strict reads agree, without a warning -------------------
if [ ! -d ../shared/corpus/hpgl ]; then
	echo "SKIP corpus-tolerant: ../shared/corpus absent"
	ok "corpus-tolerant # SKIP ../shared/corpus absent"
else
	n=0 bad=""
	for f in ../shared/corpus/hpgl/*; do
		case $f in *.md) continue ;; esac
		b=$(basename "$f")
		"$M" import "$f" -o "$T/c1.meta" 2> "$T/c1.err" && "$M" import --strict "$f" -o "$T/c2.meta" 2> /dev/null &&
			cmp -s "$T/c1.meta" "$T/c2.meta" && [ ! -s "$T/c1.err" ] || bad="$bad $b"
		n=$((n + 1))
	done
	[ -z "$bad" ] && [ $n -ge 10 ] && ok "corpus: $n files import tolerantly without a warning, as --strict does" || notok "corpus: differs or warns:$bad"
fi
done_tests

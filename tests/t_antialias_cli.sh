#!/bin/sh
# t_antialias_cli.sh: --antialias[=K], the common option of every raster program (drivers/cli/cli.c):
# it is -O antialias=K, K=1 is the exact mode, edge pixels get partial coverage, a half-covered
# pixel is the linear-light midpoint, it reaches locus-vga, locus-xga and locus-film, and bad
# factors are refused in one line with 64.
. tests/lib.sh
R="$BIN/locus-raster"
M=fixtures/meta
"$R" -f ppm -o "$T/exact.ppm" $M/strokes.meta
"$R" -f ppm --antialias -o "$T/aa.ppm" $M/strokes.meta
"$BIN/locus-play" -d ppm -O antialias=4 -o "$T/play4.ppm" $M/strokes.meta
same_file "--antialias (default K 4) is -O antialias=4" "$T/aa.ppm" "$T/play4.ppm"
"$R" -f ppm --antialias 3 -o "$T/aa3s.ppm" $M/strokes.meta
"$R" -f ppm --antialias=3 -o "$T/aa3.ppm" $M/strokes.meta
same_file "--antialias 3 (a separate word) is --antialias=3" "$T/aa3s.ppm" "$T/aa3.ppm"
# K = 1 (and 0) is the exact mode, byte for byte, on every fixture
bad=""
mkdir -p "$T/e" "$T/k1" "$T/k0"
for m in $M/*.meta; do
	n=$(basename "$m" .meta)
	"$R" -f ppm -o "$T/e/$n.ppm" "$m" && "$R" -f ppm --antialias=1 -o "$T/k1/$n.ppm" "$m" &&
		"$R" -f ppm --antialias 0 -o "$T/k0/$n.ppm" "$m" || bad="$bad $n(exit)"
done
diff -r "$T/e" "$T/k1" > /dev/null && diff -r "$T/e" "$T/k0" > /dev/null || bad="$bad (some pages differ)"
[ -z "$bad" ] && ok "--antialias=1 and 0 equal the exact mode on every fixture (every page)" || notok "K=1/0 differ:$bad"
# an input file whose name is not a number is still the input
"$R" -f ppm --antialias $M/strokes.meta > "$T/aa-in.ppm"
same_file "--antialias IN.meta reads IN.meta with the default K" "$T/aa-in.ppm" "$T/aa.ppm"

# edge pixels: exact has two colours, anti-aliased many partial ones
colours() { pnmtoplainpnm "$1" 2>/dev/null | tail -n +4 | tr -s ' \n' '\n\n' | paste - - - | sort -u | wc -l; }
ce=$(colours "$T/exact.ppm") ca=$(colours "$T/aa.ppm")
[ "$ca" -ge $((ce + 20)) ] && ok "edge pixels are partial: $ca colours anti-aliased, $ce exact" ||
	notok "colours: exact $ce, anti-aliased $ca"

# a half-covered pixel: black fill over x 0..1.5 of a white 4x2 page; pixel column 1 is half
# black, so its value is the sRGB encoding of linear 0.5 (#bcbcbc = 188), not 128
printf 'LOCUS-META 1\npage 4 2\ncolour #ffffff\nfill\nmove 0 0\ndraw 4 0\ndraw 4 2\ndraw 0 2\nend\ncolour #000000\nfill\nmove 0 0\ndraw 1.5 0\ndraw 1.5 2\ndraw 0 2\nend\nend-page\n' > "$T/half.meta"
for k in 2 4 8; do
	"$R" -f ppm --antialias=$k -o "$T/half$k.ppm" "$T/half.meta"
	v=$(pnmtoplainpnm "$T/half$k.ppm" | tail -n +4 | tr -s ' \n' '\n\n' | grep . | head -12 | tr '\n' ' ')
	[ "$v" = "0 0 0 188 188 188 255 255 255 255 255 255 " ] && ok "K=$k: a half-covered pixel is 188 (linear-light midpoint), full ones exact" ||
		notok "K=$k: first row $v"
done

# the option reaches the framebuffer programs and the film recorder through cli/cli.c
for p in vga xga; do
	"$BIN/locus-$p" -f dump -o "$T/$p-e.dump" $M/strokes.meta &&
		"$BIN/locus-$p" -f dump --antialias -o "$T/$p-a.dump" $M/strokes.meta &&
		"$BIN/locus-play" -d $p -O format=dump,antialias=4 -o "$T/$p-p.dump" $M/strokes.meta
	if cmp -s "$T/$p-e.dump" "$T/$p-a.dump"; then notok "locus-$p --antialias changes the picture"
	else ok "locus-$p --antialias changes the picture"; fi
	same_file "locus-$p --antialias is locus-play -d $p -O antialias=4" "$T/$p-a.dump" "$T/$p-p.dump"
done
SOURCE_DATE_EPOCH=0 "$BIN/locus-film" --size 200x150 -f dpx16 --antialias=3 -o "$T/f3.dpx" $M/strokes.meta &&
	SOURCE_DATE_EPOCH=0 "$BIN/locus-film" --size 200x150 -f dpx16 -O antialias=3 -o "$T/f3o.dpx" $M/strokes.meta
same_file "locus-film --antialias=3 is -O antialias=3 (one option, the common one)" "$T/f3.dpx" "$T/f3o.dpx"

# refusals: one line, 64, no output file
for k in 17 x 2x; do
	msg=$("$R" --antialias=$k -o "$T/bad-$k.png" $M/strokes.meta 2>&1); st=$?
	[ "$st" = 64 ] && [ "$(printf '%s\n' "$msg" | wc -l)" = 1 ] && [ ! -e "$T/bad-$k.png" ] &&
		ok "--antialias=$k refused (64, one line: $msg)" || notok "--antialias=$k: exit $st, '$msg'"
done
"$BIN/locus-raster" --help | grep -q -- "--antialias" && "$BIN/locus-vga" --help | grep -q -- "--antialias" &&
	ok "--help of locus-raster and locus-vga describes --antialias" || notok "--help lacks --antialias"
done_tests

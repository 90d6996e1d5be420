#!/bin/sh
# t_hpgl.sh: locus-hpgl: goldens byte for byte, what hp2xx makes of every output (no complaints,
# the line geometry of locus-raster's picture), receiver limits, options, reports, bad input.
. tests/lib.sh
P=$BIN/locus-hpgl
G=fixtures/hpgl
check "--help" "$P" --help
"$P" --version | grep -q "^locus-hpgl [0-9]" && ok "--version" || notok "--version"
"$P" --list-profiles > "$T/profiles"
n=0
for p in 7475a 7550a draftpro hpgl2 cutter; do grep -q "^$p " "$T/profiles" && n=$((n + 1)); done
[ $n = 5 ] && ok "--list-profiles names the five built-in profiles" || notok "--list-profiles: $(cat "$T/profiles")"

# ---- goldens ---------------------------------------------------------------
grep -v '^#' $G/goldens.txt | while IFS='|' read -r name args in; do
	# shellcheck disable=SC2086
	"$P" $args "$in" -o "$T/$name" 2> "$T/err"
	same_file "golden $name" "$G/$name" "$T/$name"
done > "$T/golden.log"
cat "$T/golden.log"
grep -q '^not ok' "$T/golden.log" && FAILED=1
"$P" < fixtures/meta/strokes.meta > "$T/stdin.hpgl"
same_file "stdin to stdout" $G/strokes.hpgl.7475a.hpgl "$T/stdin.hpgl"
"$BIN/locus-play" -d hpgl -O profile=hpgl2 fixtures/meta/strokes.meta -o "$T/play.hpgl"
same_file "locus-play -d hpgl -O profile=hpgl2 = locus-hpgl --profile hpgl2" $G/strokes.hpgl.hpgl2.hpgl "$T/play.hpgl"

# ---- hp2xx reads every output without complaint --------------------------------
complaints() {
	hp2xx -m png -f /dev/null "$1" 2>&1 | grep -E "ignored|Unexpected" | grep -vE "(ignored|event\(s\)):[[:space:]]*0[[:space:]]*$"
}
for in in fixtures/contour/trifocal.meta fixtures/render/sum-contour.meta fixtures/render/voronoi-mixed.meta \
		fixtures/render/trifocal-octree.meta; do
	b=$(basename "$in" .meta)
	for prof in 7475a 7550a draftpro hpgl2 cutter; do
		"$P" --profile $prof --fit yes "$in" -o "$T/$b.$prof.hpgl" 2>/dev/null || notok "$b $prof: exit $?"
	done
done
"$P" --profile hpgl2 --fill native fixtures/meta/fills.meta -o "$T/fills.native.hpgl" 2>/dev/null
"$P" --profile hpgl2 fixtures/meta/fills.meta -o "$T/fills.hatch.hpgl" 2>/dev/null
"$P" --text label fixtures/meta/text.meta -o "$T/text.label.hpgl" 2>/dev/null
"$P" --profile hpgl2 -O pcl=yes fixtures/meta/text.meta -o "$T/text.pcl.hpgl" 2>/dev/null
"$P" --profile hpgl2 fixtures/meta/text.meta -o "$T/text.nopcl.hpgl" 2>/dev/null
bad=""
for f in $G/*.hpgl "$T"/*.hpgl; do
	c=$(complaints "$f")
	[ -n "$c" ] && bad="$bad $(basename "$f"): $c;"
done
[ -z "$bad" ] && ok "hp2xx reads $(ls $G/*.hpgl "$T"/*.hpgl | wc -l) outputs with nothing ignored or unexpected" || notok "hp2xx complains:$bad"

# ---- receiver limits: integer units, short lists, SP0 at the end ------------------
lim_ok=1
for f in "$T"/*.7475a.hpgl "$T"/*.cutter.hpgl "$T"/*.hpgl2.hpgl; do
	case $f in *7475a*) max=32 ;; *cutter*) max=16 ;; *) max=256 ;; esac
	# PU/PD: at most max pairs, integers only; PE: at most max pairs (counted by the reader's
	# rule: a pair is two terminating digits, base 32, bytes 95..126)
	r=$(tr ';' '\n' < "$f" | awk -v max="$max" '
		/^P[UD]/ { s = substr($0, 3); if (s ~ /[.eE]/) bad = bad " non-integer " $0;
			n = split(s, a, ","); if (n > 2 * max) bad = bad " " n / 2 " pairs" }
		/^PE/ { t = 0; for (i = 3; i <= length($0); i++) { c = substr($0, i, 1); if (c >= "_" && c <= "~") t++ }
			if (t > 2 * max) bad = bad " PE " t / 2 " pairs" }
		END { print bad }')
	[ -n "$r" ] && { lim_ok=0; echo "# $f:$r"; }
	tail -c 8 "$f" | grep -q "SP0;" || { lim_ok=0; echo "# $f does not end with SP0"; }
	# the 7475A's 1 KB buffer: no command longer than half of it
	case $f in *7475a*) tr ';' '\n' < "$f" | awk 'length($0) > 512 { bad = 1 } END { exit bad }' ||
		{ lim_ok=0; echo "# $f: a command longer than 512 bytes"; } ;; esac
done
[ $lim_ok = 1 ] && ok "integer plotter units, lists within 32 (7475A, commands under 512 bytes) / 16 (cutter) / 256 (PE) pairs, SP0 at the end" || notok "receiver limits"
awk 'END { exit !(NR > 10) } !/;$/ { bad = 1; exit 1 }' "$T/trifocal.cutter.hpgl" && ok "cutter: one command per line" || notok "cutter: commands without a newline"
grep -q "PE7" "$T/trifocal.hpgl2.hpgl" && ! grep -q "PE" "$T/trifocal.7475a.hpgl" && ok "HP-GL/2 uses PE, HP-GL does not" || notok "PE use"
grep -q "FP" "$T/fills.native.hpgl" && ! grep -q "FP" "$T/fills.hatch.hpgl" && ok "fill=native writes FP; hatching does not" || notok "FP use"
"$P" --fill native fixtures/meta/f-test.meta -o "$T/f.ra.hpgl" 2>/dev/null
[ "$(grep -o 'RA[0-9]*,[0-9]*' "$T/f.ra.hpgl" | wc -l)" = 2 ] && grep -q "FT1" "$T/f.ra.hpgl" && ! grep -q "FP" "$T/f.ra.hpgl" &&
	ok "fill=native on HP-GL: the F's two rectangles as FT1/RA, nothing as FP" || notok "RA fills: $(grep -o 'RA[^;]*' "$T/f.ra.hpgl")"
grep -q "LB" "$T/text.label.hpgl" && grep -q "SI" "$T/text.label.hpgl" && ok "text=label writes SI and LB" || notok "labels"
head -c 5 "$T/text.pcl.hpgl" | od -c | grep -q '033   %   -   1   B' && tail -c 4 "$T/text.pcl.hpgl" | od -c | grep -q '033   %   0   A' &&
	[ "$("$P" --analyse "$T/text.pcl.hpgl" | sed 's/^analyse [^:]*://')" = "$("$P" --analyse "$T/text.nopcl.hpgl" | sed 's/^analyse [^:]*://')" ] &&
	ok "pcl=yes: ESC %-1B ... ESC %0A around the same HP-GL/2" || notok "pcl framing"
# relative coordinates where shorter: the file is shorter than with absolute coordinates alone
abs=$(tr ';' '\n' < "$T/trifocal.7475a.hpgl" | grep -c '^PR')
[ "$abs" -gt 0 ] && ok "PR is used ($abs switches)" || notok "no PR"

# ---- hp2xx draws the lines of locus-raster's picture ----------------------------------
# lines only: fills, clears, spans and images left out of the meta file
lines_only() {
	awk 'skip { if ($1 == "end") skip = 0; next } $1 == "fill" { skip = 1; next }
		$1 == "clear" || $1 == "span" || $1 == "image" || $1 == "row" { next } { print }' "$1"
}
# ink IN OUT: white where there is ink
ink() { convert "$1" -colorspace gray -threshold 97% -negate "$2"; }
# outside A B: the share of A's ink farther than 2 pixels from B's ink
outside() {
	convert "$2" -morphology Dilate Disk:2 "$T/dil.png"
	a=$(convert "$1" -format "%[fx:mean]" info:)
	o=$(convert "$1" \( "$T/dil.png" -negate \) -compose Multiply -composite -format "%[fx:mean]" info:)
	awk -v a="$a" -v o="$o" 'BEGIN { printf "%.4f", (a > 0 ? o / a : 1) }'
}
for job in contour/trifocal:7475a render/trifocal-wireframe:7475a render/sum-contour:7475a meta/strokes:7475a \
		contour/trifocal:hpgl2 render/trifocal-wireframe:cutter; do
	in=fixtures/${job%:*}.meta prof=${job#*:}
	b=$(basename "$in" .meta)
	[ "$prof" = 7475a ] || b=$b-$prof
	lines_only "$in" > "$T/$b.lines.meta"
	"$BIN/locus-raster" "$T/$b.lines.meta" -o "$T/$b.r.png"
	# (the cutter's knife paths swing 0.25 mm, under a pixel here, about the lines)
	"$P" --stats --profile "$prof" "$T/$b.lines.meta" -o "$T/$b.lines.hpgl" 2> "$T/stats"
	box=$(sed -n 's/.*box \([-0-9,]*\).*/\1/p' "$T/stats" | head -1)
	set -- $(sed -n 's/^page \([0-9]*\) \([0-9]*\).*/\1 \2/p' "$in" | head -1)
	W=$1 H=$2
	x0=${box%%,*}; r=${box#*,}; y0=${r%%,*}; r=${r#*,}; x1=${r%%,*}; y1=${r#*,}
	# hp2xx at 100 dpi over the page's box, so that one pixel is one pixel; it adds a margin
	hp2xx -q -m png -d 100 -x "$x0" -X "$x1" -y "$y0" -Y "$y1" -w "$(awk -v w="$W" 'BEGIN { print w * 0.254 }')" \
		-h "$(awk -v h="$H" 'BEGIN { print h * 0.254 }')" -f "$T/$b.h.png" "$T/$b.lines.hpgl" 2>/dev/null
	convert "$T/$b.h.png" -crop "${W}x${H}+1+2" +repage "$T/$b.hc.png"
	ink "$T/$b.r.png" "$T/$b.ra.png"
	ink "$T/$b.hc.png" "$T/$b.ha.png"
	o1=$(outside "$T/$b.ra.png" "$T/$b.ha.png")
	o2=$(outside "$T/$b.ha.png" "$T/$b.ra.png")
	awk -v a="$o1" -v b="$o2" 'BEGIN { exit !(a <= 0.03 && b <= 0.03) }' &&
		ok "$b: hp2xx's lines lie on locus-raster's ($o1 of the raster's ink and $o2 of hp2xx's farther than 2 px)" ||
		notok "$b: hp2xx and locus-raster differ ($o1 / $o2 of the ink farther than 2 px)"
done

# the comparison can fail: the picture moved by 4 pixels, or another picture
convert "$T/trifocal.ha.png" -roll +4+0 "$T/moved.png"
o3=$(outside "$T/trifocal.ra.png" "$T/moved.png")
o4=$(outside "$T/sum-contour.ra.png" "$T/strokes.ha.png" 2>/dev/null)
awk -v a="$o3" -v b="$o4" 'BEGIN { exit !(a > 0.1 && b > 0.1) }' && ok "the line comparison notices a 4-pixel shift ($o3) and another picture ($o4)" ||
	notok "the line comparison is blind ($o3, $o4)"

# ---- reports --------------------------------------------------------------------
"$P" --estimate fixtures/contour/trifocal.meta > "$T/est" 2> "$T/est.err"
grep -q "^estimate page 1 total: " "$T/est" && grep -q "^estimate page 1 pen 1: " "$T/est" && ! grep -q "IN;" "$T/est" &&
	ok "--estimate without -o: the plot time per pen and in total, no HP-GL" || notok "--estimate: $(cat "$T/est")"
"$P" -v fixtures/contour/trifocal.meta -o "$T/v.hpgl" 2> "$T/v.err"
grep -q "pen-up travel .* mm -> .* mm.*pen lifts.*pen changes" "$T/v.err" && ok "-v reports travel before/after, lifts, changes" || notok "-v: $(cat "$T/v.err")"
"$P" --no-optimize --stats fixtures/contour/trifocal.meta -o "$T/n.hpgl" 2> "$T/n.err"
opt=$(sed -n 's/.*pen-up travel \([0-9.]*\) mm -> \([0-9.]*\) mm.*/\1 \2/p' "$T/v.err" | head -1)
keep=$(sed -n 's/.*pen-up travel \([0-9.]*\) mm -> \([0-9.]*\) mm.*/\1 \2/p' "$T/n.err" | head -1)
awk -v o="$opt" -v k="$keep" 'BEGIN { split(o, x, " "); split(k, y, " "); exit !(x[2] < x[1] / 2 && y[1] == y[2] && x[2] < y[2] / 2) }' &&
	ok "the optimiser halves the pen-up travel at least ($opt mm); --no-optimize keeps the file's order ($keep mm)" ||
	notok "travel: optimised $opt, kept $keep"
"$P" --raster skip fixtures/meta/image.meta -o "$T/skip.hpgl" 2> "$T/skip.err"
[ "$(grep -c 'warning: raster content' "$T/skip.err")" = 1 ] && ok "--raster skip: one warning" || notok "--raster skip: $(cat "$T/skip.err")"
"$P" fixtures/meta/multipage.meta -o "$T/m.hpgl" 2>/dev/null
m_ok=1
for k in 001 002 003; do head -c 3 "$T/m-$k.hpgl" | grep -q "IN;" && tail -c 4 "$T/m-$k.hpgl" | grep -q "SP0;" || m_ok=0; done
[ $m_ok = 1 ] && [ ! -f "$T/m.hpgl" ] && ok "multi-page: one HP-GL file per page" || notok "multi-page: $(ls "$T" | grep '^m')"
printf 'name = tiny\nbase = 7475a\nmax-pairs = 4\nclip.a4 = 0 0 4000 3000\n' > "$T/tiny.prof"
printf 'papers = a4\n' >> "$T/tiny.prof"
"$P" --profile "$T/tiny.prof" fixtures/contour/trifocal.meta -o "$T/tiny.hpgl" 2>/dev/null &&
	tr ';' '\n' < "$T/tiny.hpgl" | awk '/^PD/ { if (split(substr($0, 3), a, ",") > 8) bad = 1 } END { exit bad }' &&
	ok "a profile file: its list limit is kept" || notok "profile file"
printf '1=black\n# the fine pen\n2=red:0.1mm\n' > "$T/pens.txt"
"$P" --pens "$T/pens.txt" fixtures/meta/strokes.meta -o "$T/pens.hpgl" && grep -q "SP2" "$T/pens.hpgl" && ! grep -q "SP3" "$T/pens.hpgl" &&
	ok "--pens FILE: only its pens are used" || notok "--pens FILE"

# ---- memory: --no-optimize streams (RSS does not grow with the page), the optimiser holds the page
gen_page() {   # N: a page of N random-walk strokes of 10 points in 4 colours
	awk -v n="$1" 'BEGIN { srand(7); print "LOCUS-META 1"; print "page 1024 768"
		for (i = 0; i < n; i++) { printf "colour #%s\nstroke\n", (i % 4 == 0 ? "000000" : i % 4 == 1 ? "d02020" : i % 4 == 2 ? "2050c0" : "20a040")
			x = rand() * 1000; y = rand() * 700; printf "move %.3f %.3f\n", x, y
			for (k = 0; k < 9; k++) { x += rand() * 10 - 5; y += rand() * 10 - 5; printf "draw %.3f %.3f\n", x, y }
			print "end" }
		print "end-page" }'
}
# (not under ASan: its quarantine keeps freed blocks, so RSS says nothing about the program)
if [ -x /usr/bin/time ] && [ "${SANITIZE:-}" != 1 ]; then
	gen_page 5000 > "$T/m1.meta"
	gen_page 40000 > "$T/m8.meta"
	rss() { /usr/bin/time -f %M -o "$T/rss" "$P" "$@" -o /dev/null 2>/dev/null; cat "$T/rss"; }
	s1=$(rss --no-optimize "$T/m1.meta") s8=$(rss --no-optimize "$T/m8.meta")
	o1=$(rss "$T/m1.meta") o8=$(rss "$T/m8.meta")
	awk -v a="$s1" -v b="$s8" -v c="$o1" -v d="$o8" 'BEGIN { exit !(b < 1.25 * a && d > b) }' &&
		ok "--no-optimize streams: peak RSS $s1 KB at 5,000 strokes, $s8 KB at 40,000 (optimised: $o1 / $o8 KB, the page held)" ||
		notok "memory: streaming $s1 -> $s8 KB, optimised $o1 -> $o8 KB"
fi

# ---- bad input: one line, an exit status, no output ------------------------------------
bad_case() {   # STATUS PATTERN DESC ARGS...
	st=$1 pat=$2 d=$3
	shift 3
	rm -f "$T/bad.hpgl"
	"$P" "$@" -o "$T/bad.hpgl" 2> "$T/bad.err"
	r=$?
	if [ "$r" = "$st" ] && grep -q -- "$pat" "$T/bad.err" && [ "$(wc -l < "$T/bad.err")" = 1 ] && [ ! -f "$T/bad.hpgl" ]; then
		ok "$d: exit $st, one line, no output"
	else
		notok "$d: exit $r, $(cat "$T/bad.err"), output $(ls "$T/bad.hpgl" 2>/dev/null)"
	fi
}
bad_case 65 "bad-colour.meta:" "bad meta file" fixtures/bad/bad-colour.meta
bad_case 66 "none.meta" "missing input" "$T/none.meta"
bad_case 64 "unknown profile 'frob'" "unknown profile" --profile frob fixtures/meta/f-test.meta
printf 'name = x\nspeed-down = fast\n' > "$T/bad.prof"
bad_case 64 "bad.prof:2:1: speed-down" "bad profile file (file:line:col)" --profile "$T/bad.prof" fixtures/meta/f-test.meta
bad_case 64 "nope.prof" "missing profile file" --profile "$T/nope.prof" fixtures/meta/f-test.meta
bad_case 64 "unknown colour" "bad pen colour" --pens 1=blak fixtures/meta/f-test.meta
printf '1=black\n2=red:wide\n' > "$T/bad.pens"
bad_case 65 "bad.pens: pens: '2=red:wide'" "bad pen file" --pens "$T/bad.pens" fixtures/meta/f-test.meta
bad_case 66 "nope.pens" "missing pen file" --pens "$T/nope.pens" fixtures/meta/f-test.meta
bad_case 64 "pen 9 does not fit" "more pens than slots" --pens 1=black,9=red fixtures/meta/f-test.meta
# The 2-opt budget is work, not clock time: a budget far too small for the contour plot to
# converge (10 us of a reference core: 1,250 moves) stops at the same move every run, busy or
# not, so the bytes are the same twice and differ from the converged default's.
for k in 1 2; do "$P" -O budget=0.00001 fixtures/contour/trifocal.meta -o "$T/budget$k.hpgl" 2>/dev/null; done
"$P" fixtures/contour/trifocal.meta -o "$T/budget-full.hpgl" 2>/dev/null
cmp -s "$T/budget1.hpgl" "$T/budget2.hpgl" && ! cmp -s "$T/budget1.hpgl" "$T/budget-full.hpgl" \
	&& ok "a 2-opt budget that runs out stops at the same point every run (deterministic bytes)" \
	|| notok "2-opt budget: the cut-short runs differ from each other, or the budget did not bite"

bad_case 64 "unknown option 'colour'" "unknown -O key" -O colour=red fixtures/meta/f-test.meta
bad_case 64 "option rotate" "bad rotation" --rotate 45 fixtures/meta/f-test.meta
bad_case 64 "pcl=yes frames HP-GL/2" "PCL framing on HP-GL" -O pcl=yes fixtures/meta/f-test.meta
bad_case 64 "no paper" "paper the profile lacks" -O profile="$T/tiny.prof",paper=a3 fixtures/meta/f-test.meta
# A failing run prints only its error, one line; warnings are for runs that succeed. A file
# whose background warning comes before its error (a non-white clear, then a bad statement)
# printed both; the same background on a good file still warns.
printf 'LOCUS-META 1\npage 10 10\nclear #ff0000\nstroke\nmove 1 1\nfrobnicate 2 2\nend\nend-page\n' > "$T/warnbad.meta"
"$P" "$T/warnbad.meta" -o "$T/warnbad.hpgl" 2> "$T/warnbad.err"; rc=$?
[ $rc = 65 ] && [ "$(wc -l < "$T/warnbad.err")" = 1 ] && grep -q "warnbad.meta:6:1: expected a statement keyword" "$T/warnbad.err" \
	&& [ ! -e "$T/warnbad.hpgl" ] && ok "a failing run with a warning before its error: exit 65, only the error: $(cat "$T/warnbad.err")" \
	|| notok "warning before error: exit $rc: $(cat "$T/warnbad.err")"
printf 'LOCUS-META 1\npage 10 10\nclear #ff0000\nstroke\nmove 1 1\ndraw 2 2\nend\nend-page\n' > "$T/warnok.meta"
"$P" "$T/warnok.meta" -o "$T/warnok.hpgl" 2> "$T/warnok.err"; rc=$?
[ $rc = 0 ] && grep -q "^locus-hpgl: warning: a non-white page background" "$T/warnok.err" \
	&& ok "the same background on a file that succeeds still warns: $(cat "$T/warnok.err")" || notok "warning on success: exit $rc: $(cat "$T/warnok.err")"
done_tests

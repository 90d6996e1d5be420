#!/bin/sh
# t_hpgl_caps.sh: wide lines on a plotter keep their caps (issue 22, item 4). A width-8 bar from
# x 16 to 48 with butt, round and square caps is drawn as parallel pen passes; the ink of the
# passes (their ends plus the pen's half width) must reach where locus-raster's cap ends: x 16-48
# for butt (the round pen tip overshoots it by its half width), 12-52 for round and square caps;
# a round cap's outer passes are shorter than its centre pass (the half disc), a square cap's not.
# (The passes are ordered by the optimiser: lengths are compared as a set.)
. tests/lib.sh
P=$BIN/locus-hpgl
# extents FILE: for the pen-down segments of an HP-GL file (PU/PD/PA/PR with coordinate
# lists, as locus-hpgl writes them): "xmin xmax" of all draws, then the length of each
# horizontal draw in the order drawn
extents() {
	tr -d '\n' < "$1" | tr ';' '\n' | awk -F, '
	{ c = substr($0, 1, 2); a = substr($0, 3); n = a == "" ? 0 : split(a, v, ",")
	  if (c == "PA") rel = 0; else if (c == "PR") rel = 1; else if (c == "IN") { rel = 0; x = y = 0 }
	  if (c != "PU" && c != "PD" && c != "PA" && c != "PR") next
	  if (c == "PU") down = 0; else if (c == "PD") down = 1
	  for (i = 1; i + 1 <= n; i += 2) {
		nx = rel ? x + v[i] : v[i]; ny = rel ? y + v[i + 1] : v[i + 1]
		if (down) { if (!seen || x < lo) lo = x; if (!seen || nx < lo) lo = nx
			if (!seen || x > hi) hi = x; if (!seen || nx > hi) hi = nx; seen = 1
			if (ny == y) len = len " " (nx > x ? nx - x : x - nx) }
		x = nx; y = ny } }
	END { print lo, hi len }'
}
# 1 px = 25.4 / 96 mm = 10.5833 plotter units; the 7475A's default pen is 0.3 mm = 12 units
for cap in butt round square; do
	printf 'LOCUS-META 1\npage 64 32\nwidth 8\ncap %s\nstroke\nmove 16 16\ndraw 48 16\nend\nend-page\n' $cap > "$T/cap-$cap.meta"
	"$P" --fit no "$T/cap-$cap.meta" -o "$T/cap-$cap.hpgl" || { notok "$cap: locus-hpgl failed"; continue; }
	set -- $(extents "$T/cap-$cap.hpgl")
	lo=$1 hi=$2; shift 2
	ink=$(awk -v a="$lo" -v b="$hi" 'BEGIN { printf "%.1f", (b - a + 12) / 10.5833 }')
	case $cap in
	butt) want=33.1 ;;      # 32 px and the pen's 0.3 mm
	*) want=40 ;;
	esac
	if awk -v i="$ink" -v w="$want" 'BEGIN { exit !(i >= w - 0.35 && i <= w + 0.35) }'; then
		ok "$cap cap: the passes' ink spans $ink px (locus-raster: $want)"
	else notok "$cap cap: the passes' ink spans $ink px where locus-raster draws $want"; fi
	min=$(echo "$@" | tr ' ' '\n' | sort -n | head -1) max=$(echo "$@" | tr ' ' '\n' | sort -n | tail -1)
	case $cap in
	round) [ "$min" -lt $((max - 20)) ] && ok "round cap: the outer passes ($min) shorter than the centre ($max): the half disc" ||
		notok "round cap: passes from $min to $max long" ;;
	*) [ "$min" -ge $((max - 2)) ] && ok "$cap cap: every pass as long ($min to $max)" ||
		notok "$cap cap: passes from $min to $max long" ;;
	esac
done
# a closed path has no caps: a width-8 square outline with round caps is drawn as before
printf 'LOCUS-META 1\npage 64 64\nwidth 8\ncap round\nstroke\nmove 16 16\ndraw 48 16\ndraw 48 48\ndraw 16 48\nclose\nend\nend-page\n' > "$T/sq.meta"
printf 'LOCUS-META 1\npage 64 64\nwidth 8\nstroke\nmove 16 16\ndraw 48 16\ndraw 48 48\ndraw 16 48\nclose\nend\nend-page\n' > "$T/sqb.meta"
"$P" --fit no "$T/sq.meta" -o "$T/sq.hpgl" && "$P" --fit no "$T/sqb.meta" -o "$T/sqb.hpgl" &&
	same_file "closed outlines have no caps: round and butt give the same HP-GL" "$T/sq.hpgl" "$T/sqb.hpgl"
done_tests

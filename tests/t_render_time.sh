#!/bin/sh
# t_render_time.sh: the time parameter t (expressions, weights, element positions, the view) and
# locus-render --frames: one page per frame, frames independent, so parts rendered apart and
# joined equal one run.
. tests/lib.sh
R="$BIN/locus-render"
printf 'view\n  eye 0 1 -6+0*t\n  size 48 36\nend\nlight point 3 6 -5\nobject a\n  point -1+0.2*t 0 0 weight 1+0.1*t\n  point 1 0 0\n  point 0 1.2 0.3\n  c 3.4+0.05*t + 0.02*t*y\nend\n' > "$T/anim.scene"
"$R" "$T/anim.scene" --frames 6 -o "$T/all.meta" --quiet; rc=$?
[ "$rc" = 0 ] && [ "$(grep -c '^page' "$T/all.meta")" = 6 ] && "$BIN/locus-meta" check "$T/all.meta" > /dev/null 2>&1 \
	&& ok "--frames 6: six pages, a valid meta file" || notok "--frames 6: exit $rc, $(grep -c '^page' "$T/all.meta") pages"
# frame k equals the scene with t replaced by k by hand
printf 'view\n  eye 0 1 -6\n  size 48 36\nend\nlight point 3 6 -5\nobject a\n  point -0.4 0 0 weight 1.3\n  point 1 0 0\n  point 0 1.2 0.3\n  c 3.55 + 0.06*y\nend\n' > "$T/f3.scene"
"$R" "$T/f3.scene" -o "$T/f3.meta" --quiet
"$BIN/locus-raster" "$T/all.meta" -o "$T/fr.png" > /dev/null 2>&1
"$BIN/locus-raster" "$T/f3.meta" -o "$T/f3.png" > /dev/null 2>&1
"$BIN/locus-diff" "$T/fr-004.png" "$T/f3.png" > /dev/null 2>&1 && ok "frame 3 is the scene at t = 3 (weight, position, c)" || notok "frame 3 differs from t = 3 by hand"
"$BIN/locus-diff" "$T/fr-001.png" "$T/fr-006.png" > /dev/null 2>&1 && notok "frames 0 and 5 are the same picture" || ok "the frames change with t"
# split across machines: two ranges, joined by dropping the second part's header line
"$R" "$T/anim.scene" --frames 0-3 -o "$T/p1.meta" --quiet && "$R" "$T/anim.scene" --frames 4-5 -o "$T/p2.meta" --quiet --threads 1
{ cat "$T/p1.meta"; tail -n +2 "$T/p2.meta"; } > "$T/joined.meta"
same_file "frame ranges rendered apart and joined: the same bytes as one run" "$T/joined.meta" "$T/all.meta"
# --time-step: t = frame x DT
"$R" "$T/anim.scene" --frames 6-6 --time-step 0.5 -o "$T/h.meta" --quiet && "$BIN/locus-raster" "$T/h.meta" -o "$T/h.png" > /dev/null 2>&1
"$BIN/locus-diff" "$T/h.png" "$T/fr-004.png" > /dev/null 2>&1 && ok "--frames 6-6 --time-step 0.5 is t = 3" || notok "--time-step"
expect_exit 64 "--frames 0 refused" "$R" "$T/anim.scene" --frames 0
expect_exit 64 "--frames 5-2 refused" "$R" "$T/anim.scene" --frames 5-2
# an expression in t that leaves the range at some frame: an error naming it, no output
printf 'object a\n  point 0 0 2e5*t\n  c 1\nend\nview\n  size 8 8\nend\n' > "$T/far.scene"
"$R" "$T/far.scene" --frames 8 -o "$T/far.meta" 2> "$T/far.txt"; rc=$?
[ "$rc" = 65 ] && [ ! -e "$T/far.meta" ] && grep -q "far.scene:2:13: expected a coordinate between -1e6 and 1e6, found '2e5\*t' = 1.2e+06 at t = 6" "$T/far.txt" \
	&& ok "a coordinate out of range at frame 6: file:line:col, the value and t, no output" || notok "far: exit $rc $(cat "$T/far.txt")"
printf 'object a\n  point 0 0 x*t\n  c 1\nend\n' > "$T/xt.scene"
"$R" "$T/xt.scene" -o "$T/xt.meta" 2> "$T/xt.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "xt.scene:2:13: expected a coordinate: an expression in t alone" "$T/xt.txt" && ok "x in a position expression refused" || notok "xt: $(cat "$T/xt.txt")"
done_tests

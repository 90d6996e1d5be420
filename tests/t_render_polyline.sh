#!/bin/sh
# t_render_polyline.sh: polyline nuclei on the Voronoi page: the gallery plate renders, its
# polyline cells equal the cells of the same scene with each polyline split into segments of
# the same weight (merged), and malformed polyline lines fail located, exit 65, no output.
. tests/lib.sh
R=$BIN/locus-render
S=fixtures/scenes/voronoi-polyline.scene
"$R" "$S" -o "$T/plate.meta" 2> "$T/plate.err" && [ ! -s "$T/plate.err" ] && ok "the gallery plate renders without a word" \
	|| notok "gallery plate: $(cat "$T/plate.err")"
# cells only, no marks or boundaries: a polyline and its segments (same weight, same colour)
# must give the same picture
base='view\n  size 120 120\nend\nrender voronoi\n  window -3 -3 3 3\n  metric multiplicative\n  boundaries no\n  point -1.5 2 colour 1 0 0\n  point 2 -2 weight 0.7 colour 0 1 0\n'
printf "$base"'  polyline -2.5 -2 -1 0 0.5 -1.5 2 0.5 weight 1.4 colour 0 0 1\nend\n' > "$T/poly.scene"
printf "$base"'  segment -2.5 -2 -1 0 weight 1.4 colour 0 0 1\n  segment -1 0 0.5 -1.5 weight 1.4 colour 0 0 1\n  segment 0.5 -1.5 2 0.5 weight 1.4 colour 0 0 1\nend\n' > "$T/segs.scene"
"$R" "$T/poly.scene" -o "$T/poly.meta" && "$R" "$T/segs.scene" -o "$T/segs.meta" &&
	"$BIN/locus-diff" "$T/poly.meta" "$T/segs.meta" > "$T/ps.diff" 2>&1 &&
	ok "a polyline's cell is its segments' cells together (multiplicative): $(cat "$T/ps.diff")" ||
	notok "polyline against its segments: $(cat "$T/ps.diff")"
bad() {
	printf 'render voronoi\n  window -1 -1 1 1\n  point 0 0\n  %s\nend\n' "$2" > "$T/bad.scene"
	rm -f "$T/bad.meta"
	"$R" "$T/bad.scene" -o "$T/bad.meta" 2> "$T/bad.err"
	rc=$?
	if [ "$rc" = 65 ] && grep -q "bad.scene:$1" "$T/bad.err" && [ ! -e "$T/bad.meta" ] && [ "$(wc -l < "$T/bad.err")" = 1 ]; then
		ok "'$2' refused: $(cat "$T/bad.err")"
	else notok "'$2': exit $rc: $(cat "$T/bad.err")"; fi
}
bad "4:3: expected at least 2 points" "polyline 0.5 0.5"
bad "4:3: expected x y pairs" "polyline 0.5 0.5 0.2 0.1 0.3"
bad "4:" "polyline 0.5 0.5 0.2 x"
bad "4:.*expected 'weight', 'z', 'colour'" "polyline 0.5 0.5 0.2 0.1 weight 1 size 3"
done_tests

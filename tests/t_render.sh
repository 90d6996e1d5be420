#!/bin/sh
# t_render.sh: locus-render end to end: goldens per visualisation, determinism over thread
# counts and encodings, exit codes and messages for bad scenes, no partial output files.
. tests/lib.sh
R="$BIN/locus-render"

check "--help exits 0" "$R" --help
"$R" --version | grep -q "^locus-render [0-9]" && ok "--version prints the version" || notok "--version"
expect_exit 64 "no scene: usage" "$R"
expect_exit 64 "unknown option: usage" "$R" --frobnicate x.scene
expect_exit 64 "bad --threads: usage" "$R" --threads 0 fixtures/render/trifocal-raytrace.scene
expect_exit 66 "missing scene: no input" "$R" "$T/nonexistent.scene"

# goldens: every fixtures/render/NAME.scene renders to exactly NAME.meta
for s in fixtures/render/*.scene; do
	n=${s%.scene}
	"$R" "$s" -o "$T/g.meta" --quiet
	same_file "golden $(basename "$n")" "$T/g.meta" "$n.meta"
done

# the same bytes whatever the thread count, text or binary
S=fixtures/render/trifocal-raytrace.scene
"$R" "$S" -o "$T/t1.meta" --threads 1 --quiet
"$R" "$S" -o "$T/t2.meta" --threads 2 --quiet
"$R" "$S" -o "$T/t5.meta" --threads 5 --quiet
same_file "1 and 2 threads give the same bytes" "$T/t1.meta" "$T/t2.meta"
same_file "1 and 5 threads give the same bytes" "$T/t1.meta" "$T/t5.meta"
"$R" "$S" -o "$T/t.lmb" --binary --quiet
"$BIN/locus-meta" convert "$T/t.lmb" -o "$T/back.meta" --text
same_file "binary output converts back to the text output" "$T/back.meta" "$T/t1.meta"
"$R" - --quiet < "$S" > "$T/stdin.meta"
same_file "scene from stdin, meta to stdout" "$T/stdin.meta" "$T/t1.meta"
"$BIN/locus-meta" check "$T/t1.meta" >/dev/null 2>&1 && ok "output passes locus-meta check" || notok "locus-meta check"

# accuracy: the float render against its double-precision polish differs by <= 1 level
sed 's/^render raytrace$/render raytrace\n  refine yes/' fixtures/scenes/bench-trifocal.scene | sed 's/size 1024 768/size 256 192/' > "$T/ref.scene"
sed 's/size 1024 768/size 256 192/' fixtures/scenes/bench-trifocal.scene > "$T/def.scene"
"$R" "$T/ref.scene" -o "$T/ref.meta" --quiet && "$R" "$T/def.scene" -o "$T/def.meta" --quiet
"$BIN/locus-diff" --max-diff 1 "$T/ref.meta" "$T/def.meta" > /dev/null 2>&1 && ok "float render within one level of the double-precision reference" \
	|| notok "refine: $("$BIN/locus-diff" "$T/ref.meta" "$T/def.meta" 2>&1)"

# --stats: one line with the evaluation counts
"$R" "$S" -o "$T/s.meta" --stats 2> "$T/stats.txt"
grep -q "^stats: pixels=6912 evals=[0-9]* evals_per_pixel=[0-9.]* primary=" "$T/stats.txt" && ok "--stats line" || notok "--stats line: $(cat "$T/stats.txt")"

# the thesis' table 6.1: both cell tests in one run, cubical visiting fewer cells
printf 'object t\n  point 1 0 0\n  point -1 0 0\n  point 0 1.2 0.3\n  c 3.6\n  bound -3 -3 -3 3 3 3\nend\nrender octree\n  depth 6\n  test both\n  draw no\nend\n' > "$T/both.scene"
"$R" "$T/both.scene" -o "$T/both.meta" --stats 2> "$T/both.txt"
sv=$(grep -o ' oct_visited=[0-9]*' "$T/both.txt" | cut -d= -f2); cv=$(grep -o 'oct_cubical_visited=[0-9]*' "$T/both.txt" | cut -d= -f2)
[ -n "$sv" ] && [ -n "$cv" ] && [ "$cv" -lt "$sv" ] && ok "test both: spherical $sv cells, cubical $cv" || notok "test both: $(cat "$T/both.txt")"

# Voronoi: the metric may come after the nuclei (default weights follow it); z lifts a nucleus
printf 'view\n  size 32 32\nend\nrender voronoi\n  point 0 0 z 1\n  point 1 1 weight 2\n  point -1 1\n  metric multiplicative\nend\n' > "$T/vor.scene"
check "voronoi: metric after the nuclei, a lifted nucleus" "$R" "$T/vor.scene" -o "$T/vor.meta" --quiet

# bad scenes: one clear line, status 65, no output file left behind
printf 'view\n  eye 0 0\nend\n' > "$T/bad1.scene"
"$R" "$T/bad1.scene" -o "$T/bad1.meta" 2> "$T/err1.txt"; rc=$?
[ "$rc" = 65 ] && ok "syntax error exits 65" || notok "syntax error exit $rc"
grep -qx "$T/bad1.scene:2:10: expected an eye coordinate (a finite number), found the end of the line" "$T/err1.txt" \
	&& ok "error message names file:line:col" || notok "message: $(cat "$T/err1.txt")"
[ ! -e "$T/bad1.meta" ] && ok "no output file after an error" || notok "partial output left"
ls "$T" | grep -q "bad1.meta.tmp" && notok "temporary file left" || ok "no temporary file left"
printf 'object a\n  point 0 0 inf\n  c 1\nend\n' > "$T/bad2.scene"
expect_exit 65 "infinite coordinate refused" "$R" "$T/bad2.scene" -o "$T/bad2.meta"
printf 'object a\n  point 0 0 0\n  distance-to ghost\nend\n' > "$T/bad3.scene"
expect_exit 65 "unknown name refused" "$R" "$T/bad3.scene" -o "$T/bad3.meta"
printf 'render octree\nend\nobject m\n  plane 0 0 0 0 1 0\n  c mandelbrot 0 1 10 1 0 0 0 0 0 1 0\n  bound -1 -1 -1 1 1 1\nend\n' > "$T/bad4.scene"
"$R" "$T/bad4.scene" -o "$T/bad4.meta" 2> "$T/err4.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "Lipschitz" "$T/err4.txt" && [ ! -e "$T/bad4.meta" ] \
	&& ok "octree of a shape without a bound: clear error, no output" || notok "octree without bound: exit $rc $(cat "$T/err4.txt")"
printf '\000' > "$T/nul.scene"
expect_exit 65 "binary junk refused" "$R" "$T/nul.scene" -o "$T/nul.meta"

# degenerate model: c below the minimum of the sum -> empty picture, warnings, status 0
printf 'view\n  size 16 12\nend\nobject a\n  point 1 0 0\n  point -1 0 0\n  c 1.5\nend\n' > "$T/empty.scene"
"$R" "$T/empty.scene" -o "$T/empty.meta" 2> "$T/warn.txt"; rc=$?
[ "$rc" = 0 ] && grep -q "warning: 'a': the shape is empty" "$T/warn.txt" && grep -q "only the background" "$T/warn.txt" \
	&& ok "c below the minimum: empty picture with warnings" || notok "degenerate: exit $rc $(cat "$T/warn.txt")"
[ "$(grep -c '^row' "$T/empty.meta")" = 12 ] && ok "the empty picture still has its 12 rows" || notok "empty picture rows"
"$R" "$T/empty.scene" -o "$T/empty2.meta" --quiet 2> "$T/quiet.txt"
[ ! -s "$T/quiet.txt" ] && ok "--quiet silences warnings" || notok "--quiet printed: $(cat "$T/quiet.txt")"

# a contour map whose levels miss the field: a warning naming the scene, the page still written
printf 'view\n  size 16 16\nend\nshape s\n  point 0 0 0\nend\nrender contour\n  field s\n  levels 3 from 50 to 60\nend\n' > "$T/nolines.scene"
"$R" "$T/nolines.scene" -o "$T/nolines.meta" 2> "$T/nolines.txt"; rc=$?
[ "$rc" = 0 ] && grep -qx "$T/nolines.scene: warning: the contour map has no lines at levels 50..60" "$T/nolines.txt" \
	&& grep -q '^end-page' "$T/nolines.meta" && ok "contour levels outside the field: one warning line, a page" || notok "no-lines warning: exit $rc $(cat "$T/nolines.txt")"

# writing to a device never replaces it
"$R" "$S" -o /dev/null --quiet && [ -c /dev/null ] && ok "-o /dev/null writes through the device" || notok "/dev/null"
done_tests

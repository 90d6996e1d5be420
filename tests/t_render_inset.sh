#!/bin/sh
# t_render_inset.sh: contour/voronoi insets drawn on the previous page, the nuclei marks of Voronoi
# pages, and the Mandelbrot solid of revolution (smooth, revolve, a shape without elements).
. tests/lib.sh
R="$BIN/locus-render"
D="$BIN/locus-diff"

# a small ray-traced page, then the same page with a contour inset of 12x10 pixels at (2, 3)
base='view\n  eye 0 0 -5\n  size 40 30\nend\nbackground 0.2 0.2 0.3\nobject s\n  point 0 0 0\n  c 1.5\nend\nrender raytrace\nend\n'
printf "$base" > "$T/page.scene"
printf "${base}render contour\n  inset 2 3 12 10\n  field s\n  levels 4 from 0 to 2\n  bands yes\nend\n" > "$T/inset.scene"
"$R" "$T/page.scene" -o "$T/page.meta" --quiet && "$R" "$T/inset.scene" -o "$T/inset.meta" --quiet \
	&& ok "a scene with an inset renders" || notok "inset scene failed"
[ "$(grep -c '^page' "$T/inset.meta")" = 1 ] && [ "$(grep -c '^end-page' "$T/inset.meta")" = 1 ] \
	&& ok "the inset is drawn on the ray-traced page, not a page of its own" || notok "inset pages: $(grep -c '^page' "$T/inset.meta")"
n=$("$D" "$T/page.meta" "$T/inset.meta" 2>&1 | grep -o '[0-9]* of [0-9]* pixels differ' | cut -d' ' -f1)
[ -n "$n" ] && [ "$n" -gt 60 ] && [ "$n" -le 120 ] && ok "the inset changes at most its 12x10 pixels ($n differ)" \
	|| notok "inset differs by '$n' pixels: $("$D" "$T/page.meta" "$T/inset.meta" 2>&1)"
"$BIN/locus-raster" "$T/inset.meta" -o "$T/inset.ppm" && "$BIN/locus-raster" "$T/page.meta" -o "$T/page.ppm" \
	&& "$D" "$T/inset.ppm" "$T/page.ppm" --max-pixels 120 >/dev/null 2>&1 && ok "outside the inset the page is unchanged" \
	|| notok "the inset spilled outside its rectangle"

# two insets in a row stay on the same page; a voronoi inset marks its nuclei
printf "${base}render contour\n  inset 2 3 12 10\n  field s\nend\nrender voronoi\n  inset 20 10 16 16\n  point 0 0\n  point 1 1\n  nuclei yes\nend\n" > "$T/two.scene"
"$R" "$T/two.scene" -o "$T/two.meta" --quiet
[ "$(grep -c '^page' "$T/two.meta")" = 1 ] && [ "$(grep -c '^circle' "$T/two.meta")" = 2 ] \
	&& ok "two insets on one page, the voronoi one with its 2 nuclei as discs" || notok "two insets: $(grep -c '^page' "$T/two.meta") pages, $(grep -c '^circle' "$T/two.meta") discs"

# nuclei outside an inset's window are not marked: a point off the window draws no disc, a
# segment crossing the window's edge is cut there (its stroke ends at the inset's frame)
printf "${base}render voronoi\n  inset 2 2 20 20\n  window -1 -1 1 1\n  point 0 0\n  point 5 5\n  segment -0.5 0.5 3 0.5\n  nuclei yes\nend\n" > "$T/clip.scene"
"$R" "$T/clip.scene" -o "$T/clip.meta" --quiet
[ "$(grep -c '^circle' "$T/clip.meta")" = 1 ] && grep -q '^draw 22 17$' "$T/clip.meta" \
	&& ok "inset nuclei: only the point inside gets a disc, the segment is cut at the window's edge" \
	|| notok "inset nuclei: $(grep -c '^circle' "$T/clip.meta") discs, $(grep '^draw' "$T/clip.meta" | tail -2 | tr '\n' ' ')"

# errors: an inset outside the page, an inset in the first block, an inset on a raytrace block
printf "${base}render contour\n  inset 30 3 12 10\n  field s\nend\n" > "$T/out.scene"
"$R" "$T/out.scene" -o "$T/out.meta" 2> "$T/out.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "out.scene:12:1: expected an inset inside the 40x30 page" "$T/out.txt" && [ ! -e "$T/out.meta" ] \
	&& ok "an inset outside the page: file:line:col error, no output" || notok "inset outside: exit $rc $(cat "$T/out.txt")"
printf 'render contour\n  inset 0 0 4 4\nend\n' > "$T/first.scene"
"$R" "$T/first.scene" -o "$T/first.meta" 2> "$T/first.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "first.scene:2:3: expected a render block before" "$T/first.txt" \
	&& ok "an inset in the first block is refused" || notok "first inset: exit $rc $(cat "$T/first.txt")"
printf 'render raytrace\nend\nrender raytrace\n  inset 0 0 4 4\nend\n' > "$T/rt.scene"
expect_exit 65 "an inset on a raytrace block is refused" "$R" "$T/rt.scene" -o "$T/rt.meta"

# voronoi nuclei: off by default; 'nuclei yes' adds a disc per point and a stroke per segment
v='view\n  size 48 48\nend\nrender voronoi\n  window -2 -2 2 2\n  point -1 -1\n  point 1 0.5 weight 0.3\n  segment -1 1 0 1.5\n'
printf "${v}end\n" > "$T/v0.scene"
printf "${v}  nuclei yes\nend\n" > "$T/v1.scene"
"$R" "$T/v0.scene" -o "$T/v0.meta" --quiet; "$R" "$T/v1.scene" -o "$T/v1.meta" --quiet
[ "$(grep -c '^circle' "$T/v0.meta")" = 0 ] && [ "$(grep -c '^circle' "$T/v1.meta")" = 2 ] \
	&& grep -q '^cap round' "$T/v1.meta" && ok "nuclei yes: 2 point discs and a round-capped segment stroke, none by default" \
	|| notok "nuclei marks: $(grep -c '^circle' "$T/v0.meta") / $(grep -c '^circle' "$T/v1.meta") discs"

# the Mandelbrot solid of revolution: a shape without elements, f = -c; hits, symmetric about the
# x axis when the eye is on it (the picture is then symmetric left-right and top-bottom)
printf 'view\n  eye -6 0 0\n  look-at 0 0 0\n  size 33 33\n  fov 50\nend\nbackground 0 0 0\nobject m\n  c mandelbrot -0.2 1 40 1 0 0 -0.6 0 1 0 0 smooth revolve\n  bound -1.5 -1.3 -1.3 1.2 1.3 1.3\n  shading constant\n  colour 1 1 1\nend\nrender raytrace\nend\n' > "$T/m.scene"
"$R" "$T/m.scene" -o "$T/m.meta" --stats 2> "$T/m.txt" && "$BIN/locus-raster" "$T/m.meta" -o "$T/m.ppm"
hits=$(python3 -c "
import sys
d=open(sys.argv[1],'rb').read(); p=d.split(b'\n',3)[3]
n=33; px=[p[3*i:3*i+3] for i in range(n*n)]
white=sum(1 for q in px if q==b'\xff\xff\xff')
sym=all(px[j*n+i]==px[j*n+n-1-i]==px[(n-1-j)*n+i]==px[i*n+j] for j in range(n) for i in range(n))
print(white, 'sym' if sym else 'asym')" "$T/m.ppm" 2>&1)
case "$hits" in
	*" sym") w=${hits% sym}; [ "$w" -gt 100 ] && [ "$w" -lt 900 ] && ok "mandelbrot revolve seen along its axis: $w solid pixels, a disc symmetric about both axes and the diagonal" || notok "mandelbrot solid: $hits";;
	*) notok "mandelbrot solid seen along its axis: $hits";;
esac
! grep -q "warning" "$T/m.txt" && ok "the smooth process is sphere-traced on its distance estimate: no bracketing warning" || notok "a warning: $(cat "$T/m.txt")"
printf 'object m\n  c mandelbrot 0 1 10 1 0 0 0 0 1 0 0 smooth smooth\n  bound -1 -1 -1 1 1 1\nend\n' > "$T/mb.scene"
"$R" "$T/mb.scene" -o "$T/mb.meta" 2> "$T/mb.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "mb.scene:2:46: expected 'smooth', 'revolve', 'stepping' or the end of the line, found 'smooth'" "$T/mb.txt" \
	&& ok "a repeated mandelbrot flag is refused at its column" || notok "repeated flag: exit $rc $(cat "$T/mb.txt")"
printf 'object m\n  c 2\n  bound -1 -1 -1 1 1 1\nend\n' > "$T/ce.scene"
expect_exit 65 "no elements and a constant c refused" "$R" "$T/ce.scene" -o "$T/ce.meta"
done_tests

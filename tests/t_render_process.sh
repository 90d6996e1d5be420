#!/bin/sh
# t_render_process.sh: Mandelbrot and Julia processes sphere-traced on their Douady-Hubbard
# distance estimate: few evaluations per pixel, the same picture as the bracketing fallback,
# real shading without `smooth`.
. tests/lib.sh
R="$BIN/locus-render"

# the gallery plate (fixtures/scenes/mandelbrot.scene) at 160x120, ray-traced page only
sed -e 's/size 480 360/size 160 120/' -e '/^render contour/,$d' fixtures/scenes/mandelbrot.scene > "$T/m.scene"
# the same f with a weight-0 element: no distance estimate, so the bracketing fallback
sed -e 's/^  c mandelbrot/  point 0 0 0 weight 0\n  c mandelbrot/' "$T/m.scene" > "$T/mb.scene"
grep -q "weight 0" "$T/mb.scene" || notok "bracketing twin scene not made"
"$R" "$T/m.scene" -o "$T/m.meta" --stats 2> "$T/m.txt"; rc=$?
"$R" "$T/mb.scene" -o "$T/mb.meta" --stats --quiet 2> "$T/mb.txt"
epp=$(grep -o 'primary=[0-9.]*' "$T/m.txt" | cut -d= -f2); bpp=$(grep -o 'primary=[0-9.]*' "$T/mb.txt" | cut -d= -f2)
[ "$rc" = 0 ] && ! grep -q "bracketing" "$T/m.txt" && awk -v e="$epp" 'BEGIN { exit !(e > 0 && e <= 30) }' \
	&& ok "Mandelbrot plate: sphere-traced, $epp evaluations per pixel (bracketing: $bpp)" || notok "Mandelbrot: exit $rc, $epp per pixel: $(cat "$T/m.txt")"
awk -v e="$epp" -v b="$bpp" 'BEGIN { exit !(b >= 5 * e) }' && ok "at least 5x fewer evaluations than bracketing" || notok "evaluations $epp vs $bpp"
"$BIN/locus-diff" --max-pixels 96 "$T/m.meta" "$T/mb.meta" > "$T/md.txt" 2>&1 \
	&& ok "same picture as the bracketing fallback: $(cat "$T/md.txt" | sed 's/.*: //')" || notok "Mandelbrot picture: $(cat "$T/md.txt")"

# Julia: the basilica (k = -1) turned about the real axis
printf 'view\n  eye 0.6 2.2 -3.2\n  look-at 0 0 0\n  fov 45\n  size 120 90\nend\nlight directional -1 3 -2\nobject j\n  c julia -0.1 1 60 -1 0 1 0 0 0 0 1 0 0 smooth revolve\n  bound -1.7 -1.1 -1.1 1.7 1.1 1.1\nend\n' > "$T/j.scene"
sed -e 's/^  c julia/  point 0 0 0 weight 0\n  c julia/' "$T/j.scene" > "$T/jb.scene"
"$R" "$T/j.scene" -o "$T/j.meta" --stats 2> "$T/j.txt"; rc=$?
"$R" "$T/jb.scene" -o "$T/jb.meta" --quiet
epp=$(grep -o 'primary=[0-9.]*' "$T/j.txt" | cut -d= -f2)
[ "$rc" = 0 ] && ! grep -q "bracketing" "$T/j.txt" && awk -v e="$epp" 'BEGIN { exit !(e > 0 && e <= 30) }' \
	&& ok "Julia basilica: sphere-traced, $epp evaluations per pixel" || notok "Julia: exit $rc: $(cat "$T/j.txt")"
"$BIN/locus-diff" --max-pixels 60 "$T/j.meta" "$T/jb.meta" > "$T/jd.txt" 2>&1 \
	&& ok "Julia: same picture as bracketing: $(sed 's/.*: //' "$T/jd.txt")" || notok "Julia picture: $(cat "$T/jd.txt")"
# a k outside the Mandelbrot set (a Cantor dust): no proven bound, bracketing with a warning that says why
sed 's/-1 0 1 0 0 0/0.4 0.3 1 0 0 0/' "$T/j.scene" > "$T/jd.scene"
"$R" "$T/jd.scene" -o "$T/jdust.meta" 2> "$T/jdust.txt"
grep -q "not connected (k is outside the Mandelbrot set)" "$T/jdust.txt" && ok "disconnected Julia set: bracketing, and the warning says why" || notok "dust: $(cat "$T/jdust.txt")"

# without `smooth` the escape count is piecewise constant; the normals come from the smooth
# count, so the solid is shaded, not flat: many distinct colours on it
sed 's/ smooth revolve/ revolve/' "$T/m.scene" > "$T/mn.scene"
"$R" "$T/mn.scene" -o "$T/mn.meta" --quiet
n=$("$BIN/locus-raster" "$T/mn.meta" -o - -f ppm 2>/dev/null | python3 -c '
import sys
d = sys.stdin.buffer.read()
# P6 header: 4 fields
parts = d.split(b"\n", 3)
px = parts[3]
cols = set(px[i:i + 3] for i in range(0, len(px), 3))
print(len(cols))' 2>/dev/null)
[ -n "$n" ] && [ "$n" -gt 200 ] && ok "no smooth: the solid is shaded ($n colours)" || notok "no smooth: $n colours"
done_tests

#!/bin/sh
# t_render_plane.sh: contour maps on any plane (`on O U V`): the plane z = Z written with `on`
# gives the same bytes as `plane Z`; a tilted plane maps f there; parallel axes are refused.
. tests/lib.sh
R="$BIN/locus-render"
base='view\n  size 48 48\nend\nshape s\n  point 1 0 0\n  point -1 0 0\n  point 0 1.2 0.3\n  c 0\nend\nrender contour\n  window -3 -3 3 3\n  levels 6 from 3 to 7\n  field s\n'
printf "${base}  plane 0.3\nend\n" > "$T/z.scene"
printf "${base}  on 0 0 0.3 1 0 0 0 1 0\nend\n" > "$T/on.scene"
"$R" "$T/z.scene" -o "$T/z.meta" --quiet && "$R" "$T/on.scene" -o "$T/on.meta" --quiet
same_file "on O (1,0,0) (0,1,0) is the plane z = O_z" "$T/on.meta" "$T/z.meta"
# the plane x = 0 spanned by (0,0,1) and (0,1,0) of f(P) = |P - (1,0,0)| + |P + (1,0,0)| + ...: symmetric in s
printf "${base}  on 0 0 0 0 0 1 0 1 0\nend\n" | sed 's/point 0 1.2 0.3/point 0 1.2 0/' > "$T/x.scene"
"$R" "$T/x.scene" -o "$T/x.meta" --quiet && "$BIN/locus-raster" "$T/x.meta" -o "$T/x.ppm" > /dev/null 2>&1
sym=$(python3 -c "
import sys
d=open(sys.argv[1],'rb').read(); p=d.split(b'\n',3)[3]; n=48
px=[p[3*i:3*i+3] for i in range(n*n)]
print('sym' if all(px[j*n+i]==px[j*n+n-1-i] for j in range(n) for i in range(n)) else 'asym')" "$T/x.ppm" 2>&1)
[ "$sym" = sym ] && ok "the map on the plane x = 0 (axes z and y) is symmetric in z, as f is" || notok "x = 0 map: $sym"
cmp -s "$T/x.meta" "$T/z.meta" && notok "the tilted map equals the z map" || ok "a different plane, a different map"
printf "${base}  on 0 0 0 1 0 0 2 0 0\nend\n" > "$T/par.scene"
"$R" "$T/par.scene" -o "$T/par.meta" 2> "$T/par.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "par.scene:14:3: expected two axes U and V that are not parallel" "$T/par.txt" && ok "parallel axes refused at line:col" || notok "parallel: exit $rc $(cat "$T/par.txt")"
done_tests

#!/bin/sh
# t_bounds_scene.sh: the renderer's work is bounded by its input: scene numbers as the spec says
# (decimal, within 1e6, constants in expressions too), shape nesting and evaluation cost limits
# with FILE:LINE:COL, octree memory, and out of memory exiting 70.
. tests/lib.sh
R=$BIN/locus-render
limited() { if [ "${SANITIZE:-}" = 1 ]; then "$@"; else (ulimit -v "$LIM"; exec "$@"); fi; }
# bad SCENE-TEXT WANT DESC: exit 65, the message WANT (a grep pattern), no output file
bad() {
	printf "$1" > "$T/b.scene"
	rm -f "$T/b.meta"
	timeout 20 "$R" "$T/b.scene" -o "$T/b.meta" 2> "$T/err"
	rc=$?
	if [ $rc = 65 ] && [ ! -e "$T/b.meta" ] && grep -q "$2" "$T/err"; then ok "$3"; else notok "$3: exit $rc: $(cat "$T/err")"; fi
}
OBJ='object t\n  point 1 0 0\n  point -1 0 0\n'
bad "${OBJ}  c 1e308\nend\n" "b.scene:4:5: expected a number between -1e6 and 1e6 .*found '1e308'" "c 1e308 refused at its column"
bad "${OBJ}  c 2 + 1e7*x\nend\n" "b.scene:4:9: expected a number between -1e6 and 1e6" "a constant inside an expression: refused"
bad "${OBJ}  c 0x10\nend\n" "b.scene:4:5: expected a decimal number" "hexadecimal constant of c refused"
bad "${OBJ}  c 1 + 0x2*x\nend\n" "b.scene:4:9: expected a decimal number" "hexadecimal inside an expression refused"
bad "view\n  size 0x10 0x8\nend\n" "b.scene:2:8: expected a width in pixels (a decimal number), found '0x10'" "size 0x10 0x8 refused"
bad "${OBJ}  c 3\n  translate 1e7 0 0\nend\n" "b.scene:5:13: expected a translation between -1e6 and 1e6" "translate 1e7 refused"
bad "background 0.5 nan 1\n" "b.scene:1:16: expected a colour component 0..1 (a finite number), found 'nan'" "nan refused as a word"
printf "${OBJ}  c 3.6 + 0.5e-1*x\n  bound -3 -3 -3 3 3 3\nend\nview\n  size 8 8\nend\n" > "$T/g.scene"
check "decimal forms stay accepted (0.5e-1, 3.6)" "$R" "$T/g.scene" -o "$T/g.meta" --quiet
# nesting: a chain of distance-to nine shapes deep is refused at the name that passes 8
python3 - "$T/chain.scene" <<'PY'
import sys
f = open(sys.argv[1], 'w')
f.write("view\n  size 8 8\nend\nshape s0\n  point 0 0 0\n  point 1 0 0\n  c 2\nend\n")
for i in range(1, 10):
    f.write("shape s%d\n  distance-to s%d\n  point 0 0.1 0\n  c 0.5\n  bound -2 -2 -2 2 2 2\nend\n" % (i, i - 1))
PY
timeout 20 "$R" "$T/chain.scene" -o "$T/c.meta" 2> "$T/err"
[ $? = 65 ] && grep -q "chain.scene:58:15: expected shapes nested at most 8 deep" "$T/err" && ok "distance-to nested 9 deep: refused at the name" || notok "nesting: $(cat "$T/err")"
# cost: each shape the distance to the previous one twice, 20 levels (2^20 evaluations per
# point): refused while parsing, in well under the time limit, at the level passing the cost
python3 - "$T/twice.scene" <<'PY'
import sys
f = open(sys.argv[1], 'w')
f.write("view\n  size 8 8\nend\nshape s0\n  point 0 0 0\n  c 1\nend\n")
for i in range(1, 21):
    f.write("shape s%d\n  distance-to s%d\n  distance-to s%d\n  c 0.5\n  bound -2 -2 -2 2 2 2\nend\n" % (i, i - 1, i - 1))
PY
timeout 20 "$R" "$T/twice.scene" -o "$T/t.meta" 2> "$T/err"
[ $? = 65 ] && grep -q "twice.scene:46:15: expected a shape that costs at most 2048 distance evaluations" "$T/err" && ok "distance to the previous shape twice, 20 deep: refused in time" || notok "cost: $(cat "$T/err")"
# distance-to the previous shape and c shape of it, 12 levels (1 KB; 24 s for 8 x 8 before)
python3 - "$T/mix.scene" <<'PY'
import sys
f = open(sys.argv[1], 'w')
f.write("view\n  size 8 8\nend\nshape s0\n  point 0 0 0\n  c 1\nend\n")
for i in range(1, 13):
    f.write("shape s%d\n  distance-to s%d\n  c shape s%d 0.5 0.1\n  bound -2 -2 -2 2 2 2\nend\n" % (i, i - 1, i - 1))
PY
timeout 20 "$R" "$T/mix.scene" -o "$T/m.meta" 2> "$T/err"
[ $? = 65 ] && grep -q "mix.scene:40:11: expected a shape that costs at most 2048" "$T/err" && ok "distance-to and c shape of the previous shape, 12 deep: refused at once" || notok "mix: $(cat "$T/err")"
printf "view\n  size 8 8\nend\nshape a\n  point 0 0 0\n  c 1\nend\n" > "$T/cs.scene"
for i in 1 2 3 4 5 6 7 8 9; do printf "shape s$i\n  point 0 0 0\n  c shape %s 0.5 1\n  bound -2 -2 -2 2 2 2\nend\n" $( [ $i = 1 ] && echo a || echo s$((i - 1)) ) >> "$T/cs.scene"; done
timeout 20 "$R" "$T/cs.scene" -o "$T/cs.meta" 2> "$T/err"
[ $? = 65 ] && grep -q "cs.scene:[0-9]*:11: expected shapes nested at most 8 deep\|cs.scene:[0-9]*:11: expected a shape that costs" "$T/err" && ok "c shape chains count too" || notok "c shape nesting: $(cat "$T/err")"
# the cost counts distance evaluations, not points: one element of 3000 points is cheap
python3 -c "
print('view\n  size 8 8\nend\nobject t\n  points ' + ' '.join('%d 0 0' % i for i in range(3000)) + '\n  c 5000\n  bound -10 -10 -10 10 10 10\nend')" > "$T/pts.scene"
check "a 3000-point element is within the cost limit" "$R" "$T/pts.scene" -o "$T/pts.meta" --quiet
# octree: depth 12 with draw no only counts (memory stays small); drawn, beyond the leaf limit
# it is refused with the render block's place
OCT='object t\n  point 1 0 0\n  point -1 0 0\n  point 0 1.2 0.3\n  c 3.6\n  bound -3 -3 -3 3 3 3\nend\nview\n  size 8 8\nend\nrender octree\n'
printf "${OCT}  depth 12\n  draw no\nend\n" > "$T/o12.scene"
LIM=100000 limited "$R" "$T/o12.scene" -o "$T/o12.meta" --quiet --stats 2> "$T/err"
[ $? = 0 ] && grep -q "oct_leaves=12350910" "$T/err" && ok "octree depth 12, draw no: 12.35 M leaves counted within 100 MB" || notok "depth 12: $(cat "$T/err")"
bad "${OCT}  depth 11\nend\n" "b.scene:11:1: the octree has more than 2097152 leaves to draw" "octree depth 11 drawn: refused beyond the leaf limit"
# out of memory: 70, not 65
printf 'view\n  size 30000 30000\nend\nobject t\n  point 0 0 0\n  c 1\nend\n' > "$T/big.scene"
if [ "${SANITIZE:-}" = 1 ]; then
	ok "out of memory: skipped under ASan (no address-space limit)"
else
	rm -f "$T/big.meta"
	LIM=1000000 limited "$R" "$T/big.scene" -o "$T/big.meta" 2> "$T/err"
	rc=$?
	[ $rc = 70 ] && [ ! -e "$T/big.meta" ] && grep -q "out of memory" "$T/err" && ok "out of memory: 70, no file" || notok "out of memory: exit $rc: $(cat "$T/err")"
fi
done_tests

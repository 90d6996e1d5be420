#!/bin/sh
# t_render_msgs.sh: locus-render's messages say what is true and what to do: empty scenes refused,
# a second `c` refused, control bytes from the scene escaped, no misleading "empty" warning for contours.
. tests/lib.sh
R="$BIN/locus-render"

: > "$T/zero.scene"
"$R" "$T/zero.scene" -o "$T/zero.meta" 2> "$T/zero.txt"; rc=$?
[ "$rc" = 65 ] && [ ! -e "$T/zero.meta" ] && grep -q "zero.scene:1:1: expected an 'object' block or a 'render' block: the scene is empty" "$T/zero.txt" \
	&& ok "a 0-byte scene: exit 65, one line, no output" || notok "0-byte scene: exit $rc $(cat "$T/zero.txt")"

printf 'object a\n  point 0 0 0\n  c 1\n  c 2\nend\n' > "$T/c2.scene"
"$R" "$T/c2.scene" -o "$T/c2.meta" 2> "$T/c2.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "c2.scene:4:3: expected one 'c' line per shape" "$T/c2.txt" && ok "c given twice: refused at the second" \
	|| notok "c twice: exit $rc $(cat "$T/c2.txt")"

# an escape sequence (ESC [ 2 J clears a terminal) in the scene and in an object name
printf 'object a\n  point 0 0 0\n  c \033[2J\nend\n' > "$T/esc.scene"
"$R" "$T/esc.scene" -o "$T/esc.meta" 2> "$T/esc.txt"; rc=$?
[ "$rc" = 65 ] && ! LC_ALL=C grep -q "$(printf '\033')" "$T/esc.txt" && grep -q "found '\\\\x1b\[2J'" "$T/esc.txt" \
	&& ok "control bytes in an error message are escaped as \\xHH" || notok "escape: exit $rc $(od -c "$T/esc.txt" | head -3)"
printf 'view\n  size 8 8\nend\nobject a\033]0;pwned\007\n  point 1 0 0\n  point -1 0 0\n  c 1\nend\n' > "$T/escw.scene"
"$R" "$T/escw.scene" -o "$T/escw.meta" 2> "$T/escw.txt"; rc=$?
[ "$rc" = 0 ] && grep -q "the shape is empty" "$T/escw.txt" && ! LC_ALL=C grep -q "$(printf '\033')" "$T/escw.txt" \
	&& ok "control bytes in a warning are escaped" || notok "warning escape: exit $rc $(od -c "$T/escw.txt" | head -3)"

# the contour map of sum d (c 0, the documented way) draws lines and does not warn "empty"
printf 'view\n  size 32 32\nend\nobject a\n  point 1 0 0\n  point -1 0 0\n  c 0\nend\nrender contour\n  window -3 -3 3 3\n  levels 5 from 0.5 to 4\nend\n' > "$T/cont.scene"
"$R" "$T/cont.scene" -o "$T/cont.meta" 2> "$T/cont.txt"; rc=$?
[ "$rc" = 0 ] && ! grep -q "empty" "$T/cont.txt" && ok "contour map with c 0: no 'empty' warning" || notok "contour c 0: exit $rc $(cat "$T/cont.txt")"

printf 'object a\n  point 0 0 0 weight 0\n  point 1 0 0 weight 0\n  c 1\nend\n' > "$T/w0.scene"
"$R" "$T/w0.scene" -o "$T/w0.meta" 2> "$T/w0.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "every element has weight 0" "$T/w0.txt" && ! grep -q "negative" "$T/w0.txt" \
	&& ok "all-zero weights named as such, not as negative weights" || notok "zero weights: exit $rc $(cat "$T/w0.txt")"
printf 'shape b\n  point 0 0 0\n  c 1\nend\nobject a\n  distance-to b\n  c 0.5\nend\n' > "$T/dt.scene"
"$R" "$T/dt.scene" -o "$T/dt.meta" 2> "$T/dt.txt"; rc=$?
[ "$rc" = 65 ] && grep -q "only distance-to other shapes.*add 'bound X0 Y0 Z0 X1 Y1 Z1'" "$T/dt.txt" \
	&& ok "a shape of distance-to only: the message asks for a bound" || notok "distance-to: exit $rc $(cat "$T/dt.txt")"
printf 'shape b\n  point 0 0 0\n  c 1\nend\nobject a\n  distance-to b\n  c 0.5\n  bound -3 -3 -3 3 3 3\nend\nview\n  size 8 8\nend\n' > "$T/dtb.scene"
check "... and renders once it has one" "$R" "$T/dtb.scene" -o "$T/dtb.meta" --quiet
done_tests

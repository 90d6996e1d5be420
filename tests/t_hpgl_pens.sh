#!/bin/sh
# t_hpgl_pens.sh: an Inkscape drawing with layers to the emulated plotter, one pen per layer
# (issue 23, item 2): vpype's three named layers (../shared/corpus/svg) imported with --pens
# by-layer, then locus-hpgl with per-pen settings (VS, FS, AS sent with each SP) and a pause
# before pen 2, which is loaded by hand. Through the plotter emulator on a pseudo-terminal
# (tests/emu/plotemu.c) with a terminal of locus-hpgl's own (tests/tools/ttyanswer.py types the
# answers): Enter goes on and the plotter gets exactly the job's bytes; "s" stops with the
# journal at the pen change (exit 75), and --resume asks nothing again and sends the rest: the
# two parts are the uninterrupted job's bytes, byte for byte (after the resume's restore). No
# terminal and --no-prompt stop the same way; the profile file's pen.N keys equal the options.
. tests/emu/lib.sh
SVG=$CORPUS_DIR/svg/vpype/misc/multilayer_named_layers.svg
M=$BIN/locus-meta
ANS="/usr/bin/python3 tests/tools/ttyanswer.py --timeout 30"
if ! need_corpus svg/vpype "an Inkscape drawing with layers to the plotter"; then
	done_tests
fi
PENS=1=black,2=red,3=blue
"$M" import --pens "$PENS" --pens by-layer "$SVG" -o "$T/l.meta" 2> /dev/null
grep -q '^# pen 2: layer "my layer 2"$' "$T/l.meta" && ok "import --pens by-layer: three layers, pens 1-3, named in the meta file" \
	|| notok "import: $(grep '^#' "$T/l.meta")"

# --- per-pen settings, one pen per layer (to a file) ---
P="--profile 7550a --pens $PENS --pen 1:speed=30 --pen 2:speed=20,force=3 --pen 3:accel=2"
"$H" $P "$T/l.meta" -o "$T/set.hpgl" 2> "$T/e"
seq=$(grep -o 'SP[0-9]*;\(VS[0-9.]*;\|FS[0-9.]*;\|AS[0-9.]*;\)*' "$T/set.hpgl" | tr -d '\n')
[ "$seq" = "SP1;VS30;SP2;VS20;FS3;SP3;VS80;FS;AS2;SP0;" ] \
	&& ok "one SP per layer, each with its settings; a pen without its own gets the profile's speed and the default force back: $seq" \
	|| notok "settings: $seq"
"$SEG" "$T/set.hpgl" | cut -d' ' -f1 | uniq -c | awk '{printf "%s:%s ", $2, $1}' > "$T/perpen"
[ "$(cat "$T/perpen")" = "1:5 2:4 3:7 " ] \
	&& ok "pen 1 draws layer 1's square and the line outside every layer, pen 2 layer 2's square, pen 3 layer 3's two squares, cut by the page's edge (segments per pen: $(cat "$T/perpen"))" \
	|| notok "segments per pen: $(cat "$T/perpen")"
# the plot-time model draws each pen at its own speed: pen 2's 212 mm at 5 cm/s take over 4 s
"$H" --pens "$PENS" --estimate "$T/l.meta" > "$T/est0" 2>&1
"$H" --pens "$PENS" --pen 2:speed=5 --estimate "$T/l.meta" > "$T/est5" 2>&1
d0=$(sed -n 's/^estimate page 1 pen 2: .*drawing \([0-9]*\) mm in \([0-9.]*\) s.*/\1 \2/p' "$T/est0")
d5=$(sed -n 's/^estimate page 1 pen 2: .*drawing \([0-9]*\) mm in \([0-9.]*\) s.*/\1 \2/p' "$T/est5")
awk -v a="$d0" -v b="$d5" 'BEGIN { split(a, x, " "); split(b, y, " "); exit !(x[1] == y[1] && x[1] > 0 &&
	y[2] >= x[1] / 50 && y[2] < x[1] / 50 + 1 && x[2] < y[2] / 4) }' \
	&& ok "--estimate draws pen 2 at its own speed: $d0 (mm, s) at the 7475A's 38.1 cm/s, $d5 at 5 cm/s" \
	|| notok "estimate: '$d0' '$d5': $(cat "$T/est5")"
cat > "$T/prof.txt" <<EOF
name = my7550
base = 7550a
pen.1 = speed=30
pen.2 = speed=20, force=3
pen.3 = accel=2
EOF
"$H" --profile "$T/prof.txt" --pens "$PENS" "$T/l.meta" -o "$T/prof.hpgl" 2> /dev/null
same_file "a profile file's pen.N keys give the same job as --pen" "$T/prof.hpgl" "$T/set.hpgl"
"$H" --pen 2:force=3 "$T/l.meta" -o "$T/bad.hpgl" > /dev/null 2> "$T/e"; rc=$?
[ $rc = 64 ] && [ "$(wc -l < "$T/e")" = 1 ] && grep -q "profile 7475a has no FS" "$T/e" && [ ! -e "$T/bad.hpgl" ] \
	&& ok "force on a 7475A (no FS): exit 64, one line: $(cat "$T/e")" || notok "no FS: $rc $(cat "$T/e")"
for a in "--pen 0:speed=1" "--pen 2:speed=0" "--pen 2:colour=red" "--pause-at-pen 300"; do
	"$H" $a "$T/l.meta" -o "$T/bad.hpgl" > /dev/null 2> "$T/e"; rc=$?
	[ $rc = 64 ] && [ "$(wc -l < "$T/e")" = 1 ] && [ ! -e "$T/bad.hpgl" ] && ok "$a: exit 64, one line: $(cat "$T/e")" \
		|| notok "$a: $rc $(cat "$T/e")"
done

# --- the pause before pen 2 ---
P="$P --pause-at-pen 2"
"$H" $P "$T/l.meta" -o "$T/whole.hpgl" 2> "$T/e"
grep -q "PU;SP2;" "$T/whole.hpgl" && grep -q "pauses before pens happen only when the job goes to a device" "$T/e" \
	&& ok "to a file: the pen is lifted before pen 2 and nobody is asked (one warning)" || notok "file: $(cat "$T/e")"
# (the emulator's own deadline bounds each run too)
emu() { "$EMU_PLOTTER" --deadline 60 --pen-scale 100 "$@"; }
OUT="serial:@TTY@?baud=115200"
# Enter at the question: the job goes on; the plotter gets exactly the job
emu --record "$T/r0" --expect "$T/whole.hpgl" -- $ANS --log "$T/log0" --answer 'stop): =\n' -- "$H" $P "$T/l.meta" -o "$OUT" > "$T/o0" 2> "$T/e0"
[ "$(word child "$T/o0")" = 0 ] && [ "$(word bytes "$T/o0")" = same ] && [ "$(grep -c 'load pen' "$T/log0")" = 1 ] \
	&& grep -q 'load pen 2 (layer "my layer 2"), then press Enter' "$T/log0" \
	&& ok "asked once on the terminal ('$(grep -o 'load pen 2[^,]*' "$T/log0")'), Enter: the plotter got the whole job as written to a file" \
	|| notok "Enter: $(cat "$T/o0" "$T/e0" "$T/log0")"
# "s" at the question: a stop at the pen change, resumable
rm -f "$T/j"
emu --record "$T/r1" -- $ANS --log "$T/log1" --answer 'stop): =s\n' -- "$H" $P "$T/l.meta" -o "$OUT" --journal "$T/j" > "$T/o1" 2> "$T/e1"
safe=$(sed -n 's/^safe //p' "$T/j") acked=$(sed -n 's/^acked //p' "$T/j") restore=$(sed -n 's/^restore //p' "$T/j")
at=$(grep -bo 'PU;SP2;' "$T/whole.hpgl" | cut -d: -f1)
[ "$(word child "$T/o1")" = 75 ] && [ "$(wc -l < "$T/e1")" = 1 ] && grep -q '^state interrupted' "$T/j" \
	&& [ "$safe" = $((at + 3)) ] && [ "$acked" = "$safe" ] && [ "$(wc -c < "$T/r1")" = "$safe" ] \
	&& grep -q "stopped before pen 2 (layer \"my layer 2\"): stopped at the question, as asked; load the pen, then resume; page 1, command [0-9]* (byte $safe of the job) reached; resume with: .* --resume $T/j" "$T/e1" \
	&& ok "s: exit 75, the plotter has the job up to the pen lifted before SP2 (byte $safe), the journal's point exactly there; one line: $(cut -c1-160 "$T/e1")..." \
	|| notok "stop: safe $safe acked $acked at $at got $(wc -c < "$T/r1"): $(cat "$T/o1" "$T/e1" "$T/j")"
emu --record "$T/r2" -- $ANS --log "$T/log2" -- "$H" $P "$T/l.meta" -o "$OUT" --resume "$T/j" > "$T/o2" 2> "$T/e2"
# the resumed bytes: ';' and the restore, then the job from the point on
{ cat "$T/r1"; tail -c +$((${#restore} + 2)) "$T/r2"; } > "$T/joined"
[ "$(word child "$T/o2")" = 0 ] && [ ! -s "$T/log2" ] && grep -q '^state done' "$T/j" \
	&& [ "$(head -c $((${#restore} + 1)) "$T/r2")" = ";$restore" ] && cmp -s "$T/joined" "$T/whole.hpgl" \
	&& ok "--resume asks nothing and goes on with pen 2: the parts are the uninterrupted job, byte for byte, after the restore '$restore'" \
	|| notok "resume: $(cat "$T/o2" "$T/e2" "$T/log2"; cmp "$T/joined" "$T/whole.hpgl")"
parts_whole "stop at the pen change, then --resume" "$T/whole.hpgl" "$safe" "$T/r1" "$T/r2"
# no terminal at all (a new session without one), and --no-prompt: a stop too
rm -f "$T/j3"
emu --record "$T/r3" -- setsid -w "$H" $P "$T/l.meta" -o "$OUT" --journal "$T/j3" > "$T/o3" 2> "$T/e3"
[ "$(word child "$T/o3")" = 75 ] && grep -q "no terminal to ask on" "$T/e3" && [ "$(sed -n 's/^safe //p' "$T/j3")" = "$safe" ] \
	&& ok "no terminal: a stop at the same point: $(cut -c1-140 "$T/e3")..." || notok "no tty: $(cat "$T/o3" "$T/e3")"
emu --record "$T/r4" -- $ANS --log "$T/log4" -- "$H" $P --no-prompt "$T/l.meta" -o "$OUT" > "$T/o4" 2> "$T/e4"
[ "$(word child "$T/o4")" = 75 ] && [ ! -s "$T/log4" ] && grep -q -- "--no-prompt: a pause is a stop.*no journal was kept" "$T/e4" \
	&& ok "--no-prompt: nobody asked, a stop (and without --journal the line says so)" || notok "no-prompt: $(cat "$T/o4" "$T/e4" "$T/log4")"
# a hand-fed plotter: a pause before every pen, each answered
emu --record "$T/r5" -- $ANS --log "$T/log5" --answer 'stop): =\n' --answer 'stop): =\n' --answer 'stop): =\n' \
	-- "$H" --pens "$PENS" --pause-pens "$T/l.meta" -o "$OUT" > "$T/o5" 2> "$T/e5"
asked=$(grep -o 'load pen [0-9]' "$T/log5" | cut -c10 | tr -d '\n')
[ "$(word child "$T/o5")" = 0 ] && [ "$asked" = 123 ] && ok "--pause-pens: asked for pens 1, 2 and 3 in turn" \
	|| notok "pause-pens: asked '$asked': $(cat "$T/o5" "$T/e5")"
done_tests

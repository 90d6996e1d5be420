#!/bin/sh
# t_driver_cli.sh: locus-play and locus-raster parse through drivers/cli/cli.h (getopt_long): the
# long and attached option forms, "--", repeated -O, and unknown device options refused.
. tests/lib.sh
: "${T:?T (a scratch directory) must be set: run through tests/run.sh}"
P=$BIN/locus-play
R=$BIN/locus-raster
F=fixtures/meta/f-test.meta
G=fixtures/raster/f-test.raster
# unknown device options: one line naming the key and the device, exit 64, no output
"$P" -d png -O frob=1 -o "$T/x.png" "$F" 2> "$T/err"; rc=$?
[ $rc = 64 ] && [ "$(wc -l < "$T/err")" = 1 ] && grep -q "unknown option 'frob' for device png" "$T/err" && [ ! -e "$T/x.png" ] \
	&& ok "play: -O with an unknown key: exit 64, one line, no output" || notok "play -O frob=1: exit $rc, $(cat "$T/err")"
"$P" -d png -O frob=1 -O bar=2 "$F" 2> "$T/err" > /dev/null; rc=$?
[ $rc = 64 ] && grep -q "unknown option 'frob'" "$T/err" \
	&& ok "play: repeated -O add up (the first unknown key is named)" || notok "play: repeated -O: exit $rc, $(cat "$T/err")"
"$P" -d null -O frob "$F" 2> "$T/err"; rc=$?
[ $rc = 64 ] && grep -q "key=value" "$T/err" && ok "play: -O without '=': usage error" || notok "play -O frob: exit $rc, $(cat "$T/err")"
"$R" -O frob=1 "$F" > /dev/null 2> "$T/err"; rc=$?
[ $rc = 64 ] && grep -q "unknown option 'frob'" "$T/err" && ok "raster: -O with an unknown key: exit 64" || notok "raster -O: exit $rc, $(cat "$T/err")"
# getopt_long forms the hand-written loops did not take
# made DESC GOLDEN OUT CMD...: CMD succeeds and writes OUT equal to GOLDEN
made() { d=$1 g=$2 o=$3; shift 3; if "$@" 2> "$T/err"; then same_file "$d" "$g" "$o"; else notok "$d: $(cat "$T/err")"; fi; }
made "raster: --band-rows=N --output=OUT" "$G.png" "$T/a.png" "$R" --band-rows=3 --output="$T/a.png" "$F"
made "raster: attached -fppm -oOUT" "$G.ppm" "$T/b" "$R" -fppm -o"$T/b" "$F"
cp "$F" "$T/-dash.meta"
made "raster: -- ends the options" "$G.png" "$T/c.png" "$R" -o "$T/c.png" -- "$T/-dash.meta"
made "play: options after the input, --band-rows=N" "$G.png" "$T/d.png" "$P" "$F" -d png --band-rows=5 -o "$T/d.png"
made "play: --mem-budget from the shared options" "$G.png" "$T/e.png" "$P" -d png --mem-budget=1 "$F" -o "$T/e.png"
# the old messages
"$R" --band-rows 0 "$F" 2> "$T/err"; rc=$?
[ $rc = 64 ] && grep -q "^locus-raster: --band-rows needs a positive number, not '0'" "$T/err" && ok "raster: --band-rows 0 refused as before" \
	|| notok "raster --band-rows 0: exit $rc, $(cat "$T/err")"
"$R" -f gif "$F" 2> "$T/err"; rc=$?
[ $rc = 64 ] && grep -q "^locus-raster: unknown format 'gif' (png, ppm or rle)" "$T/err" && ok "raster: unknown format as before" \
	|| notok "raster -f gif: exit $rc, $(cat "$T/err")"
"$P" "$F" 2> "$T/err"; rc=$?
[ $rc = 64 ] && grep -q "^locus-play: no device given: use -d DEVICE" "$T/err" && ok "play: no device as before" || notok "play without -d: $(cat "$T/err")"
expect_exit 64 "play: -d without a value" "$P" -d
expect_exit 64 "raster: two inputs" "$R" "$F" "$F"
done_tests

#!/bin/sh
# t_meta_cli.sh: locus-meta options, exit statuses and the info report.
. tests/lib.sh
M="$BIN/locus-meta"
F=fixtures/meta
expect_exit 0 "--help" "$M" --help
"$M" --help | grep -q "convert \[IN\]" && ok "--help prints usage" || notok "--help text"
"$M" --version | grep -q "^locus-meta [0-9]" && ok "--version" || notok "--version"
expect_exit 64 "no subcommand is a usage error" "$M"
expect_exit 64 "unknown subcommand" "$M" frob
expect_exit 64 "unknown option" "$M" check --frob "$F/f-test.meta"
expect_exit 64 "check without FILE" "$M" check
expect_exit 64 "-o without a name" "$M" fmt "$F/f-test.meta" -o
expect_exit 64 "--binary belongs to convert" "$M" fmt --binary "$F/f-test.meta"
expect_exit 66 "missing input" "$M" check "$T/nonexistent.meta"
"$M" check "$T/nonexistent.meta" 2>&1 | grep -q "nonexistent.meta: cannot open" && ok "missing input names the file" || notok "missing input message"
expect_exit 74 "unwritable output" "$M" convert "$F/f-test.meta" -o "$T/no/such/dir/out.lmb"
expect_exit 0 "check reads stdin" sh -c "'$M' check - < '$F/f-test.meta'"
"$M" check - < fixtures/bad/nan.meta 2>&1 | grep -q "^<stdin>:3:7: " && ok "stdin errors are named <stdin>" || notok "stdin error name"
if [ -e /dev/full ]; then
	expect_exit 74 "write error on stdout" sh -c "'$M' fmt '$F/strokes.meta' > /dev/full"
fi

"$M" info "$F/f-test.meta" > "$T/info"
grep -q "^page 1: 160 x 120 px, 42.333 x 31.75 mm," "$T/info" && ok "info: page size" || notok "info: page size"
grep -q "geometry bounds x 20.000 .. 144.000, y 10.000 .. 102.000" "$T/info" && ok "info: bounds" || notok "info: bounds: $(cat "$T/info")"
grep -q "^statements:.* fill 2 .* draw 7 .* span 1 image 1 row 6" "$T/info" && ok "info: statement counts" || notok "info: counts"
grep -q "^colours: 7 distinct #000000 #0000ff #00c000 #00ffff #e8e8e8 #ff0000 #ffff00" "$T/info" && ok "info: colours" || notok "info: colours: $(grep colours "$T/info")"
printf 'LOCUS-META 1\npage 100 100\nstroke\narc 50 50 10 45 -180\nend\nend-page\n' | "$M" info - > "$T/arc"
grep -q "bounds x 42.929 .. 60.000, y 40.000 .. 57.071" "$T/arc" && ok "info: arc bounds by its extent" || notok "info: arc bounds: $(cat "$T/arc")"
"$M" info "$F/multipage.meta" | grep -c "^page [123]:" | grep -q 3 && ok "info: three pages" || notok "info: pages"

# the colour set is capped: 2000 distinct span colours
awk 'BEGIN { print "LOCUS-META 1"; print "page 64 64"; for (i = 0; i < 2000; i++) printf "span 0 %d 1 #%06x\n", i % 64, i * 97; print "end-page" }' > "$T/many.meta"
"$M" info "$T/many.meta" | grep -q "^colours: more than 1024 distinct" && ok "info: colour set capped" || notok "info: colour cap"
# streaming: a 300,000-statement file read from a pipe, memory independent of its size
gen() { awk -v n="$1" 'BEGIN { print "LOCUS-META 1"; print "page 1024 768"; print "stroke"; print "move 0 0";
	for (i = 0; i < n; i++) printf "draw %d.%03d %d.5\n", i % 1024, i % 1000, (i * 7) % 768; print "end"; print "end-page" }'; }
gen 300000 | "$M" check - && ok "300k statements through a pipe" || notok "300k statements through a pipe"
if [ "${SANITIZE:-}" != 1 ] && [ -x /usr/bin/time ]; then
	gen 300000 > "$T/big.meta"
	gen 30000 > "$T/small.meta"
	big=$( { /usr/bin/time -f %M "$M" check "$T/big.meta"; } 2>&1 | tail -1)
	small=$( { /usr/bin/time -f %M "$M" check "$T/small.meta"; } 2>&1 | tail -1)
	if [ "$big" -lt 8192 ] && [ "$big" -lt $((small + 1024)) ]; then ok "memory bounded: ${big} KB for 10x the ${small} KB input"; else notok "memory grows with the file: $small KB -> $big KB"; fi
fi
expect_exit 65 "info of a bad file" "$M" info fixtures/bad/nan.meta
done_tests

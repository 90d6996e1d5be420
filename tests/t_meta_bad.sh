#!/bin/sh
# t_meta_bad.sh: each fixtures/bad/* input gets exactly its one-line message from
# fixtures/bad/expected.txt, exit status 65, and leaves no output file behind.
. tests/lib.sh
M="$(cd "$BIN" && pwd)/locus-meta"
top=$(pwd)
cd fixtures/bad || exit 1
n=0
for f in *; do
	[ "$f" = expected.txt ] && continue
	n=$((n + 1))
	want=$(grep -F -e "$f:" -e "$f: byte" expected.txt | grep -v '^#' | head -1)
	if [ -z "$want" ]; then notok "$f: no line in expected.txt"; continue; fi
	"$M" check "$f" > "$T/out" 2> "$T/err"; rc=$?
	got=$(cat "$T/err")
	lines=$(wc -l < "$T/err")
	if [ "$rc" = 65 ] && [ "$lines" = 1 ] && [ "$got" = "$want" ] && [ ! -s "$T/out" ]; then
		ok "$f: check exits 65 with the expected line"
	else
		notok "$f: check exit $rc, $lines lines: '$got' (wanted '$want')"
	fi
	for sub in convert fmt; do
		rm -f "$T/o" "$T/o.tmp"
		"$M" $sub "$f" -o "$T/o" 2> "$T/err"; rc=$?
		if [ "$rc" = 65 ] && [ ! -e "$T/o" ] && [ ! -e "$T/o.tmp" ] && [ "$(cat "$T/err")" = "$want" ]; then
			ok "$f: $sub -o exits 65, same message, leaves neither OUT nor OUT.tmp"
		else
			notok "$f: $sub -o exit $rc, out $(ls "$T" | grep '^o' | tr '\n' ' ')"
		fi
	done
done
# every table entry names an existing file
grep -v '^#' expected.txt | sed -E 's/(: byte [0-9]+|:[0-9]+:[0-9]+): .*//' | while read -r f; do
	[ -e "$f" ] || echo "missing $f"
done > "$T/missing"
if [ -s "$T/missing" ]; then notok "expected.txt names missing files: $(cat "$T/missing")"; else ok "every expected.txt entry has its file"; fi
if [ "$n" -ge 30 ]; then ok "$n bad inputs checked"; else notok "only $n bad inputs"; fi
# an existing OUT survives a failed convert untouched
cd "$top"
echo keep > "$T/keep"
"$M" convert fixtures/bad/nan.meta -o "$T/keep" 2>/dev/null
if [ "$(cat "$T/keep")" = keep ] && [ ! -e "$T/keep.tmp" ]; then ok "failed convert leaves an existing OUT as it was"; else notok "failed convert damaged OUT"; fi
done_tests

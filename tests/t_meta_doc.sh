#!/bin/sh
# t_meta_doc.sh: the statement table of docs/meta-language.md §4 agrees with meta/opcodes.def
# (keyword and binary code of every statement), and locus-meta --help matches the man page's commands.
. tests/lib.sh
n=0
sed -n 's/^META_OP([A-Z_]*, *"\([^"]*\)", *0x\([0-9a-f][0-9a-f]\),.*/\1 \2/p' meta/opcodes.def > "$T/ops"
while read -r kw code; do
	n=$((n + 1))
	if grep -qF "| \`$kw\` | $code |" docs/meta-language.md; then ok "spec lists '$kw' as $code"; else notok "spec lacks '| \`$kw\` | $code |'"; fi
done < "$T/ops"
# the kinds column (§4) spells the signature of opcodes.def, one letter per operand
sed -n 's/^META_OP([A-Z_]*, *"\([^"]*\)", *0x[0-9a-f]*, *"\([^"]*\)").*/\1 \2/p' meta/opcodes.def > "$T/sigs"
while read -r kw sig; do
	want=$(printf '%s' "$sig" | sed 's/./& /g; s/ $//')
	got=$(grep -F "| \`$kw\` | " docs/meta-language.md | head -1 | sed 's/\\|/!/g' | awk -F'|' '{print $5}' | tr -d '\` ' )
	if [ "$got" = "$sig" ]; then ok "spec gives '$kw' the operand kinds '$want'"; else notok "spec kinds of '$kw': '$got', opcodes.def '$sig'"; fi
done < "$T/sigs"
rows=$(sed -n '/^## 4\./,/^Structure/p' docs/meta-language.md | grep -c '^| `')
if [ "$n" -ge 24 ] && [ "$rows" = "$n" ]; then ok "spec table has exactly the $n statements of opcodes.def"; else notok "spec table has $rows rows, opcodes.def $n"; fi
for sub in check fmt info convert; do
	if grep -q "^\.B locus-meta $sub" docs/man/locus-meta.1 && "$BIN/locus-meta" --help | grep -q "locus-meta $sub"; then ok "'$sub' in --help and the man page"; else notok "'$sub' missing from --help or man page"; fi
done
done_tests

#!/bin/sh
# t_meta_roundtrip.sh: every fixtures/meta/*.meta is valid, canonical (fmt is a no-op), and
# text -> binary -> text and binary -> text -> binary are byte-identical.
. tests/lib.sh
M="$BIN/locus-meta"
n=0
for f in fixtures/meta/*.meta; do
	b=$(basename "$f" .meta)
	n=$((n + 1))
	check "$b: check passes" "$M" check "$f"
	"$M" fmt "$f" -o "$T/$b.fmt"
	same_file "$b: fmt is a no-op (file is canonical)" "$f" "$T/$b.fmt"
	"$M" convert "$f" -o "$T/$b.lmb"
	"$M" convert "$T/$b.lmb" -o "$T/$b.txt"
	same_file "$b: text -> binary -> text is identical" "$f" "$T/$b.txt"
	"$M" convert "$T/$b.txt" --binary -o "$T/$b.2.lmb"
	same_file "$b: binary -> text -> binary is identical" "$T/$b.lmb" "$T/$b.2.lmb"
	"$M" convert --text < "$T/$b.lmb" > "$T/$b.stdout"
	same_file "$b: convert through stdin/stdout" "$f" "$T/$b.stdout"
	"$M" fmt "$T/$b.lmb" -o "$T/$b.fmt2"
	same_file "$b: fmt of the binary form gives the canonical text" "$f" "$T/$b.fmt2"
	s_text=$(wc -c < "$f"); s_bin=$(wc -c < "$T/$b.lmb")
	if [ "$s_bin" -lt "$s_text" ]; then ok "$b: binary smaller ($s_bin < $s_text bytes)"; else notok "$b: binary not smaller ($s_bin >= $s_text)"; fi
done
if [ "$n" -ge 5 ]; then ok "$n fixtures round-tripped"; else notok "only $n fixtures found"; fi

# together the fixtures use every statement of opcodes.def
for f in fixtures/meta/*.meta; do "$M" info "$f"; done | sed -n 's/^statements://p' | tr ' ' '\n' | grep '^[a-z#-]' | sort -u > "$T/used"
sed -n 's/^META_OP([A-Z_]*, *"\([^"]*\)".*/\1/p' meta/opcodes.def | sed 's/^#$/comment/' | sort -u > "$T/all"
missing=$(comm -23 "$T/all" "$T/used" | tr '\n' ' ')
if [ -z "$missing" ] && [ -s "$T/all" ]; then ok "fixtures use all $(wc -l < "$T/all") statements"; else notok "statements no fixture uses: $missing"; fi

# fmt canonicalises: blanks, case, numbers, empty lines, CRLF
printf 'LOCUS-META   1\r\n\npage 10  10\n  colour\t#ABCDEF\nwidth +02.50000\nstroke\nmove -0.0004 .5\ndraw 1.0005 7.\nend\n# note\nend-page\n' > "$T/messy.meta"
printf 'LOCUS-META 1\npage 10 10\ncolour #abcdef\nwidth 2.5\nstroke\nmove 0 0.5\ndraw 1.001 7\nend\n# note\nend-page\n' > "$T/clean.meta"
"$M" fmt "$T/messy.meta" > "$T/messy.out"
same_file "fmt canonicalises spacing, case, numbers, CRLF" "$T/clean.meta" "$T/messy.out"
done_tests

# t_bench_gen.sh: the benchmark generator writes valid, deterministic and identical drawings in both formats.
. tests/lib.sh
: "${TESTBIN:=build/native/tests}"
LIBDIR=$(dirname "$TESTBIN")
SAN=""
[ "${SANITIZE:-}" = 1 ] && SAN="-fsanitize=address,undefined -fno-omit-frame-pointer"
gen="$T/gen_workloads"
# shellcheck disable=SC2086
if ${CC:-cc} -std=c11 -D_POSIX_C_SOURCE=200809L -DLOCUS_VERSION='"test"' -O1 $SAN -Wall -Wextra -Werror \
	-Imeta tests/bench/gen_workloads.c "$LIBDIR/libmeta.a" -lm -o "$gen" 2> "$T/cc.log"; then
	ok "gen_workloads builds without warnings"
else
	notok "gen_workloads builds without warnings: $(head -3 "$T/cc.log")"
	done_tests
fi

check "b text" "$gen" b text -o "$T/b.meta"
check "b binary" "$gen" b binary -o "$T/b.lmb"
check "b plot" "$gen" b plot -o "$T/b.plot"
check "c text" "$gen" c text -o "$T/c.meta"
check "c plot" "$gen" c plot -o "$T/c.plot"
"$gen" b text > "$T/b2.meta" 2> /dev/null
same_file "b text is deterministic (file and stdout agree)" "$T/b.meta" "$T/b2.meta"
expect_exit 64 "unknown workload is a usage error" "$gen" z text
expect_exit 64 "unknown format is a usage error" "$gen" a svg
[ ! -e "$T/b.meta.tmp" ] && ok "no temporary file left" || notok "b.meta.tmp left behind"

# valid Locus meta, and the binary form is the same drawing as the text form
check "b.meta passes locus-meta check" "$BIN/locus-meta" check "$T/b.meta"
check "b.lmb passes locus-meta check" "$BIN/locus-meta" check "$T/b.lmb"
check "c.meta passes locus-meta check" "$BIN/locus-meta" check "$T/c.meta"
"$BIN/locus-meta" convert "$T/b.lmb" --text -o "$T/b.lmb.meta" > /dev/null 2>&1
same_file "binary b converts back to the text b" "$T/b.meta" "$T/b.lmb.meta"

# counts promised by the workload definition
n=$(grep -c '^fill$' "$T/b.meta")
[ "$n" = 10001 ] && ok "b has 10,000 polygons and a background" || notok "b has $n fills, wanted 10001"
n=$(grep -c -E '^(move|draw) ' "$T/b.meta")
[ "$n" = 75004 ] && ok "b has 75,004 vertices" || notok "b has $n vertices, wanted 75004"
segs=$(awk '/^stroke$/ {p = -1} /^(move|draw) / {p++} /^end$/ {s += p} END {print s}' "$T/c.meta")
[ "$segs" -gt 190000 ] && [ "$segs" -lt 210000 ] && ok "c has about 200,000 segments ($segs)" ||
	notok "c has $segs segments, wanted about 200,000"

# the plotutils file carries exactly the same points, colours and paths
for w in b c; do
	awk '/^(move|draw) / {print $2, $3}' "$T/$w.meta" > "$T/$w.meta.pts"
	awk '/^[$)] / {print $2, $3}' "$T/$w.plot" > "$T/$w.plot.pts"
	same_file "$w: same points in Locus meta and #PLOT 2" "$T/$w.meta.pts" "$T/$w.plot.pts"
done
awk '/^colour / {print $2}' "$T/b.meta" > "$T/b.meta.col"
awk '/^D / {printf "#%02x%02x%02x\n", $2 / 257, $3 / 257, $4 / 257}' "$T/b.plot" > "$T/b.plot.col"
same_file "b: same colours in both formats" "$T/b.meta.col" "$T/b.plot.col"
if command -v plot > /dev/null 2>&1; then
	check "plotutils reads b.plot" plot -T meta "$T/b.plot"
	check "plotutils reads c.plot" plot -T meta "$T/c.plot"
else
	ok "# skip: plot (plotutils) not installed"
fi
done_tests

#!/bin/sh
# t_render_oom.sh: a scene whose c expression outgrows its first code buffer, read by
# locus-render with the Nth allocation failing (tests/fault/fault.c) for every N of a clean run:
# each failure is one line saying "out of memory" (or strerror's "Cannot allocate memory"; the
# expression compiler's own words where it was the one that failed, never "expected memory")
# with exit 70, and no output file.
. tests/lib.sh
if [ "${SANITIZE:-}" = 1 ]; then ok "fault injection skipped under SANITIZE=1 (the sanitizer owns malloc)"; done_tests; fi
LIB=$TESTBIN/libfault.so
if [ ! -f "$LIB" ]; then notok "no $LIB (tests/mk/fault.mk builds it)"; done_tests; fi
LIB=$(cd "$(dirname "$LIB")" && pwd)/$(basename "$LIB")
R=$BIN/locus-render
S=$T/oom.scene
# 2 + 24 terms: more than the 16 operations of the compiler's first buffer
printf 'object o\n  c 0.5 + 0.01 * (x + y + z + x * y + y * z + z * x + x * x + y * y + z * z + x + y + z)\n  bound -1 -1 -1 1 1 1\nend\nrender contour\n  field o\n  window -1 -1 1 1\n  levels 3 from 0 to 1\nend\n' > "$S"
rm -f "$T/count"
LD_PRELOAD=$LIB LOCUS_FAULT_COUNT=$T/count "$R" "$S" -o "$T/clean.meta" 2> "$T/clean.err"
rc=$?
set -- $(cat "$T/count" 2>/dev/null)
n_alloc=${2:-0}
if [ "$rc" = 0 ] && [ "$n_alloc" -ge 3 ]; then ok "clean run under the fault library ($n_alloc allocations)"
else notok "clean run: exit $rc, $n_alloc allocations: $(cat "$T/clean.err")"; done_tests; fi
[ "$n_alloc" -gt 400 ] && n_alloc=400
bad=0 expr_seen=0 n=1
while [ "$n" -le "$n_alloc" ]; do
	rm -f "$T/o.meta"
	LD_PRELOAD=$LIB LOCUS_FAULT_ALLOC=$n "$R" "$S" -o "$T/o.meta" 2> "$T/o.err"
	rc=$?
	if [ "$rc" != 0 ]; then
		lines=$(wc -l < "$T/o.err")
		if [ "$rc" != 70 ] || [ "$lines" != 1 ] || ! grep -q -e "out of memory" -e "Cannot allocate memory" "$T/o.err" || grep -q "expected memory" "$T/o.err" || [ -e "$T/o.meta" ]; then
			bad=$((bad + 1))
			[ "$bad" -le 3 ] && notok "allocation $n fails: exit $rc, $lines lines: $(head -2 "$T/o.err")"
		fi
		grep -q "oom.scene:2:.*out of memory compiling the expression" "$T/o.err" && expr_seen=$((expr_seen + 1))
	elif ! cmp -s "$T/o.meta" "$T/clean.meta"; then
		bad=$((bad + 1))
		[ "$bad" -le 3 ] && notok "allocation $n fails: exit 0 with a different output"
	fi
	n=$((n + 1))
done
[ "$bad" = 0 ] && ok "every failing allocation of $n_alloc: one 'out of memory' line, exit 70, no output (or exit 0 with the clean output)"
if [ "$expr_seen" -ge 1 ]; then ok "the expression compiler's own failure ($expr_seen of them) says so, at the expression's line"
else notok "no run failed inside the expression compiler"; fi
done_tests

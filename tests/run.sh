#!/bin/sh
# run.sh: run every unit-test program in $TESTBIN and every tests/t_*.sh script;
# each prints "ok - ..."/"not ok - ..." lines, and "SKIP name: reason" for a part it cannot run
# here (../shared absent, a signal it cannot restore). Ends with "N passed, N failed, N skipped"
# (CI reads that line). A program that fails without reporting a failed check counts as one
# failure. Every test runs with a time limit (TEST_TIMEOUT seconds, 1800): one that hangs is
# killed and counts as one failure, and the suite goes on.
set -u
: "${BIN:=bin}" "${TESTBIN:=build/native/tests}"
export BIN TESTBIN
if [ "${SANITIZE:-}" = 1 ]; then
	export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:verify_asan_link_order=0"
	export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
fi
top=$(pwd)
T=$(mktemp -d "${TMPDIR:-/tmp}/locus-test.XXXXXX")
export T
trap 'rm -rf "$T"' EXIT
pass=0; fail=0; skipped=0
: "${TEST_TIMEOUT:=1800}"
run_one() {
	name=$1; shift
	out="$T/$(basename "$name").log"
	timeout -k 10 "$TEST_TIMEOUT" "$@" > "$out" 2>&1 < /dev/null
	rc=$?
	if [ "$rc" = 124 ] || [ "$rc" = 137 ]; then echo "not ok - $name killed after $TEST_TIMEOUT s" >> "$out"; fi
	p=$(grep -c '^ok - ' "$out"); f=$(grep -c '^not ok - ' "$out"); s=$(grep -c '^SKIP ' "$out")
	if [ "$rc" != 0 ] && [ "$f" = 0 ]; then f=1; echo "not ok - $name exited $rc" >> "$out"; fi
	pass=$((pass + p)); fail=$((fail + f)); skipped=$((skipped + s))
	grep '^SKIP ' "$out"
	if [ "$f" != 0 ]; then
		echo "FAIL $name ($p passed, $f failed)"
		grep -v '^ok - ' "$out" | head -40 | sed 's/^/    /'
	else
		echo "PASS $name ($p checks)"
	fi
}
for t in "$TESTBIN"/test_*; do
	[ -x "$t" ] || continue
	run_one "$t" "$t"
done
for t in "$top"/tests/t_*.sh; do
	[ -f "$t" ] || continue
	mkdir -p "$T/work" && rm -rf "$T/work"/* 
	run_one "$t" sh -c "cd '$top' && T='$T/work' sh '$t'"
done
echo "$pass passed, $fail failed, $skipped skipped"
[ "$fail" = 0 ]

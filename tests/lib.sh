# lib.sh: helpers for shell tests. Each check prints "ok - ..." or "not ok - ..." for tests/run.sh.
# Source it; BIN (programs), TESTBIN (unit tests) and T (a scratch directory) are set.
: "${BIN:=bin}"
FAILED=0
ok()    { echo "ok - $*"; }
notok() { echo "not ok - $*"; FAILED=1; }
# check DESC CMD...: passes when CMD exits 0
check() { d=$1; shift; if "$@" >/dev/null 2>&1; then ok "$d"; else notok "$d"; fi; }
# expect_exit CODE DESC CMD...: passes when CMD exits with CODE
expect_exit() { c=$1; d=$2; shift 2; "$@" >/dev/null 2>&1; r=$?; if [ "$r" = "$c" ]; then ok "$d"; else notok "$d (exit $r, wanted $c)"; fi; }
# same_file DESC A B: byte-identical
same_file() { if cmp -s "$2" "$3"; then ok "$1"; else notok "$1 ($2 differs from $3)"; fi; }
done_tests() { exit $FAILED; }

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
# skip REASON: one "SKIP name: reason" line, counted by tests/run.sh (name: the script's name)
skip() { echo "SKIP $(basename "$0"): $*"; }
# need_corpus DIR WHAT: true when ../shared/corpus/DIR is there; otherwise one SKIP line for WHAT
CORPUS_DIR=../shared/corpus
need_corpus() {
	[ -d "$CORPUS_DIR/$1" ] && return 0
	skip "$2: $CORPUS_DIR/$1 is absent (files made by other programs; CI lays ../shared beside the clone)"
	return 1
}
# bounded SECONDS DESC CMD...: runs CMD with a time limit and returns its status; past the limit
# the command is killed (TERM, then KILL 5 s later), the check "DESC" fails with one line and
# bounded returns 124, so a hung child costs one check, not the suite.
bounded() {
	_s=$1 _d=$2; shift 2
	timeout -k 5 "$_s" "$@"
	_r=$?
	[ "$_r" = 124 ] || [ "$_r" = 137 ] && notok "$_d: no answer in $_s s (killed)"
	return "$_r"
}
# wait_bounded SECONDS DESC PID: waits for a background child PID at most SECONDS; past that it
# kills it, fails the check "DESC" and returns 124; otherwise returns the child's status.
wait_bounded() {
	_s=$1 _d=$2 _p=$3 _n=0
	while kill -0 "$_p" 2>/dev/null; do
		# a child that has exited but is not yet reaped still answers kill -0: state Z in /proc
		_st=$(sed 's/.*) //' "/proc/$_p/stat" 2>/dev/null)
		case $_st in Z*) break ;; esac
		if [ "$_n" -ge $((_s * 10)) ]; then
			kill -KILL "$_p" 2>/dev/null
			wait "$_p" 2>/dev/null
			notok "$_d: still running after $_s s (killed)"
			return 124
		fi
		sleep 0.1
		_n=$((_n + 1))
	done
	wait "$_p"
}
# $DEFAULT_SIGNALS CMD... &: runs CMD with SIGHUP, SIGINT, SIGQUIT, SIGTERM and SIGPIPE at their
# default disposition, whatever this shell inherited (nohup ignores HUP; a background job of a
# non-interactive shell starts with INT and QUIT ignored, and a shell cannot undo an ignore it
# inherited). coreutils' env has --default-signal since 8.31 (Debian 12: 9.1), and it execs CMD,
# so $! is CMD's pid. (A variable, not a function: a function run with & is a subshell.)
DEFAULT_SIGNALS="env --default-signal=HUP,INT,QUIT,TERM,PIPE"

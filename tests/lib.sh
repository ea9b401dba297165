# Shared helpers of the shell tests: paths, a temporary directory, and checks that say what failed.
top_srcdir=${top_srcdir:-$(cd "$(dirname "$0")/.." && pwd)}
top_builddir=${top_builddir:-$top_srcdir}
AALAB="$top_builddir/aalab"
export AALAB_SCENE_DIR="${AALAB_SCENE_DIR:-$top_srcdir/scenes}"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
TMP=$(mktemp -d "${TMPDIR:-/tmp}/aalab-test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
failures=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

# expect_status STATUS DESCRIPTION -- command...: runs the command, checks its exit status
expect_status() {
	want=$1; what=$2; shift 3
	"$@" >"$TMP/out" 2>"$TMP/err"
	got=$?
	if [ "$got" -eq "$want" ]; then pass "$what (exit $got)"; else
		fail "$what: exit $got, expected $want"; sed 's/^/  | /' "$TMP/err" | head -20; fi
}

# expect_stderr PATTERN DESCRIPTION: the last command's stderr matches the extended regex
expect_stderr() {
	if grep -Eq -- "$1" "$TMP/err"; then pass "$2"; else
		fail "$2: stderr does not match /$1/"; sed 's/^/  | /' "$TMP/err" | head -20; fi
}

finish() { [ "$failures" -eq 0 ] && exit 0 || exit 1; }

# start_daemon [AALABD ARGS...]: aalabd on $TMP/aalabd.sock, its state in $TMP/state and its log in
# $TMP/daemon.log, stopped by its PID on exit; returns once it is ready. Sets sock, daemon (the PID) and,
# with --http 127.0.0.1:0, port.
start_daemon() {
	sock="$TMP/aalabd.sock"
	"$top_builddir/aalabd" --socket "$sock" --state-dir "$TMP/state" "$@" >"$TMP/daemon.log" 2>&1 &
	daemon=$!
	trap 'kill $daemon 2>/dev/null; wait $daemon 2>/dev/null; rm -rf "$TMP"' EXIT
	i=0
	until grep -qs "aalabd: ready" "$TMP/daemon.log"; do
		i=$((i + 1)); [ $i -gt 600 ] && { cat "$TMP/daemon.log"; fail "aalabd did not start"; finish; }
		kill -0 $daemon 2>/dev/null || { cat "$TMP/daemon.log"; fail "aalabd exited"; finish; }
		sleep 0.1
	done
	port=$(sed -n 's/^aalabd: listening (http) on 127.0.0.1:\([0-9]*\)$/\1/p' "$TMP/daemon.log")
}

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

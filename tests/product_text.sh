#!/bin/sh
# What users read speaks of the product only: no issue numbers ("issue 17", "#14"), no links outside the
# repository (../shared/..., DESIGN.md) in README, NEWS, docs/ (pages and man pages) and the output of
# every command's help, `aalab methods`, `aalab scenes` and `aalab suites`. Colours written as "#RRGGBB"
# or "#RRGGBBAA" are not issue numbers. Every hit is printed with where it was found. History belongs in
# NEWS, measurements in docs/benchmarks.md.
. "$(dirname "$0")/lib.sh"

pattern='issue [0-9]|#[0-9]{2}|\.\./shared|DESIGN\.md'
# hex colours, removed from a line before it is matched
colour='#[0-9A-Fa-f]{6}([0-9A-Fa-f]{2})?([^0-9A-Za-z_]|$)'

# check_text NAME FILE: FILE holds text users read; NAME says where it comes from
check_text() {
	hits=$(sed -E "s/$colour/\\2/g" "$2" | grep -nEi -- "$pattern")
	if [ -n "$hits" ]; then
		fail "$1 names development history or a file outside the repository:"
		printf '%s\n' "$hits" | sed 's/^/  | /'
	else
		checked=$((checked + 1))
	fi
}

checked=0
for f in "$top_srcdir/README.md" "$top_srcdir/NEWS" "$top_srcdir"/docs/*.md "$top_srcdir"/docs/*.[0-9]; do
	[ -f "$f" ] || { fail "missing: $f"; continue; }
	check_text "${f#"$top_srcdir"/}" "$f"
done

# help_text NAME -- COMMAND...: COMMAND's output (stdout and stderr) is text users read; it must say something
help_text() {
	name=$1; shift 2
	"$@" >"$TMP/help" 2>&1
	if [ ! -s "$TMP/help" ]; then fail "$name printed nothing"; return; fi
	check_text "$name" "$TMP/help"
}

help_text "aalab --help" -- "$AALAB" --help
# every subcommand aalab lists, so that a new one is checked without editing this test
commands=$(sed -n '/^commands:/,/^$/s/^  \([a-z][a-z-]*\) .*/\1/p' "$TMP/help")
count=$(printf '%s\n' "$commands" | grep -c .)
[ "$count" -ge 10 ] || fail "aalab --help lists $count commands; expected the table of subcommands"
for c in $commands; do
	help_text "aalab $c --help" -- "$AALAB" "$c" --help
done
help_text "aalab methods" -- "$AALAB" methods
help_text "aalab methods --json" -- "$AALAB" methods --json
help_text "aalab scenes" -- "$AALAB" scenes
help_text "aalab suites" -- "$AALAB" suites
help_text "aalabd --help" -- "$top_builddir/aalabd" --help

[ "$failures" -eq 0 ] && pass "$checked texts speak of the product only ($count subcommands' help)"
finish

#!/bin/sh
# make update-golden: runs each golden test program in update mode ($AALAB_GOLDEN_OUT), which writes its
# values instead of comparing them, shows `diff -u` against the committed file under tests/golden/, and
# replaces the committed file only when accepted: ACCEPT=yes, or "y" at the prompt (ACCEPT=no: diff only).
# Arguments: the test programs (built); each names its file in the golden_open() call of its source.
set -u
top_srcdir=${top_srcdir:-$(cd "$(dirname "$0")/../.." && pwd)}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/aalab-golden.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
status=0
for prog in "$@"; do
	src="$top_srcdir/$prog.c"
	name=$(sed -n 's/.*golden_open("\([^"]*\)").*/\1/p' "$src" | head -1)
	if [ -z "$name" ]; then echo "update-golden: $src calls no golden_open"; exit 1; fi
	golden="$top_srcdir/tests/golden/$name"
	new="$tmp/$name"
	{
		echo "# Golden values of $prog (KEY<TAB>VALUE, one a line), written by \`make update-golden\`."
		echo "# Review the diff of this file like code: each changed line is a number that moved."
	} >"$new"
	echo "update-golden: running $prog (a minute or two)"
	if ! AALAB_GOLDEN_OUT="$new" "./$prog" >"$tmp/$name.log" 2>&1; then
		cat "$tmp/$name.log"
		echo "update-golden: $prog failed; nothing replaced"
		exit 1
	fi
	if [ -f "$golden" ] && cmp -s "$golden" "$new"; then
		echo "update-golden: $name unchanged"
		continue
	fi
	diff -u "$golden" "$new" 2>/dev/null || [ -f "$golden" ] || cat "$new"
	answer=${ACCEPT:-}
	if [ -z "$answer" ]; then
		if [ -t 0 ]; then
			printf 'update-golden: replace tests/golden/%s with these values? [y/N] ' "$name"
			read -r answer
		else
			answer=no
		fi
	fi
	case "$answer" in
	y|Y|yes|YES)
		cp "$new" "$golden"
		echo "update-golden: tests/golden/$name replaced; commit it with a message that says why the numbers moved";;
	*)
		echo "update-golden: tests/golden/$name left as it was (make update-golden ACCEPT=yes to replace it)"
		status=1;;
	esac
done
exit $status

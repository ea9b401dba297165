#!/bin/sh
# docs/job-format.md's key table lists every top-level key the job parser accepts (the list its
# "unknown key" error gives), so that a key added to the parser is documented.
. "$(dirname "$0")/lib.sh"

doc="$top_srcdir/docs/job-format.md"
printf '{"unknown_key_for_the_list": 1}\n' >"$TMP/job.json"
expect_status 2 "a job with an unknown key is refused" -- "$AALAB" run --local "$TMP/job.json" --out "$TMP/out"
keys=$(sed -n 's/.*unknown key; valid keys: //p' "$TMP/err" | tr -d ',')
[ -n "$keys" ] || fail "the refusal lists no valid keys"
n=0
for k in $keys; do
	n=$((n + 1))
	# a row of the table: | `key` | ... or | `a`, `key` | ...
	if grep -Eq "^\| (\`[a-z_]+\`, )*\`$k\`( \||,)" "$doc"; then :; else
		fail "docs/job-format.md's key table has no row for \`$k\`"
	fi
done
[ "$failures" -eq 0 ] && pass "docs/job-format.md lists all $n keys the parser accepts"
finish

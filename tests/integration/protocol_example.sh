#!/bin/sh
# docs/protocol.md is enough to write a client: its Python example, taken from the document as is, submits
# a job to a real aalabd and reads its stream with frames.
. "$(dirname "$0")/../lib.sh"
start_daemon
# the first ```python block of the document
sed -n '/^```python$/,/^```$/p' "$top_srcdir/docs/protocol.md" | sed '1d;$d' >"$TMP/example.py"
[ -s "$TMP/example.py" ] && pass "docs/protocol.md has a Python example" || fail "no python block in docs/protocol.md"
expect_status 0 "the example runs" -- timeout 120 /usr/bin/python3 "$TMP/example.py" "$sock"
cat "$TMP/out"
[ "$(grep -c '^frame .* PNG bytes [1-9]' "$TMP/out")" -eq 4 ] && pass "it printed 4 method frames with PNGs" || fail "frames"
grep -q '^job_finished .*"label": "ssaa:4"' "$TMP/out" && pass "and the summary" || fail "no job_finished"
kill -TERM $daemon; wait $daemon
[ $? -eq 0 ] && pass "aalabd exits 0" || fail "aalabd exit status"
finish

#!/bin/sh
# The dashboard's trends in headless Chromium: after three labelled jobs of a suite, each case has a chart
# with one line per method through three points, and the x axis reads the jobs' commits in submission
# order; the verdict against a baseline shows in the job list. Skipped without chromium.
. "$(dirname "$0")/../lib.sh"
command -v chromium >/dev/null 2>&1 || { echo "SKIP: chromium not installed (scripts/install-deps.sh)"; exit 77; }
start_daemon --http 127.0.0.1:0
cat >"$TMP/suite.json" <<'JSON'
{"suite": "trend", "scenes": ["thin-wires", "hard-edges"], "size": "64x36", "frames": 2, "reference": {"samples": 4},
 "methods": ["none", "fxaa", "smaa"], "keep_frames": false}
JSON
for commit in c1 c2 c3; do
	expect_status 0 "labelled job $commit" -- "$AALAB" submit "$TMP/suite.json" --label commit=$commit --label branch=main \
		--baseline latest:branch=main --watch --quiet --connect "unix:$sock"
done
browse() {
	timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-background-networking \
		--disable-component-update --disable-sync --no-first-run --user-data-dir="$TMP/profile" \
		--virtual-time-budget=8000 "$@" "http://127.0.0.1:$port/" 2>"$TMP/chromium.err"
}
browse --dump-dom >"$TMP/dom.html"
/usr/bin/python3 - "$TMP/dom.html" <<'PY' && pass "a trend chart per case, a line per method through three jobs, commits c1 c2 c3 on the x axis" || { fail "trend charts"; head -c 3000 "$TMP/dom.html"; }
import re, sys
dom = open(sys.argv[1]).read()
charts = re.findall(r'<svg[^>]*class="trend-chart"[^>]*data-case="([^"]*)"(.*?)</svg>', dom, re.S)
assert [c[0] for c in charts] == ["thin-wires/default/64x36", "hard-edges/default/64x36"], [c[0] for c in charts]
for case, body in charts:
    lines = re.findall(r'<polyline[^>]*data-method="([^"]*)"[^>]*points="([^"]*)"', body)
    assert sorted(m for m, _ in lines) == ["fxaa", "none", "smaa"], lines
    assert all(len(p.split()) == 3 for _, p in lines), lines
    assert re.findall(r'<text class="commit"[^>]*>([^<]*)</text>', body) == ["c1", "c2", "c3"]
PY
grep -q 'class="verdict-held">held<' "$TMP/dom.html" && pass "the job list shows the verdict" || fail "verdict not shown"
grep -q 'commit=c3 branch=main' "$TMP/dom.html" && pass "and the labels" || fail "labels not shown"
browse --screenshot="$TMP/trends.png" --window-size=1200,1400 >/dev/null
[ -s "$TMP/trends.png" ] && pass "screenshot taken" || fail "no screenshot"
[ -n "$AALAB_KEEP_SCREENSHOT" ] && cp "$TMP/trends.png" "$AALAB_KEEP_SCREENSHOT"
kill -TERM $daemon; wait $daemon
[ $? -eq 0 ] && pass "aalabd exits 0" || fail "aalabd exit status"
finish

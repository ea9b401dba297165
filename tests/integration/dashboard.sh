#!/bin/sh
# The dashboard page served by aalabd, in headless Chromium: it lists the jobs and draws the finished
# job's cost-vs-accuracy chart (one point per method) from the polled /v1/jobs. Skipped without chromium.
. "$(dirname "$0")/../lib.sh"
command -v chromium >/dev/null 2>&1 || { echo "SKIP: chromium not installed (scripts/install-deps.sh)"; exit 77; }
start_daemon --http 127.0.0.1:0
expect_status 0 "a job runs" -- "$AALAB" submit --watch --quiet --connect "unix:$sock" --scene thin-wires \
	--methods none,ssaa:4 --frames 2 --size 64x36 --reference-samples 4
id=$(head -1 "$TMP/out")
browse() {
	timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-background-networking \
		--disable-component-update --disable-sync --no-first-run --user-data-dir="$TMP/profile" \
		--virtual-time-budget=5000 "$@" "http://127.0.0.1:$port/" 2>"$TMP/chromium.err"
}
browse --dump-dom >"$TMP/dom.html"
grep -q "data-job=\"$id\"" "$TMP/dom.html" && pass "the page lists job $id" || { fail "job $id not listed"; head -c 2000 "$TMP/dom.html"; }
points=$(grep -o '<g class="point[^"]*" data-method=' "$TMP/dom.html" | wc -l)
[ "$points" -eq 2 ] && pass "the chart has one point per method" || fail "chart points: $points"
grep -q 'GPU ms per frame' "$TMP/dom.html" && grep -q 'ssaa:4' "$TMP/dom.html" && pass "axes and labels drawn" || fail "chart labels"
# the verdict line is results.json's headline as it is, and the warnings follow it
headline=$("$AALAB" get "$id" --connect "unix:$sock" --json | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)["verdict"]["headline"])')
grep -qF "<p class=\"front\">verdict: $headline</p>" "$TMP/dom.html" && pass "the detail shows the verdict: $headline" ||
	{ fail "verdict line '$headline' not shown"; grep -o '<div id="detail">.\{0,600\}' "$TMP/dom.html"; }
grep -q '<li class="warning"><b>psnr-at-reference-noise</b>\|<li class="warning"><b>reference-not-converged</b>' "$TMP/dom.html" &&
	pass "the detail lists the warnings (4-sample reference)" || fail "warnings not shown"
browse --screenshot="$TMP/dashboard.png" --window-size=900,700 >/dev/null
[ -s "$TMP/dashboard.png" ] && pass "screenshot taken" || fail "no screenshot"
[ -n "$AALAB_KEEP_SCREENSHOT" ] && cp "$TMP/dashboard.png" "$AALAB_KEEP_SCREENSHOT"
kill -TERM $daemon; wait $daemon
[ $? -eq 0 ] && pass "aalabd exits 0" || fail "aalabd exit status"
finish

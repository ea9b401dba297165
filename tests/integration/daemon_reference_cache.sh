#!/bin/sh
# aalabd's store of reference frames: by default STATE_DIR/references; a job run twice reads every
# reference from it the second time (results.json says so, with the same metrics), and /metrics counts
# the hits, misses and bytes; a setting that cannot be used stops the start-up naming it.
. "$(dirname "$0")/../lib.sh"

expect_status 2 "a reference-cache-size under 1M" -- "$top_builddir/aalabd" --socket "$TMP/x.sock" \
	--state-dir "$TMP/x" --reference-cache-size 100K
expect_stderr "reference-cache-size" "the size names its setting"
expect_status 1 "a reference-cache that cannot be made" -- "$top_builddir/aalabd" --socket "$TMP/y.sock" \
	--state-dir "$TMP/y" --reference-cache /proc/aalab-references
expect_stderr "^aalabd: reference-cache: .*/proc/aalab-references" "the folder names its setting"

start_daemon --http 127.0.0.1:0
job="--connect unix:$sock --scene moving-sphere --methods none --frames 2 --size 64x36 --reference-samples 8 --quiet"
expect_status 0 "a job on aalabd" -- "$AALAB" run $job --out "$TMP/a"
expect_status 0 "the same job again" -- "$AALAB" run $job --out "$TMP/b"
/usr/bin/python3 - "$TMP/a/results.json" "$TMP/b/results.json" <<'PY' && pass "the second job read both references from the store, same metrics" || fail "results.json reference.cache"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["reference"]["cache"]["misses"] == 2, a["reference"]["cache"]
assert b["reference"]["cache"]["hits"] == 2 and b["reference"]["cache"]["misses"] == 0, b["reference"]["cache"]
assert a["methods"][0]["metrics"] == b["methods"][0]["metrics"]
PY
[ -n "$(find "$TMP/state/references" -name '*.ref')" ] && pass "entries under STATE_DIR/references" ||
	fail "no entry under STATE_DIR/references"
/usr/bin/python3 - "$port" <<'PY' && pass "/metrics: 2 hits, 2 misses, bytes read and written" || fail "/metrics"
import sys, urllib.request
text = urllib.request.urlopen("http://127.0.0.1:%s/metrics" % sys.argv[1], timeout=10).read().decode()
v = {l.split()[0]: float(l.split()[1]) for l in text.splitlines() if l.startswith("aalab_reference_cache_")}
assert v["aalab_reference_cache_hits_total"] == 2 and v["aalab_reference_cache_misses_total"] == 2, v
assert v["aalab_reference_cache_read_bytes_total"] > 0 and v["aalab_reference_cache_written_bytes_total"] > 0, v
assert "aalab_reference_cache_evictions_total" in v and "aalab_reference_cache_discarded_total" in v, v
PY
finish

#!/bin/sh
# The store of reference frames from the command line: a second run reads every reference from it (the
# table's first line and the report's card say so) with the same metrics; --reference-cache off stores
# nothing; a damaged entry is reported, removed and rendered again; --explain-key names the parts; bad
# settings name the field; aalab cache stats, verify and clear.
. "$(dirname "$0")/lib.sh"

store="$TMP/store"
job="--local --scene moving-sphere --methods none,fxaa --frames 2 --size 64x36 --reference-samples 8 --quiet"
expect_status 0 "a first run fills the store" -- "$AALAB" run $job --reference-cache "$store" --out "$TMP/a"
grep -q "reference 8 samples, from the cache: 0 of 2 frames" "$TMP/out" && pass "first line: 0 of 2" ||
	fail "first line: $(head -1 "$TMP/out")"
expect_status 0 "a second run" -- "$AALAB" run $job --reference-cache "$store" --out "$TMP/b"
grep -q "reference 8 samples, from the cache: 2 of 2 frames" "$TMP/out" && pass "first line: 2 of 2" ||
	fail "first line: $(head -1 "$TMP/out")"
grep -q "8 samples, from the cache: 2 of 2 frames" "$TMP/b/report.html" && pass "the report's Reference card" ||
	fail "no cache in the report's Reference card"
/usr/bin/python3 - "$TMP/a/results.json" "$TMP/b/results.json" <<'PY' && pass "results.json: reference.cache, the same metrics to the byte" || fail "results.json of the second run"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
ca, cb = a["reference"]["cache"], b["reference"]["cache"]
assert ca["misses"] == 2 and ca["hits"] == 0 and ca["bytes_written"] > 0, ca
assert cb["hits"] == 2 and cb["misses"] == 0 and cb["bytes_read"] > 0 and cb["bytes_written"] == 0, cb
assert [f["cache"] for f in b["reference"]["per_frame"]] == ["hit", "hit"]
for ma, mb in zip(a["methods"], b["methods"]):
    assert ma["metrics"] == mb["metrics"], ma["label"]
    drop = ("gpu_ms", "cpu_ms", "passes")  # the times of this run; everything else is quality
    fa = [{k: v for k, v in f.items() if k not in drop} for f in ma["frames"]]
    fb = [{k: v for k, v in f.items() if k not in drop} for f in mb["frames"]]
    assert fa == fb and len(fa) == 2, ma["label"]
PY
for f in frames/reference/0001.png frames/fxaa/0001.png diff/fxaa/0001.png; do
	cmp -s "$TMP/a/$f" "$TMP/b/$f" || fail "$f differs between the runs"
done

expect_status 0 "--reference-cache off" -- "$AALAB" run $job --reference-cache off --out "$TMP/c"
grep -q "from the cache" "$TMP/out" && fail "off: the first line names a store" || pass "off: no store named"
grep -q '"cache": null' "$TMP/c/results.json" && pass "off: reference.cache is null" || fail "off: reference.cache"

expect_status 0 "--explain-key" -- "$AALAB" run $job --reference-cache "$store" --out "$TMP/d" --explain-key
for part in scene camera time size samples pattern accumulation alpha-rule lod-bias shaders code device driver; do
	grep -Eq "^  $part +[0-9a-f]{12}  " "$TMP/err" || fail "--explain-key has no part $part"
done
grep -q "frame 1: reference key [0-9a-f]*: in the store" "$TMP/err" && pass "--explain-key: each frame's key" ||
	fail "--explain-key: $(head -3 "$TMP/err")"

# damage one entry: its last byte (the CRC) flipped
entry=$(find "$store" -name '*.ref' | head -1)
/usr/bin/python3 -c "import sys; p = sys.argv[1]; b = bytearray(open(p, 'rb').read()); b[-1] ^= 1; open(p, 'wb').write(b)" "$entry"
expect_status 0 "a run over a damaged entry" -- "$AALAB" run $job --reference-cache "$store" --out "$TMP/e"
expect_stderr "warning: reference cache: entry [0-9a-f]{16} failed its check: its CRC-32 does not match its bytes.*removed, rendering it again" \
	"the damaged entry is reported"
grep -q "from the cache: 1 of 2 frames" "$TMP/out" && pass "the damaged frame is rendered again" || fail "$(head -1 "$TMP/out")"
# and it is one of the run's warnings, where every other warning is: results.json and after the table
/usr/bin/python3 -c 'import json,sys; w=json.load(open(sys.argv[1]))["warnings"]; sys.exit(not any(x["code"] == "reference-cache" and "CRC-32" in x["message"] for x in w))' \
	"$TMP/e/results.json" && pass "results.json's warnings name the damaged entry" || fail "no reference-cache warning in results.json"
grep -q "failed its check" "$TMP/out" && pass "the table's warnings name it" || fail "the table's warnings do not name it"
grep -q '"discarded": 1' "$TMP/e/results.json" && pass "results.json counts it" || fail "discarded not counted"

expect_status 2 "a size that is too small" -- "$AALAB" run $job --reference-cache-size 12K --out "$TMP/f"
expect_stderr "^aalab run: --reference-cache-size: expected a size of at least 1M" "the size names its field"
expect_status 2 "a store that cannot be made" -- "$AALAB" run $job --reference-cache /proc/aalab-store --out "$TMP/f"
expect_stderr "^aalab run: --reference-cache: .*/proc/aalab-store" "the folder names its field"
expect_status 2 "an empty store name" -- "$AALAB" run $job --reference-cache "" --out "$TMP/f"
expect_stderr "reference-cache: expected a folder or 'off'" "an empty name"

expect_status 0 "aalab cache stats" -- "$AALAB" cache stats --reference-cache "$store" --json
/usr/bin/python3 - "$TMP/out" <<'PY' && pass "stats: entries, bytes, hits, misses, damaged" || fail "stats: $(cat "$TMP/out")"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["entries"] == 2 and s["bytes"] > 0 and s["hits"] >= 4 and s["misses"] >= 3 and s["discarded"] == 1, s
PY
expect_status 0 "aalab cache verify" -- "$AALAB" cache verify --reference-cache "$store" --sample 2
grep -q "^2 of 2 identical$" "$TMP/out" && pass "verify: 2 of 2 identical" || fail "verify: $(tail -1 "$TMP/out")"
expect_status 2 "cache: an unknown action" -- "$AALAB" cache sweep --reference-cache "$store"
expect_status 2 "cache: --sample without verify" -- "$AALAB" cache stats --sample 3 --reference-cache "$store"
expect_status 0 "aalab cache clear" -- "$AALAB" cache clear --reference-cache "$store"
grep -q "removed 2 entries" "$TMP/out" && pass "clear removes every entry" || fail "clear: $(cat "$TMP/out")"
[ -z "$(find "$store" -name '*.ref')" ] && pass "no entry left" || fail "entries left after clear"
finish

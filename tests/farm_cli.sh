#!/bin/sh
# Suites and `aalab compare` end to end, as a build farm uses them: a suite run with labels writes one
# results.json with a case per scene and one report; a run compared with itself holds every gate; a run
# with fxaa degraded (fxaa:preset=10,edge_threshold=0.333) trips the PSNR gate and names the case, pairing
# the new label with fxaa and showing the parameters; the JUnit file validates against tests/junit.xsd
# (the subset of Jenkins's junit-10.xsd that Jenkins and GitLab read, made stricter) with lxml; runs that
# do not share their cases, bad gates and bad files exit 2 naming what is wrong.
. "$(dirname "$0")/lib.sh"
PY=/usr/bin/python3

mkdir -p "$TMP/suites"
cat >"$TMP/suites/farmtest.json" <<'JSON'
{"suite": "farmtest", "name": "farm test", "scenes": ["thin-wires", "cutout-fence"], "sizes": ["64x36"],
 "frames": 2, "reference": {"samples": 4}, "timing": {"repeat": 3}, "methods": ["none", "fxaa", "smaa"]}
JSON
sed 's/"fxaa"/"fxaa:preset=10,edge_threshold=0.333"/' "$TMP/suites/farmtest.json" >"$TMP/degraded.json"

expect_status 0 "a suite runs with labels" -- "$AALAB" run "$TMP/suites/farmtest.json" --label commit=A \
	--label branch=main --label build_url=https://ci.example/1 --quiet --out "$TMP/a"
grep -q "thin-wires/default/64x36" "$TMP/out" && grep -q "cutout-fence/default/64x36" "$TMP/out" &&
	grep -q "commit=A" "$TMP/out" && pass "the table runs across both cases with the labels" ||
	{ fail "suite table"; cat "$TMP/out"; }
$PY - "$TMP/a" <<'PY' && pass "results.json: one document, a case each, ids, labels, job hash, images that exist" || fail "suite results.json"
import json, os, sys
d = sys.argv[1]
r = json.load(open(os.path.join(d, "results.json")))
assert r["suite"] == "farmtest" and r["labels"] == {"commit": "A", "branch": "main", "build_url": "https://ci.example/1"}, r["labels"]
assert r["job_hash"].startswith("sha256:") and len(r["job_hash"]) == 71
assert [c["id"] for c in r["cases"]] == ["thin-wires/default/64x36", "cutout-fence/default/64x36"]
assert [c["dir"] for c in r["cases"]] == ["cases/thin-wires_default_64x36", "cases/cutout-fence_default_64x36"]
assert len(r["job"]["cases"]) == 2 and "scene" not in r["job"]
for c in r["cases"]:
    # inside, the schema of a job's results.json
    assert c["scene"]["name"] == c["id"].split("/")[0] and c["size"] == {"width": 64, "height": 36}
    assert [m["label"] for m in c["methods"]] == ["none", "fxaa", "smaa"]
    for m in c["methods"]:
        for f in m["frames"]:
            for k in ("image", "diff", "flip_map"):
                assert f[k].startswith(c["dir"] + "/") and os.path.exists(os.path.join(d, f[k])), f[k]
    assert os.path.exists(os.path.join(d, c["dir"], "report.html"))
PY
grep -q 'href="cases/cutout-fence_default_64x36/report.html"' "$TMP/a/report.html" &&
	grep -q "Summary across cases" "$TMP/a/report.html" && grep -q "branch=main" "$TMP/a/report.html" &&
	pass "report.html: the summary across cases links each case's report and shows the labels" || fail "suite report"
# the cases x methods matrix: each cell the PSNR over none of results.json, the front ringed
$PY - "$TMP/a" <<'PY' && pass "report.html: the matrix's cells are results.json's PSNR over none, the front ringed" || fail "suite matrix"
import json, os, re, sys
d = sys.argv[1]
r = json.load(open(os.path.join(d, "results.json")))
page = open(os.path.join(d, "report.html")).read()
table = re.search(r'<table class="matrix">(.*?)</table>', page, re.S).group(1)
rows = re.findall(r'<tr><th class="case"><a [^>]*>([^<]*)</a></th>(.*?)</tr>', table)
assert [c for c, _ in rows] == [c["id"] for c in r["cases"]], rows
for (cid, body), case in zip(rows, r["cases"]):
    cells = re.findall(r'<td class="n( front)?"[^>]*>([^<]*)</td>', body)
    ms = case["methods"]
    none = next(m for m in ms if m["label"] == "none")["metrics"]["psnr"]["mean"]
    want = [("%+.1f" % (m["metrics"]["psnr"]["mean"] - none), m["label"] in case["verdict"]["front"]) for m in ms]
    got = [(text, bool(front)) for front, text in cells]
    assert got == want, (cid, got, want)
PY
grep -q "Labels" "$TMP/a/cases/thin-wires_default_64x36/report.html" && pass "a case's report shows the labels" ||
	fail "case report labels"

AALAB_SUITE_DIR="$TMP/suites" expect_status 0 "a suite is found by name" -- "$AALAB" run farmtest --no-images \
	--quiet --out "$TMP/by-name"
# the shipped suites are valid jobs (full.json once had 17 methods, one over a job's limit, unnoticed)
AALAB_SUITE_DIR="$top_srcdir/suites" expect_status 0 "aalab suites" -- "$AALAB" suites --json
/usr/bin/python3 -c '
import json, sys
s = {x["name"]: x for x in json.load(open(sys.argv[1]))}
assert all("error" not in x for x in s.values()), s
assert (s["smoke"]["cases"], s["smoke"]["methods"]) == (6, 18) and (s["full"]["cases"], s["full"]["methods"]) == (16, 23), s
assert (s["hard"]["cases"], s["hard-cases"]["cases"], s["hard-cases"]["methods"]) == (7, 16, 20), s
' "$TMP/out" && pass "the shipped suites (smoke, full, hard) are valid jobs" || { fail "shipped suites"; cat "$TMP/out"; }
# a suite of the user's with a user method is listed as valid (its method file read as aalab run reads it)
mkdir -p "$TMP/user-suites"
echo '{"suite": "withuser", "scenes": ["hard-edges"], "sizes": ["64x36"], "methods": ["none",
 "user:file='"$top_srcdir"'/examples/methods/edge_blur.json"]}' >"$TMP/user-suites/withuser.json"
AALAB_SUITE_DIR="$TMP/user-suites" expect_status 0 "aalab suites with a user method" -- "$AALAB" suites --json
/usr/bin/python3 -c '
import json, sys
s = {x["name"]: x for x in json.load(open(sys.argv[1]))}
assert "error" not in s["withuser"] and s["withuser"]["methods"] == 2, s["withuser"]
' "$TMP/out" && pass "a suite with a user method is listed as valid" || { fail "suite with a user method"; cat "$TMP/out"; }
expect_status 2 "an unknown suite name" -- "$AALAB" run no-such-suite --quiet --out "$TMP/x"
expect_stderr "no suite of that name \(suites:.*smoke" "says which suites exist"
expect_status 2 "scene and scenes together" -- "$AALAB" run "$TMP/suites/farmtest.json" --scene hard-edges --quiet \
	--out "$TMP/x"
expect_stderr "scenes: give either \"scene\" or \"scenes\"" "names the field"
expect_status 2 "a label without a value" -- "$AALAB" run "$TMP/suites/farmtest.json" --label commit --quiet --out "$TMP/x"
expect_stderr "--label: \"commit\" is not a label; write KEY=VALUE" "names --label"
expect_status 2 "a baseline needs aalabd" -- "$AALAB" run "$TMP/suites/farmtest.json" --baseline 000001 --local \
	--quiet --out "$TMP/x"
expect_stderr "^aalab run: baseline: " "names baseline"

expect_status 0 "a run compared with itself" -- "$AALAB" compare "$TMP/a" "$TMP/a/results.json" --json
$PY -c '
import json, sys
c = json.load(open(sys.argv[1]))
n = c["counts"]
assert c["verdict"] == "held" and n["gates"] == 2 * 3 * 6 and n["held"] == n["gates"], n
' "$TMP/out" && pass "every gate held (2 cases x 3 methods x 6 default gates)" || fail "self-compare: $(head -c 300 "$TMP/out")"

expect_status 0 "the degraded run" -- "$AALAB" run "$TMP/degraded.json" --label commit=B --quiet --out "$TMP/b"
expect_status 1 "compare trips" -- "$AALAB" compare "$TMP/a" "$TMP/b" --junit "$TMP/junit.xml" --markdown "$TMP/summary.md"
grep -q "tripped psnr < -0.1 in cutout-fence/default/64x36, fxaa:preset=10,edge_threshold=0.333" "$TMP/out" &&
	pass "names the case, the method and the PSNR gate" || { fail "tripped gate not named"; cat "$TMP/out"; }
grep -q "was fxaa (paired by name): preset 12 -> 10, edge_threshold 0.166 -> 0.333" "$TMP/out" &&
	pass "the new label pairs with fxaa and the parameter change is shown" || fail "pairing note"
expect_status 1 "the same as JSON" -- "$AALAB" compare "$TMP/a" "$TMP/b" --json
$PY -c '
import json, sys
c = json.load(open(sys.argv[1]))
tripped = {(t["case"], t["method"], t["gate"]) for t in c["tripped"]}
assert ("cutout-fence/default/64x36", "fxaa:preset=10,edge_threshold=0.333", "psnr < -0.1") in tripped, tripped
assert all(t[1] != "none" and t[1] != "smaa" for t in tripped), tripped
m = [m for m in c["cases"][1]["methods"] if m["base_label"] == "fxaa"][0]
assert m["paired_by"] == "name" and m["metrics"]["psnr"]["change"] < -0.1
' "$TMP/out" && pass "only the degraded method trips" || fail "JSON tripped list"

$PY - "$top_srcdir/tests/junit.xsd" "$TMP/junit.xml" <<'PY' && pass "JUnit validates against tests/junit.xsd; counts add up; the failure is there" || fail "JUnit"
import sys
from lxml import etree
schema = etree.XMLSchema(etree.parse(sys.argv[1]))
doc = etree.parse(sys.argv[2])
schema.assertValid(doc)
root = doc.getroot()
cases = root.findall("testsuite/testcase")
assert len(cases) == int(root.get("tests")) == 2 * 3 * 6
assert sum(int(s.get("tests")) for s in root.findall("testsuite")) == len(cases)
failed = [c for c in cases if c.find("failure") is not None]
assert len(failed) == int(root.get("failures")) >= 1
assert any(c.get("classname") == "cutout-fence/default/64x36" and
           c.get("name") == "fxaa:preset=10,edge_threshold=0.333: psnr < -0.1" for c in failed)
PY
grep -q "aalab compare: \*\*FAILED\*\*" "$TMP/summary.md" &&
	grep -q '| cutout-fence/default/64x36 | fxaa:preset=10,edge_threshold=0.333 | `psnr < -0.1` |' "$TMP/summary.md" &&
	pass "the markdown summary lists the tripped gate" || { fail "markdown"; cat "$TMP/summary.md"; }
expect_status 2 "an unwritable JUnit file" -- "$AALAB" compare "$TMP/a" "$TMP/a" --junit "$TMP/no/such/dir/j.xml"

# runs that do not share their cases
expect_status 0 "a plain job of one of the cases" -- "$AALAB" run --scene thin-wires --size 64x36 --frames 2 \
	--reference-samples 4 --repeat 3 --methods none,fxaa,smaa --no-images --quiet --out "$TMP/plain"
expect_status 2 "cases missing" -- "$AALAB" compare "$TMP/a" "$TMP/plain"
expect_stderr "the runs do not share their cases: missing from NEW: cutout-fence/default/64x36" "names the missing case"
expect_status 0 "--allow-missing compares the case both have" -- "$AALAB" compare "$TMP/a" "$TMP/plain" --allow-missing
grep -q "case cutout-fence/default/64x36: only in BASE, not compared" "$TMP/out" && pass "and says which it left out" ||
	fail "allow-missing note"

# bad input
expect_status 2 "a bad gate" -- "$AALAB" compare "$TMP/a" "$TMP/a" --fail-if "psnr dropped"
expect_stderr "^aalab compare: --fail-if: \"psnr dropped\" is not a gate" "names --fail-if and shows the grammar"
expect_status 2 "one run only" -- "$AALAB" compare "$TMP/a"
echo '{"cases": [{"id": "x", "methods": [{"label": 3}]}]}' >"$TMP/bad.json"
expect_status 2 "a file that is not results.json" -- "$AALAB" compare "$TMP/a" "$TMP/bad.json"
expect_stderr "NEW cases\[0\].methods\[0\].label: expected the method's label" "names the run and the field"
echo '{"cases": [' >"$TMP/broken.json"
expect_status 2 "a file that is not JSON" -- "$AALAB" compare "$TMP/broken.json" "$TMP/a"
expect_stderr "BASE: .*broken.json:" "names the run and the file"
expect_status 2 "nothing there" -- "$AALAB" compare "$TMP/nothing" "$TMP/a"
expect_stderr "BASE: '.*nothing' is neither a results folder" "says what it expected"
finish

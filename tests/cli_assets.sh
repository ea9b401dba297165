#!/bin/sh
# Mesh files from the command line: every refusal rule exits 2 naming the file and the field or
# extension, once; warnings reach the table and results.json; a job file's scene path is relative to the
# job file; `aalab scenes` lists scenes without loading their meshes.
. "$(dirname "$0")/lib.sh"

assets="$top_srcdir/tests/assets"
mkdir -p "$TMP/scenes"
cp "$assets"/*.gltf "$assets"/*.glb "$assets"/*.obj "$assets"/*.mtl "$assets"/*.ply "$assets"/*.png "$TMP/scenes/"

# scene FILE [OBJECT-KEYS]: a scene of one object drawing FILE, in $TMP/scenes
scene() {
	name=$(echo "$1" | tr . _)
	printf '{"objects": [{"mesh": {"type": "file", "path": "%s"}%s}], "camera": {"position": [0, 0, 5], "target": [0, 0, 0]}}\n' \
		"$1" "$2" >"$TMP/scenes/$name.json"
	echo "$TMP/scenes/$name.json"
}

run() { "$AALAB" run --local --scene "$1" --size 32x18 --reference-samples 2 --methods none --out "$TMP/o" --quiet; }

# refusal rules: file, what names the field or extension
while read -r file says; do
	s=$(scene "$file")
	expect_status 2 "$file is refused" -- run "$s"
	expect_stderr "mesh file '$file': .*$says" "$file: the message names the file and says '$says'"
	# the field's path once (the CLI used to print it before the message that names it too)
	n=$(grep -o "objects\[0\]\.mesh\.path" "$TMP/err" | wc -l)
	[ "$n" -eq 1 ] && pass "$file: the field is named once" || fail "$file: the field is named $n times: $(cat "$TMP/err")"
done <<'EOF'
broken-required-extension.gltf requires the extension EXT_unknown_foo \(extensionsRequired\[0\]\)
broken-index-range.gltf meshes\[0\]\.primitives\[0\]\.indices: index 60000
broken-nan-position.gltf not a finite number
broken-huge-position.gltf positions must be within 1e\+07
broken-nan-position.obj not a finite number
broken-huge-position.obj positions must be within 1e\+07
broken-huge-position.ply positions must be within 1e\+07
broken-index-range.obj a face names a vertex that does not exist
broken-truncated.glb truncated: its header says 1060 bytes
broken-not-json.gltf is not glTF
broken-gltf1.gltf is glTF 1.0 \(asset.version\)
broken-missing-texture.gltf texture 'missing-texture.png' not found
broken-missing-mtl.obj material library \(mtllib\) 'no-such-file.mtl' not found
broken-missing-map.obj texture 'no-such-image.png' not found
broken-morph-targets.gltf meshes\[0\]\.primitives\[0\] has morph targets
EOF

# asked for: a missing texture is a warning, and the warning reaches the table and results.json
s=$(scene broken-missing-texture.gltf '' )
sed -i 's/"path": "broken-missing-texture.gltf"/"path": "broken-missing-texture.gltf", "missing_files": "warn"/' "$s"
expect_status 0 "a missing texture as a warning" -- "$AALAB" run --local --scene "$s" --size 32x18 \
	--reference-samples 2 --methods none --out "$TMP/w" --quiet
grep -q "texture 'missing-texture.png' not found: drawn without it" "$TMP/out" && pass "the table shows the warning" ||
	fail "the table lacks the warning: $(cat "$TMP/out")"
s=$(scene warnings.gltf)
expect_status 0 "a file with approximations runs" -- "$AALAB" run --local --scene "$s" --size 32x18 \
	--reference-samples 2 --methods none --out "$TMP/w2" --quiet
/usr/bin/python3 - "$TMP/w2/results.json" <<'PY' && pass "results.json's warnings[] has them (code scene)" || fail "results.json warnings[]"
import json, sys
w = [x["message"] for x in json.load(open(sys.argv[1]))["warnings"] if x["code"] == "scene"]
assert len(w) == 4, w
assert any("KHR_materials_clearcoat" in x for x in w) and any("CUBICSPLINE" in x for x in w), w
PY
grep -q "KHR_materials_clearcoat" "$TMP/w2/report.html" && pass "the report shows the warnings" || fail "report lacks warnings"

# a job file's scene path is relative to the job file, wherever aalab runs
mkdir -p "$TMP/jobs/sub"
cp "$TMP/scenes/base-color.gltf" "$TMP/jobs/sub/"
printf '{"objects": [{"mesh": {"type": "file", "path": "base-color.gltf"}}], "camera": {"position": [0, 0, 5], "target": [0, 0, 0]}}\n' \
	>"$TMP/jobs/sub/colors.json"
printf '{"scene": "sub/colors.json", "size": "32x18", "reference": {"samples": 2}, "methods": ["none"]}\n' >"$TMP/jobs/job.json"
expect_status 0 "a job file's relative scene path" -- sh -c "cd / && '$AALAB' run --local '$TMP/jobs/job.json' --out '$TMP/j' --quiet"

# aalab scenes lists from the JSON alone: a scene whose mesh file is broken still lists, and fast
mkdir -p "$TMP/list"
cp "$assets/broken-truncated.glb" "$TMP/list/"
printf '{"name": "heavy", "description": "a mesh file never loaded by the listing", "objects": [{"mesh": {"type": "file", "path": "broken-truncated.glb"}}], "camera": {"position": [0, 0, 5], "target": [0, 0, 0]}}\n' \
	>"$TMP/list/heavy.json"
expect_status 0 "scenes" -- env AALAB_SCENE_DIR="$TMP/list" "$AALAB" scenes
grep -q "^heavy .*paths: default, static, main" "$TMP/out" && ! grep -q invalid "$TMP/out" &&
	pass "scenes lists without loading the mesh" || fail "scenes: $(cat "$TMP/out")"
expect_status 2 "scenes NAME loads it whole" -- env AALAB_SCENE_DIR="$TMP/list" "$AALAB" scenes heavy
expect_stderr "mesh file 'broken-truncated.glb': truncated" "scenes NAME names the broken file"
s=$(scene skin.gltf)
expect_status 0 "scenes FILE shows a file's animations" -- "$AALAB" scenes "$s"
grep -q "animation 'bend' of skin.gltf: 1.000 s" "$TMP/out" && pass "scenes FILE lists the clip" || fail "no clip: $(cat "$TMP/out")"
expect_status 0 "scenes NAME with an OBJ mesh" -- "$AALAB" scenes hard-edges
grep -Eq "^  reads /.*/assets/torus\.obj \([0-9]+ bytes\)$" "$TMP/out" && pass "shows the files it reads (what aalabd's cache watches)" ||
	fail "no files read: $(cat "$TMP/out")"
! grep -q '^ *$' "$TMP/out" && pass "a scene without a description gets no blank line" || fail "blank line: $(cat "$TMP/out")"
printf '{"objects": [{"mesh": "cube"}], "camera": {"position": [0, 0, 5], "target": [0, 0, 0]}}\n' >"$TMP/list/plain.json"
expect_status 0 "scenes lists one without a description" -- env AALAB_SCENE_DIR="$TMP/list" "$AALAB" scenes
! grep -q '^ *$' "$TMP/out" && pass "and prints no blank line for it" || fail "blank line: $(cat "$TMP/out")"
finish

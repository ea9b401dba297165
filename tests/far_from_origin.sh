#!/bin/sh
# Camera-relative rendering (docs/hard-cases.md, far-from-origin): a scene placed far from the world's
# origin renders as its copy at the origin does: identical references, taa within 77 dB at this size.
. "$(dirname "$0")/lib.sh"

here="$top_srcdir/tests/camrel"
run() { # run SCENE OUT: 3 frames of the orbit, the reference and three methods (taa: velocity; gbaa: edges)
	expect_status 0 "renders $(basename "$1" .json)" -- "$AALAB" run --local --quiet --scene "$1" --size 160x90 \
		--frames 3 --reference-samples 8 --methods none,taa,gbaa --out "$2"
}
compare() { # compare CONTROL FAR METHOD MIN_PSNR MAX_OFF WHAT
	/usr/bin/python3 "$here/compare_frames.py" "$1" "$2" "$3" 3 "$4" "$5" >"$TMP/cmp" 2>&1 &&
		pass "$6: $(cat "$TMP/cmp")" || fail "$6 (>= $4 dB, <= $5 pixels off): $(cat "$TMP/cmp")"
}

# the shipped pair: 600,000 units out along x and z, camera and orbit included
run far-from-origin-control "$TMP/control"
run far-from-origin "$TMP/far"
# gbaa too: its edge distances were computed from projected vertices, so the floor's triangles (reaching
# under the camera) got different wrong distances in the two copies (246 pixels apart by 0.01 or more)
for m in reference none taa gbaa; do
	compare "$TMP/control" "$TMP/far" $m 50 0 "far-from-origin's $m matches its control's"
done

# the same about 1,000,000 units out (off the 1/16-unit grid of floats there) with what else must follow
# the eye: a shadow-casting light (cascades), a point light, crates spinning about their own (far)
# positions. The shadow map's texel grid is fixed in the world, so its phase under the content differs
# between the copies: a few pixels of shadow edge may differ (measured: up to 1 in the reference, 7 in none).
/usr/bin/python3 "$here/shift_scene.py" "$AALAB_SCENE_DIR/far-from-origin-control.json" "$TMP/near.json" 0 0 0 \
	--shadow --point-light --spin || fail "shift_scene.py"
/usr/bin/python3 "$here/shift_scene.py" "$AALAB_SCENE_DIR/far-from-origin-control.json" "$TMP/away.json" \
	1000000.3 0 -999999.7 --shadow --point-light --spin || fail "shift_scene.py"
run "$TMP/near.json" "$TMP/near"
run "$TMP/away.json" "$TMP/away"
compare "$TMP/near" "$TMP/away" reference 50 5 "1e6 units out with shadows, a point light and spin: the reference"
compare "$TMP/near" "$TMP/away" none 40 20 "and none (shadow edges may differ by a texel)"
compare "$TMP/near" "$TMP/away" taa 40 20 "and taa (velocity and reprojection far out)"
finish

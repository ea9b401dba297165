#!/bin/sh
# GBAA blends at triangle edges and only there (docs/methods.md, gbaa). Its edge lines are evaluated per
# pixel from homogeneous coordinates. The seed's form, distances computed at the projected vertices and
# interpolated, cannot serve a triangle that reaches behind the eye (such triangles got no edges), and
# went wrong for big triangles far off screen:
# - a plane from under the camera to a far edge against the sky (tests/gbaa/eye-plane.json): the edge was
#   never blended (gbaa 29.47 dB, exactly none's); now 49.06 dB;
# - moire's floor (two triangles from under the camera to the horizon): 18.4% of the pixels blended, none
#   of them at an edge, a blur that scored +1.6 dB over none on a pattern GBAA cannot see; now 1.9%.
. "$(dirname "$0")/lib.sh"

changed() { # changed DIR SCENE MAX_PCT: percent of pixels where gbaa differs from none by 2/255 or more
	/usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import glob, sys
import numpy as np
from skimage import io
d, scene, limit = sys.argv[1], sys.argv[2], float(sys.argv[3])
worst = 0.0
for f in sorted(glob.glob(d + "/frames/none/*.png")):
    a = io.imread(f)[..., :3].astype(int)
    b = io.imread(f.replace("/none/", "/gbaa/"))[..., :3].astype(int)
    worst = max(worst, 100.0 * (np.abs(a - b).max(axis=2) >= 2).mean())
print("%s: gbaa changes at most %.2f%% of a frame's pixels (limit %g%%)" % (scene, worst, limit))
sys.exit(0 if worst <= limit else 1)
PY
}
expect_status 0 "the eye-plane scene renders" -- "$AALAB" run --local --quiet --scene "$top_srcdir/tests/gbaa/eye-plane.json" \
	--size 160x90 --frames 1 --reference-samples 16 --methods none,gbaa --no-images --out "$TMP/eye-plane"
/usr/bin/python3 -c '
import json, sys
m = {x["label"]: x["metrics"]["psnr"]["mean"] for x in json.load(open(sys.argv[1]))["methods"]}
print("gbaa %.2f dB, none %.2f dB" % (m["gbaa"], m["none"]))
sys.exit(0 if m["gbaa"] >= m["none"] + 10 else 1)
' "$TMP/eye-plane/results.json" >"$TMP/cmp" 2>&1 && pass "the far edge of a plane reaching behind the eye is blended: $(cat "$TMP/cmp")" \
	|| fail "the far edge of a plane reaching behind the eye (gbaa >= none + 10 dB): $(cat "$TMP/cmp")"

expect_status 0 "moire renders" -- "$AALAB" run --local --quiet --scene moire --size 160x90 --frames 2 \
	--reference-samples 4 --methods none,gbaa --no-viewer --out "$TMP/moire"
changed "$TMP/moire" moire 5 >"$TMP/cmp" 2>&1 && pass "$(cat "$TMP/cmp")" || fail "$(cat "$TMP/cmp")"
finish

#!/bin/sh
# The pictures of docs/hard-cases.md: frame 0 of each hard case at 320x180, its reference ("auto", cap 256)
# on the left and the case's worst method in the suite's run on the right (far-from-origin: the control's
# reference and the far scene's). Run from the build directory:  sh scripts/make_hard_case_pictures.sh
set -e
src=$(cd "$(dirname "$0")/.." && pwd)
out="$src/docs/img/hard-cases"
aalab=${AALAB:-./aalab}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/aalab-pictures.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
render() { # scene method
	"$aalab" run --local --quiet --scene "$1" --size 320x180 --frames 1 --methods "$2" \
		--reference-samples auto --out "$tmp/$1" >/dev/null
}
side_by_side() { # left right out
	/usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import sys
import numpy as np
from skimage import io
a, b = (io.imread(p)[..., :3] for p in sys.argv[1:3])
gap = np.full((a.shape[0], 4, 3), 255, dtype=np.uint8)
io.imsave(sys.argv[3], np.concatenate([a, gap, b], axis=1), check_contrast=False)
PY
}
for pair in specular-aliasing:smaa subpixel-specks:none moire:none depth-extremes:none hdr-fireflies:asaa; do
	scene=${pair%%:*}
	method=${pair#*:}
	render "$scene" "$method"
	side_by_side "$tmp/$scene/frames/reference/0000.png" "$tmp/$scene/frames/$method/0000.png" "$out/$scene.png"
done
render far-from-origin-control none
render far-from-origin none
side_by_side "$tmp/far-from-origin-control/frames/reference/0000.png" \
	"$tmp/far-from-origin/frames/reference/0000.png" "$out/far-from-origin.png"
ls -l "$out"

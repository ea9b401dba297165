#!/bin/sh
# Checks metrics_tool's MSE, PSNR and SSIM against numpy and scikit-image on generated image pairs.
# Exit status: 0 pass, 1 fail, 77 skip (/usr/bin/python3 lacks scikit-image).
set -u

srcdir=${top_srcdir:-$(cd "$(dirname "$0")/.." && pwd)}
builddir=${top_builddir:-$srcdir}
# Debian's python3-skimage is installed for the system interpreter; another python3 may come first in PATH.
python=/usr/bin/python3
tool=$builddir/tests/tools/metrics_tool

if [ ! -x "$python" ] || ! "$python" -c 'import numpy, scipy.ndimage, skimage.io, skimage.metrics' 2>/dev/null; then
	echo "SKIP: $python with scikit-image, scipy and numpy is not available"
	exit 77
fi
if [ ! -x "$tool" ]; then
	echo "FAIL: $tool is not built (make check builds it)"
	exit 1
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/aalab-ssim-oracle.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT
trap 'exit 1' INT TERM HUP

"$python" "$srcdir/tests/oracle/ssim_oracle.py" "$tool" "$work"
status=$?
case $status in
0 | 77) exit $status ;;
*) exit 1 ;;
esac

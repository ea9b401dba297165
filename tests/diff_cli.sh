#!/bin/sh
# `aalab diff` as a user meets it: text and JSON output, thresholds and exit statuses 0/1/2, the error map,
# HDR input, and clear errors for missing, unreadable, mismatched and unsupported files. Test images are
# made with oiiotool (openimageio-tools, a dependency); the test is skipped (77) without it.
. "$(dirname "$0")/lib.sh"

if ! command -v oiiotool >/dev/null 2>&1; then
	echo "SKIP: oiiotool (openimageio-tools) is not installed"
	exit 77
fi
python=/usr/bin/python3
img() { oiiotool "$@" >/dev/null 2>&1 || fail "oiiotool $*"; }

# a checkerboard render and a blurred copy of it: a difference on every edge
img --pattern checker:width=8:height=8:color1=0.9,0.8,0.1:color2=0.1,0.2,0.6 96x64 3 -d uint8 -o "$TMP/ref.png"
img "$TMP/ref.png" --blur 3x3 -d uint8 -o "$TMP/blur.png"
img --pattern checker:width=8:height=8 64x64 3 -d uint8 -o "$TMP/small.png"
img --pattern constant:color=0.5,0.5,0.5,1,1 96x64 5 -d uint8 -o "$TMP/five.tif"
img "$TMP/ref.png" -d uint16 -o "$TMP/ref16.png"
img --pattern checker:width=8:height=8:color1=4,2,1:color2=0.05,0.1,0.2 96x64 3 -d half -o "$TMP/ref.exr"
img "$TMP/ref.exr" --blur 3x3 -d half -o "$TMP/blur.exr"
echo "not an image" >"$TMP/text.png"

expect_status 0 "identical images" -- "$AALAB" diff "$TMP/ref.png" "$TMP/ref.png"
grep -q "^PSNR *inf (identical)" "$TMP/out" && pass "identical PSNR is inf" || fail "identical PSNR: $(cat "$TMP/out")"
grep -q "^FLIP *0.000000" "$TMP/out" && pass "identical FLIP is 0" || fail "identical FLIP is not 0"

expect_status 0 "blurred image" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png"
for what in PSNR SSIM FLIP; do
	grep -q "^$what " "$TMP/out" && pass "prints $what" || fail "no $what line in: $(cat "$TMP/out")"
done
grep -q "weighted median" "$TMP/out" && pass "prints the pooled FLIP statistics" || fail "no weighted median"

expect_status 0 "--json" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --json --metrics all
if "$python" - "$TMP/out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["mode"] == "ldr" and d["width"] == 96 and d["height"] == 64, d
assert 0 < d["flip"]["mean"] < 1 and d["flip"]["min"] <= d["flip"]["weighted_median"] <= d["flip"]["max"], d["flip"]
assert 0 < d["ssim"] < 1 and d["psnr"] > 0 and d["identical"] is False, d
bands = d["fourier"]
assert abs(bands["low"] + bands["mid"] + bands["high"] - d["mse"]) <= 1e-6 * d["mse"], (bands, d["mse"])
assert d["failed"] is False and d["thresholds"] == []
PY
then pass "JSON has psnr, ssim, flip stats and Fourier bands summing to the MSE"; else fail "JSON content"; fi

expect_status 1 "--fail-above flip trips" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --fail-above flip=0.001
expect_stderr "flip = .* is above 0.001" "the tripped threshold is named"
expect_status 0 "--fail-above flip holds" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --fail-above flip=0.99
expect_status 1 "--fail-below psnr trips" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --metrics psnr \
	--fail-below psnr=99
expect_status 0 "identical images pass any psnr floor" -- "$AALAB" diff "$TMP/ref.png" "$TMP/ref.png" \
	--metrics psnr --fail-below psnr=99
expect_status 1 "a threshold computes its metric" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --metrics psnr \
	--fail-above fourier.high=0 --json
grep -q '"fourier"' "$TMP/out" && pass "fourier computed for its threshold" || fail "fourier missing"
expect_status 1 "a threshold before --metrics still counts" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" \
	--fail-below ssim=0.9999 --metrics flip
expect_stderr "ssim = .* is below 0.9999" "the SSIM threshold is evaluated"

expect_status 0 "--error-map" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --metrics psnr --error-map "$TMP/map.png"
oiiotool --info "$TMP/map.png" 2>/dev/null | grep -q "96 x  *64" && pass "error map has the image size" ||
	fail "error map: $(oiiotool --info "$TMP/map.png" 2>&1)"
expect_status 2 "unwritable error map" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --error-map "$TMP/no/dir/map.png"

expect_status 0 "16-bit PNG against 8-bit" -- "$AALAB" diff "$TMP/ref16.png" "$TMP/ref.png" --metrics psnr
grep -q "identical" "$TMP/out" && pass "16-bit reads as the same 8-bit values" || fail "16-bit: $(cat "$TMP/out")"

expect_status 0 "EXR pair (HDR-FLIP)" -- "$AALAB" diff "$TMP/ref.exr" "$TMP/blur.exr" --json
if "$python" - "$TMP/out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
f = d["flip"]
assert d["mode"] == "hdr" and f["tone_mapper"] == "aces" and f["exposures"] >= 2, d
assert f["start_exposure"] <= f["stop_exposure"] and 0 < f["mean"] < 1, f
PY
then pass "EXR uses HDR-FLIP with an exposure range"; else fail "HDR JSON: $(cat "$TMP/out")"; fi
expect_status 0 "--ldr on EXR" -- "$AALAB" diff "$TMP/ref.exr" "$TMP/blur.exr" --ldr --metrics flip --json
grep -q '"mode": "ldr"' "$TMP/out" && pass "--ldr forces LDR" || fail "--ldr ignored"

expect_status 2 "size mismatch" -- "$AALAB" diff "$TMP/ref.png" "$TMP/small.png"
expect_stderr "differ in size.*96x64.*64x64" "size mismatch names both sizes"
expect_status 2 "missing file" -- "$AALAB" diff "$TMP/ref.png" "$TMP/nosuch.png"
expect_stderr "nosuch.png.*does not exist" "missing file is named"
expect_status 2 "not an image" -- "$AALAB" diff "$TMP/text.png" "$TMP/ref.png"
expect_stderr "text.png" "unreadable file is named"
expect_status 2 "five channels" -- "$AALAB" diff "$TMP/five.tif" "$TMP/five.tif"
expect_stderr "5 channels" "unsupported channel layout is explained"
expect_status 2 "one image" -- "$AALAB" diff "$TMP/ref.png"
expect_status 2 "unknown metric" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --metrics psnr,vmaf
expect_stderr "vmaf" "unknown metric is named"
expect_status 2 "bad threshold" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --fail-above flip
expect_status 2 "unknown threshold metric" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --fail-above lpips=1
expect_status 2 "bad ppd" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --ppd -1
expect_status 2 "unknown option" -- "$AALAB" diff "$TMP/ref.png" "$TMP/blur.png" --frobnicate
expect_status 0 "--help" -- "$AALAB" diff --help
grep -q -- "--fail-above" "$TMP/out" && pass "help documents --fail-above" || fail "help lacks --fail-above"
finish

#!/usr/bin/python3
"""Checks aalab's MSE, PSNR and SSIM against numpy and scikit-image on generated PNG pairs.

Usage: ssim_oracle.py METRICS_TOOL WORKDIR
Exit status: 0 all pairs agree, 1 a pair disagrees or the tool fails, 77 scikit-image is missing.
SSIM must agree within 1e-4 (absolute), MSE and PSNR within 1e-9 (relative).
"""
import json
import math
import os
import subprocess
import sys

try:
    import numpy as np
    from scipy import ndimage
    from skimage import io as skio
    from skimage.metrics import structural_similarity
except ImportError as exc:  # the oracle is optional: skip, do not fail
    print(f"SKIP: scikit-image is not available ({exc})")
    sys.exit(77)

SSIM_TOLERANCE = 1e-4
RELATIVE_TOLERANCE = 1e-9


def shapes_image(width, height):
    """A flat-shaded 'render': background, a tilted bar, a disc and a triangle, with hard edges."""
    yy, xx = np.mgrid[0:height, 0:width].astype(np.float64) + 0.5
    img = np.empty((height, width, 3), np.float64)
    img[:] = (40, 60, 90)
    angle = math.radians(23)
    across = (xx - width / 2) * -math.sin(angle) + (yy - height / 2) * math.cos(angle)
    img[np.abs(across) < 4] = (230, 220, 200)
    img[(xx - width * 0.3) ** 2 + (yy - height * 0.35) ** 2 < (height * 0.2) ** 2] = (200, 40, 30)
    tri = (yy > height * 0.55) & (xx - width * 0.6 > -(yy - height * 0.55)) & (xx < width * 0.85)
    img[tri] = (30, 180, 60)
    return img


def make_pairs(rng):
    """(name, reference, test) uint8 RGB arrays covering flat, noisy, smooth and rendered content."""
    def u8(a):
        return np.clip(np.rint(a), 0, 255).astype(np.uint8)

    pairs = []
    pairs.append(("constant", np.full((32, 48, 3), 128, np.uint8), np.full((32, 48, 3), 131, np.uint8)))
    pairs.append(("identical", np.full((20, 20, 3), 77, np.uint8), np.full((20, 20, 3), 77, np.uint8)))
    pairs.append(("noise", rng.integers(0, 256, (64, 80, 3), dtype=np.uint8),
                  rng.integers(0, 256, (64, 80, 3), dtype=np.uint8)))
    noisy = rng.integers(0, 256, (50, 70, 3)).astype(np.float64)
    pairs.append(("noise_plus_noise", u8(noisy), u8(noisy + rng.normal(0, 12, noisy.shape))))
    yy, xx = np.mgrid[0:90, 0:120]
    grad = np.stack([xx * 255 / 119, yy * 255 / 89, (xx + yy) * 255 / 208], axis=2)
    blurred = ndimage.gaussian_filter(grad, sigma=(2.0, 2.0, 0), mode="nearest")
    pairs.append(("gradient_blurred", u8(grad), u8(blurred + 3 * np.sin(xx / 5.0)[..., None])))
    shapes = shapes_image(160, 120)
    shifted = np.roll(shapes, (1, 2), axis=(0, 1)) + rng.normal(0, 4, shapes.shape)
    pairs.append(("shapes_shifted_noisy", u8(shapes), u8(shifted)))
    # Large enough that the tool splits SSIM over threads; the test is a smoothed ("anti-aliased") copy.
    wide = shapes_image(640, 360)
    pairs.append(("shapes_640x360_smoothed", u8(wide),
                  u8(ndimage.gaussian_filter(wide, sigma=(0.7, 0.7, 0)))))
    odd = shapes_image(37, 23)
    pairs.append(("odd_37x23", u8(odd), u8(ndimage.uniform_filter(odd, size=(3, 3, 1)))))
    pairs.append(("window_11x11", u8(rng.integers(0, 256, (11, 11, 3))),
                  u8(rng.integers(0, 256, (11, 11, 3)))))
    return pairs


def relative_error(ours, expected):
    if expected == 0:
        return abs(ours)
    return abs(ours - expected) / abs(expected)


def check_pair(tool, workdir, name, ref, test):
    ref_path = os.path.join(workdir, f"{name}_ref.png")
    test_path = os.path.join(workdir, f"{name}_test.png")
    skio.imsave(ref_path, ref, check_contrast=False)
    skio.imsave(test_path, test, check_contrast=False)
    # Compare on what the files hold, so the oracle and the tool see the same pixels.
    ref = skio.imread(ref_path)[..., :3]
    test = skio.imread(test_path)[..., :3]

    run = subprocess.run([tool, ref_path, test_path], capture_output=True, text=True)
    if run.returncode != 0:
        print(f"FAIL {name}: metrics_tool exited {run.returncode}: {run.stderr.strip()}")
        return False
    ours = json.loads(run.stdout)

    diff = ref.astype(np.float64) - test.astype(np.float64)
    mse = float(np.mean(diff * diff))
    psnr = None if mse == 0 else 10 * math.log10(255.0 ** 2 / mse)
    ssim = float(structural_similarity(ref, test, channel_axis=2, gaussian_weights=True, sigma=1.5,
                                       use_sample_covariance=False, data_range=255))

    ok = True
    ssim_dev = abs(ours["ssim"] - ssim)
    if not ssim_dev <= SSIM_TOLERANCE:
        print(f"FAIL {name}: ssim {ours['ssim']!r} vs skimage {ssim!r}")
        ok = False
    if not relative_error(ours["mse"], mse) <= RELATIVE_TOLERANCE:
        print(f"FAIL {name}: mse {ours['mse']!r} vs numpy {mse!r}")
        ok = False
    if psnr is None:
        if ours["psnr"] is not None or ours["identical"] is not True:
            print(f"FAIL {name}: identical images must give psnr null, identical true; got {ours}")
            ok = False
    elif ours["psnr"] is None or not relative_error(ours["psnr"], psnr) <= RELATIVE_TOLERANCE:
        print(f"FAIL {name}: psnr {ours['psnr']!r} vs numpy {psnr!r}")
        ok = False
    if ok:
        print(f"ok   {name} {ref.shape[1]}x{ref.shape[0]}: ssim {ssim:.10f} (deviation {ssim_dev:.2e}), "
              f"mse {mse:.6g}, psnr {psnr if psnr is None else round(psnr, 6)}")
    return ok


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 1
    tool, workdir = sys.argv[1], sys.argv[2]
    rng = np.random.default_rng(20240601)
    results = [check_pair(tool, workdir, *pair) for pair in make_pairs(rng)]
    failed = results.count(False)
    print(f"{len(results) - failed}/{len(results)} pairs agree with scikit-image")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

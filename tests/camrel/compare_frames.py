"""Compares two runs' frames of one method, frame by frame: PSNR (8-bit sRGB) and the pixels where some
channel differs by 32/255 or more. Fails (exit 1) when a frame's PSNR is under MIN_PSNR or more than
MAX_OFF pixels are off. Usage: compare_frames.py DIR_A DIR_B METHOD FRAMES MIN_PSNR MAX_OFF"""
import sys

import numpy as np
from skimage import io

a_dir, b_dir, method = sys.argv[1], sys.argv[2], sys.argv[3]
frames, min_psnr, max_off = int(sys.argv[4]), float(sys.argv[5]), int(sys.argv[6])
ok = True
report = []
for f in range(frames):
    a = io.imread("%s/frames/%s/%04d.png" % (a_dir, method, f))[..., :3].astype(np.float64)
    b = io.imread("%s/frames/%s/%04d.png" % (b_dir, method, f))[..., :3].astype(np.float64)
    mse = ((a - b) ** 2).mean()
    psnr = 10 * np.log10(255.0 ** 2 / mse) if mse > 0 else float("inf")
    off = int((np.abs(a - b).max(axis=2) >= 32).sum())
    report.append("%d: %.1f dB, %d off" % (f, psnr, off))
    ok = ok and psnr >= min_psnr and off <= max_off
print("%s frames %s" % (method, "; ".join(report)))
sys.exit(0 if ok else 1)

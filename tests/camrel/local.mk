# Camera-relative rendering (issue 17, far-from-origin): a scene far from the origin renders as its control.
TESTS += tests/far_from_origin.sh
EXTRA_DIST += tests/far_from_origin.sh tests/camrel/local.mk tests/camrel/shift_scene.py tests/camrel/compare_frames.py

# GBAA's edges: blended where a triangle's edge is, including triangles that reach behind the eye, and
# nowhere else (tests/gbaa_edges.sh).
TESTS += tests/gbaa_edges.sh
EXTRA_DIST += tests/gbaa_edges.sh tests/gbaa/local.mk tests/gbaa/eye-plane.json

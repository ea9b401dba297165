# tests: Makefile fragment, included from Makefile.am. Mesh files as their authors made them (issue 12):
# materials, skins and animation, the refusal rules and warnings of the loader, the shadow fit, and the
# images each material feature draws. The files in tests/assets/ are written by
# scripts/make_scene_assets.py.
EXTRA_DIST += tests/assets

# loading without a GPU: every test asset, every broken file
check_PROGRAMS += tests/unit/test_mesh_files
tests_unit_test_mesh_files_SOURCES = tests/unit/test_mesh_files.c
tests_unit_test_mesh_files_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_mesh_files_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_mesh_files

# the shadow map's fit to the view and the frame plan's reasons, without a GPU
check_PROGRAMS += tests/unit/test_shadow_plan
tests_unit_test_shadow_plan_SOURCES = tests/unit/test_shadow_plan.c
tests_unit_test_shadow_plan_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_shadow_plan_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_shadow_plan

# on the GPU: each material feature's reference against known values and a golden image
# (tests/assets/golden/, rewritten with AALAB_UPDATE_GOLDEN=1), skinned velocity, every method on every
# feature, and horizon's fence shadows
check_PROGRAMS += tests/integration/test_assets
tests_integration_test_assets_SOURCES = tests/integration/test_assets.c $(GPU_TEST_FIXTURE)
tests_integration_test_assets_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_assets_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_assets

# the command line: refusals exit 2 naming the file and the field once, warnings in the table and
# results.json, job files' relative scene paths, aalab scenes without loading meshes
TESTS += tests/cli_assets.sh
EXTRA_DIST += tests/cli_assets.sh
EXTRA_DIST += bench/materials

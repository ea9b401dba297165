# tests: Makefile fragment, included from Makefile.am. Tests that pin behaviour (issue 20): exact values
# where an answer is known, golden values where none is, long temporal runs, parameter ranges from the
# method tables, durability of atomic writes under injected faults.

# exact values without a GPU: Halton points, jitter sequences, standard sample positions, FXAA/SMAA presets
check_PROGRAMS += tests/unit/test_known_values
tests_unit_test_known_values_SOURCES = tests/unit/test_known_values.c
tests_unit_test_known_values_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_known_values_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_known_values

# the frame plan for every shipped scene and method, without a GPU
check_PROGRAMS += tests/unit/test_frame_plan
tests_unit_test_frame_plan_SOURCES = tests/unit/test_frame_plan.c
tests_unit_test_frame_plan_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_frame_plan_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_frame_plan

# every parameter of every method, generated from the method tables: bounds in, one past out, field named
check_PROGRAMS += tests/unit/test_param_ranges
tests_unit_test_param_ranges_SOURCES = tests/unit/test_param_ranges.c
tests_unit_test_param_ranges_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_param_ranges_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_param_ranges

# golden values: every method on every scene at a small size, pinned in tests/golden/quality.tsv
GOLDEN_FIXTURE = tests/integration/golden.h tests/integration/golden.c
check_PROGRAMS += tests/integration/test_golden
tests_integration_test_golden_SOURCES = tests/integration/test_golden.c $(GPU_TEST_FIXTURE) $(GOLDEN_FIXTURE)
tests_integration_test_golden_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_golden_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_golden
EXTRA_DIST += tests/golden/quality.tsv tests/golden/update.sh tests/golden/README.md

# the temporal methods over 128 still frames, a steady pan and a camera cut (tests/golden/temporal.tsv)
check_PROGRAMS += tests/integration/test_temporal_long
tests_integration_test_temporal_long_SOURCES = tests/integration/test_temporal_long.c $(GPU_TEST_FIXTURE) \
	$(GOLDEN_FIXTURE)
tests_integration_test_temporal_long_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_temporal_long_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_temporal_long
EXTRA_DIST += tests/golden/temporal.tsv

# scene loading with exact answers: a mesh file's node transform and uvs, the documented material defaults
check_PROGRAMS += tests/unit/test_scene_known
tests_unit_test_scene_known_SOURCES = tests/unit/test_scene_known.c
tests_unit_test_scene_known_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_scene_known_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_scene_known

# aalabd's limits at their exact bounds: configuration keys, job budget, queued jobs, list
TESTS += tests/integration/daemon_bounds.py
EXTRA_DIST += tests/integration/daemon_bounds.py

# render-nice: aalabd renders below its protocol loop's priority (threads, worker process, bad values)
TESTS += tests/integration/daemon_priority.py
EXTRA_DIST += tests/integration/daemon_priority.py

# `make update-golden`: computes every golden file anew, shows the diff against the committed one and asks
# before replacing it (ACCEPT=yes replaces without asking; ACCEPT=no only shows). tests/golden/README.md.
GOLDEN_TEST_BINARIES = tests/integration/test_golden tests/integration/test_temporal_long
update-golden: $(GOLDEN_TEST_BINARIES)
	@$(AM_TESTS_ENVIRONMENT) ACCEPT='$(ACCEPT)'; export ACCEPT; \
	$(SHELL) $(srcdir)/tests/golden/update.sh $(GOLDEN_TEST_BINARIES)
.PHONY: update-golden

# durability: aalabd and aalab, unchanged, under an LD_PRELOAD shim that records the order of their file
# calls and fails one on demand (tests/durability/fault_shim.c). Built without sanitizers; in sanitizer
# builds the tests preload the ASan runtime ahead of it.
check_PROGRAMS += tests/durability/fault_shim.so
tests_durability_fault_shim_so_SOURCES = tests/durability/fault_shim.c
tests_durability_fault_shim_so_CPPFLAGS =
tests_durability_fault_shim_so_CFLAGS = -std=c11 -Wall -Wextra -fPIC
tests_durability_fault_shim_so_LDFLAGS = -shared
tests_durability_fault_shim_so_LDADD = -ldl
DURABILITY_TESTS = tests/durability/results_atomic.py tests/durability/daemon_atomic.py
TESTS += $(DURABILITY_TESTS)
EXTRA_DIST += $(DURABILITY_TESTS) tests/durability/durability_lib.py

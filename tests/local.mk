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

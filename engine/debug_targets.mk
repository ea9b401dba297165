# Job option debug_targets (issue 17): the registry of every method's intermediate images, read back
# after each frame, and its test. Included from Makefile.am.

libaaengine_a_SOURCES += engine/debug_targets.h engine/debug_targets.c

# a method whose output filters NaN (taa) is caught holding one in an intermediate only with the option on
check_PROGRAMS += tests/integration/test_debug_targets
tests_integration_test_debug_targets_SOURCES = tests/integration/test_debug_targets.c $(GPU_TEST_FIXTURE)
tests_integration_test_debug_targets_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_debug_targets_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_debug_targets

# the count itself, on hand-made half, float and depth texels
check_PROGRAMS += tests/unit/test_debug_targets_count
tests_unit_test_debug_targets_count_SOURCES = tests/unit/test_debug_targets_count.c
tests_unit_test_debug_targets_count_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_debug_targets_count_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_debug_targets_count

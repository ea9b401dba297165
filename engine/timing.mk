# Timings as distributions (rotating method order, timing.repeat) and their tests: Makefile fragment,
# included from Makefile.am.
check_PROGRAMS += tests/integration/test_timing
tests_integration_test_timing_SOURCES = tests/integration/test_timing.c $(GPU_TEST_FIXTURE)
tests_integration_test_timing_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_timing_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_timing

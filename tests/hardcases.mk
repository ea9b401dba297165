# issue 17 (hard cases): the self-measuring reference, the hard-case scenes' suite and its verdicts.
libaaengine_a_SOURCES += engine/metrics/change.c engine/results/verdicts.h engine/results/verdicts.c \
	engine/results/verdicts_expected.h
TESTS += tests/reference_auto.sh tests/hard_cases.sh tests/hard_cases_long.sh
EXTRA_DIST += tests/reference_auto.sh tests/hard_cases.sh tests/hardcases.mk tests/hardcases/small-suite.json \
	tests/hard_cases_long.sh tests/hardcases/long-static.json tests/hardcases/long_run_check.py bench/hard-cases-long
dist_suites_DATA += suites/hard-cases.json
aalab_SOURCES += client/verdict_table.c
check_PROGRAMS += tests/unit/test_verdicts
tests_unit_test_verdicts_SOURCES = tests/unit/test_verdicts.c
tests_unit_test_verdicts_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_verdicts_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_verdicts

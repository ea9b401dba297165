# Build farms (issue 15): suites, labels, job hashes, `aalab compare` with gates, JUnit and markdown,
# and their tests. Makefile fragment, included from Makefile.am.
libaaengine_a_SOURCES += \
	engine/farm.h engine/job_parse.h engine/job_suite.c engine/suite_run.c \
	engine/sha256.h engine/sha256.c engine/results/suite_results.c
libaaengine_a_SOURCES += \
	engine/results/compare.h engine/results/gate.c engine/results/compare.c engine/results/compare_cost.h \
	engine/results/compare_cost.c engine/results/compare_output.c
libaaengine_a_SOURCES += engine/suite_files.c
AM_CPPFLAGS += -DAA_SOURCE_SUITE_DIR='"$(abs_top_srcdir)/suites"' -DAA_INSTALLED_SUITE_DIR='"$(pkgdatadir)/suites"'
aalab_SOURCES += client/suite_table.c client/cmd_compare.c client/cmd_suites.c
aalabd_SOURCES += daemon/farm_routes.h daemon/farm_routes.c
# the suites `aalab run NAME` finds, installed beside the scenes
suitesdir = $(pkgdatadir)/suites
dist_suites_DATA = suites/smoke.json suites/full.json suites/hard.json

check_PROGRAMS += tests/unit/test_farm
tests_unit_test_farm_SOURCES = tests/unit/test_farm.c
tests_unit_test_farm_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_farm_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_farm

FARM_SCRIPT_TESTS = tests/farm_cli.sh tests/farm_cost.sh
TESTS += $(FARM_SCRIPT_TESTS)
EXTRA_DIST += $(FARM_SCRIPT_TESTS) tests/junit.xsd
FARM_DAEMON_TESTS = tests/integration/daemon_farm.py tests/integration/dashboard_trends.sh
TESTS += $(FARM_DAEMON_TESTS)
EXTRA_DIST += $(FARM_DAEMON_TESTS)

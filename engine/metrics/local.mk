# engine/metrics: Makefile fragment, included from Makefile.am (keeps parallel work in separate files).
# FLIP, the Fourier-band error, `aalab diff`, their tests and bench/metrics.

libaaengine_a_SOURCES += \
	engine/metrics/flip.h engine/metrics/flip.c engine/metrics/flip_internal.h engine/metrics/flip_color.c \
	engine/metrics/flip_simd.c engine/metrics/flip_pool.c engine/metrics/fourier.h engine/metrics/fourier.c

aalab_SOURCES += client/cmd_diff.c

check_PROGRAMS += tests/unit/test_flip tests/unit/test_fourier
tests_unit_test_flip_SOURCES = tests/unit/test_flip.c
tests_unit_test_flip_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_flip_LDADD = $(TEST_LIBS)
tests_unit_test_fourier_SOURCES = tests/unit/test_fourier.c
tests_unit_test_fourier_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_fourier_LDADD = $(TEST_LIBS)

TESTS += tests/unit/test_flip tests/unit/test_fourier tests/diff_cli.sh
EXTRA_DIST += tests/diff_cli.sh

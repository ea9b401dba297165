# rsaa: resampling AA from geometric subsamples with a trained offset table (seed 002).
libaaengine_a_SOURCES += engine/methods/rsaa.c engine/methods/rsaa_table.h engine/methods/rsaa_table.c

rsaa_glsl = shaders/rsaa_prepass.comp shaders/rsaa_resolve.comp
glsl_files += $(rsaa_glsl)
EXTRA_DIST += shaders/rsaa_common.glsl
$(patsubst shaders/%,shaders/%.h,$(rsaa_glsl)): $(srcdir)/shaders/rsaa_common.glsl

# the offset table: classes, the paper's readable entries, reproducibility; SADP's properties
check_PROGRAMS += tests/unit/test_rsaa_table
tests_unit_test_rsaa_table_SOURCES = tests/unit/test_rsaa_table.c
tests_unit_test_rsaa_table_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_rsaa_table_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_rsaa_table

# rsaa on the GPU: 8 beats 4 beats none on analytic edges, every parameter mix runs, dense detail stays finite
check_PROGRAMS += tests/integration/test_rsaa
tests_integration_test_rsaa_SOURCES = tests/integration/test_rsaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_rsaa_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_rsaa_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_rsaa

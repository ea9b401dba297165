# MSAA's shading point (one rule for hardware and virtual samples), the alpha rule of every method family
# and their tests: Makefile fragment, included from Makefile.am.
libaaengine_a_SOURCES += engine/methods/alpha_rule.c
glsl_files += shaders/virtual_sample.geom shaders/virtual_sample_gbuffer.geom
EXTRA_DIST += shaders/shading_point.glsl
$(glsl_headers): $(srcdir)/shaders/shading_point.glsl

check_PROGRAMS += tests/integration/test_msaa
tests_integration_test_msaa_SOURCES = tests/integration/test_msaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_msaa_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_msaa_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_msaa

check_PROGRAMS += tests/integration/test_alpha_rule
tests_integration_test_alpha_rule_SOURCES = tests/integration/test_alpha_rule.c $(GPU_TEST_FIXTURE)
tests_integration_test_alpha_rule_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_alpha_rule_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_alpha_rule

# asaa and t2msaa (seed 000's temporal methods) and their stability tests.
libaaengine_a_SOURCES += engine/methods/asaa.c engine/methods/t2msaa.c

temporal2_glsl = shaders/asaa.comp shaders/t2msaa.comp
glsl_files += $(temporal2_glsl)
EXTRA_DIST += shaders/asaa_t2msaa.glsl
$(patsubst shaders/%,shaders/%.h,$(temporal2_glsl)): $(srcdir)/shaders/asaa_t2msaa.glsl

# NaN/Inf never reaches history or output; 2,000 still frames stay within 0.5 dB; a cut resets history;
# off-screen velocities are rejected
check_PROGRAMS += tests/integration/test_temporal_stability_asaa_t2msaa
tests_integration_test_temporal_stability_asaa_t2msaa_SOURCES = \
	tests/integration/test_temporal_stability_asaa_t2msaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_temporal_stability_asaa_t2msaa_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_temporal_stability_asaa_t2msaa_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_temporal_stability_asaa_t2msaa

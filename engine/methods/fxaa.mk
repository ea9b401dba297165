# fxaa and fxaa-cs (FXAA 3.11, pixel shader and compute variants) and the reusable compute pass helper.
libaaengine_a_SOURCES += engine/methods/fxaa.h engine/methods/fxaa.c engine/methods/fxaa_cs.c \
	engine/passes/compute_pass.h engine/passes/compute_pass.c

fxaa_glsl = shaders/fxaa_luma.frag shaders/fxaa_edges.frag shaders/fxaa.frag \
	shaders/fxaa_cs_luma.comp shaders/fxaa_cs_classify.comp shaders/fxaa_cs_edges.comp
glsl_files += $(fxaa_glsl)
EXTRA_DIST += shaders/fxaa_common.glsl shaders/fxaa_cs_queue.glsl
$(patsubst shaders/%,shaders/%.h,$(fxaa_glsl)): $(srcdir)/shaders/fxaa_common.glsl \
	$(srcdir)/shaders/fxaa_cs_queue.glsl

# fxaa and fxaa-cs agree within 1/255; fxaa beats none; bad parameters are refused
check_PROGRAMS += tests/integration/test_fxaa
tests_integration_test_fxaa_SOURCES = tests/integration/test_fxaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_fxaa_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_fxaa_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_fxaa

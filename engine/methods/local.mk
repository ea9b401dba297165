# engine/methods: Makefile fragment, included from Makefile.am (keeps parallel work in separate files).

libaaengine_a_SOURCES += engine/methods/msaa.c engine/methods/gbaa.c engine/methods/copy.c \
	engine/gpu/sample_positions.h engine/gpu/sample_positions.c \
	engine/temporal/jitter.h engine/temporal/jitter.c \
	engine/methods/taa_impl.h engine/methods/taa_impl.c engine/methods/taa.c
glsl_files += shaders/gbaa.geom shaders/gbaa.frag shaders/gbaa_resolve.frag shaders/gbuffer.vert shaders/gbuffer.frag \
	shaders/taa_resolve.frag shaders/taa_master_resolve.frag shaders/taa_sharpen.frag \
	shaders/taa_sobel_edges.frag shaders/taa_sobel_stabilise.frag \
	shaders/taa_converge.comp shaders/taa_master_converge.comp
EXTRA_DIST += shaders/shading.glsl shaders/taa_common.glsl shaders/taa_resolve.glsl shaders/taa_converge.glsl \
	shaders/resolve_weight.glsl
$(glsl_headers): $(srcdir)/shaders/shading.glsl $(srcdir)/shaders/taa_common.glsl $(srcdir)/shaders/taa_resolve.glsl \
	$(srcdir)/shaders/taa_converge.glsl $(srcdir)/shaders/resolve_weight.glsl

check_PROGRAMS += tests/integration/test_analytic_edges
tests_integration_test_analytic_edges_SOURCES = tests/integration/test_analytic_edges.c $(GPU_TEST_FIXTURE)
tests_integration_test_analytic_edges_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_analytic_edges_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_analytic_edges

check_PROGRAMS += tests/integration/test_temporal
tests_integration_test_temporal_SOURCES = tests/integration/test_temporal.c $(GPU_TEST_FIXTURE)
tests_integration_test_temporal_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_temporal_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_temporal

# jitter through the real renderer: quads at two depths move by the same sub-pixel amount
check_PROGRAMS += tests/integration/test_temporal_jitter
tests_integration_test_temporal_jitter_SOURCES = tests/integration/test_temporal_jitter.c $(GPU_TEST_FIXTURE)
tests_integration_test_temporal_jitter_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_temporal_jitter_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_temporal_jitter
include $(srcdir)/engine/methods/smaa.mk
include $(srcdir)/engine/methods/fxaa.mk
include $(srcdir)/engine/methods/temporal2.mk
include $(srcdir)/engine/methods/rsaa.mk
include $(srcdir)/engine/methods/floor.mk
include $(srcdir)/engine/methods/user.mk

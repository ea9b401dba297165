# engine/methods: Makefile fragment, included from Makefile.am (keeps parallel work in separate files).

libaaengine_a_SOURCES += engine/methods/msaa.c engine/methods/gbaa.c engine/methods/copy.c \
	engine/gpu/sample_positions.h engine/gpu/sample_positions.c \
	engine/temporal/jitter.h engine/temporal/jitter.c
glsl_files += shaders/gbaa.geom shaders/gbaa.frag shaders/gbaa_resolve.frag shaders/gbuffer.vert shaders/gbuffer.frag
EXTRA_DIST += shaders/shading.glsl
$(glsl_headers): $(srcdir)/shaders/shading.glsl

check_PROGRAMS += tests/integration/test_analytic_edges
tests_integration_test_analytic_edges_SOURCES = tests/integration/test_analytic_edges.c
tests_integration_test_analytic_edges_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_analytic_edges_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_analytic_edges

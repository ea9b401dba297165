# SMAA 1x (engine/methods/smaa.c): the method, its generated look-up textures, shaders and tests.

libaaengine_a_SOURCES += engine/methods/smaa.h engine/methods/smaa.c engine/methods/smaa_textures.h engine/methods/smaa_textures.c
glsl_files += shaders/smaa_encode.frag shaders/smaa_edges.frag shaders/smaa_queue.comp \
	shaders/smaa_weights.comp shaders/smaa_blend.frag
EXTRA_DIST += shaders/smaa_queue.glsl
shaders/smaa_queue.comp.h shaders/smaa_weights.comp.h: $(srcdir)/shaders/smaa_queue.glsl

check_PROGRAMS += tests/unit/test_smaa_textures tests/integration/test_smaa
tests_unit_test_smaa_textures_SOURCES = tests/unit/test_smaa_textures.c
tests_unit_test_smaa_textures_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_smaa_textures_LDADD = $(TEST_LIBS)
tests_integration_test_smaa_SOURCES = tests/integration/test_smaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_smaa_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_smaa_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_smaa_textures tests/integration/test_smaa

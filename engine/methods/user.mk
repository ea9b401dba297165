# user methods (docs/user-methods.md): method files of the user's GLSL, compiled at run time with
# glslangValidator through a SPIR-V cache; the examples of examples/methods/ and their tests.
libaaengine_a_SOURCES += engine/methods/user_method.h engine/methods/user_method.c \
	engine/methods/user_method_file.c engine/methods/user_method_source.c engine/methods/user_method_glsl.c engine/methods/glsl_compile.h engine/methods/glsl_compile.c
# (engine/sha256.c, the content hash, is built by engine/farm.mk, which uses it too)
# the compiler configure found is the one user shaders are compiled with ($AALAB_GLSLANG overrides it)
AM_CPPFLAGS += -DAA_GLSLANG='"$(GLSLANG)"'
# the client reads a job's method files, and sends them to aalabd with the job
aalab_SOURCES += client/method_files.c

# method files, parameters, job specs, the GLSL of a pass, SHA-256, compiling and the SPIR-V cache
check_PROGRAMS += tests/unit/test_user_method
tests_unit_test_user_method_SOURCES = tests/unit/test_user_method.c
tests_unit_test_user_method_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_user_method_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_user_method

# on the GPU: a pass-through user method measured as `copy`, the contract's values in the shaders, the
# frame plan, compile errors and timing repeats
check_PROGRAMS += tests/integration/test_user_methods
tests_integration_test_user_methods_SOURCES = tests/integration/test_user_methods.c $(GPU_TEST_FIXTURE)
tests_integration_test_user_methods_CFLAGS = $(TEST_CFLAGS)
tests_integration_test_user_methods_LDADD = $(TEST_LIBS)
TESTS += tests/integration/test_user_methods

# the examples users copy (installed under pkgdatadir), run by the test of the CLI that also tries what a
# user would: a copy with a constant changed, a syntax error, a bad method file
examplesdir = $(pkgdatadir)/examples/methods
dist_examples_DATA = examples/methods/edge_blur.json examples/methods/edge_blur.frag \
	examples/methods/simple_taa.json examples/methods/simple_taa_resolve.frag \
	examples/methods/simple_taa_sharpen.comp
TESTS += tests/user_methods.sh
EXTRA_DIST += tests/user_methods.sh

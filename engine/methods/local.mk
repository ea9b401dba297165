# engine/methods: Makefile fragment, included from Makefile.am (keeps parallel work in separate files).

libaaengine_a_SOURCES += engine/methods/msaa.c engine/methods/gbaa.c \
	engine/gpu/sample_positions.h engine/gpu/sample_positions.c
glsl_files += shaders/gbaa.geom shaders/gbaa.frag shaders/gbaa_resolve.frag
EXTRA_DIST += shaders/shading.glsl
$(glsl_headers): $(srcdir)/shaders/shading.glsl

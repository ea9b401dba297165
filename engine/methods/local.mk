# engine/methods: the AA methods, one file each with its shaders, the registry that lists them, and what
# they share (jitter sequences, FXAA and SMAA tables, user methods read from method files).

# the registry, parameters and labels, alpha rules, jitter sequences
libaaengine_a_SOURCES += engine/methods/methods.h engine/methods/methods_registry.c \
	engine/methods/method_params.c engine/methods/methods_describe.c engine/methods/alpha_rule.c \
	engine/methods/jitter.h engine/methods/jitter.c

# none, copy and floor (the rasterizer's floor: the scene's geometry with a constant colour)
libaaengine_a_SOURCES += engine/methods/none.c engine/methods/copy.c engine/methods/floor.c
glsl_files += shaders/floor.frag

# ssaa and msaa (with virtual samples where the device lacks a count; Karis-weighted resolves)
libaaengine_a_SOURCES += engine/methods/ssaa.c engine/methods/msaa.c
glsl_files += shaders/virtual_sample.geom shaders/virtual_sample_gbuffer.geom \
	shaders/resolve_karis.frag shaders/resolve_karis_ms.frag

# gbaa
libaaengine_a_SOURCES += engine/methods/gbaa.c
glsl_files += shaders/gbaa.geom shaders/gbaa.frag shaders/gbaa_resolve.frag shaders/gbuffer.vert shaders/gbuffer.frag

# taa and taa-sobel (seed 001)
libaaengine_a_SOURCES += engine/methods/taa_impl.h engine/methods/taa_impl.c engine/methods/taa.c
glsl_files += shaders/taa_resolve.frag shaders/taa_master_resolve.frag shaders/taa_sharpen.frag \
	shaders/taa_sobel_edges.frag shaders/taa_sobel_stabilise.frag \
	shaders/taa_converge.comp shaders/taa_master_converge.comp shaders/taa_production.comp \
	shaders/taa_master_production.comp
EXTRA_DIST += shaders/taa_common.glsl shaders/taa_resolve.glsl shaders/taa_converge.glsl \
	shaders/resolve_weight.glsl
$(glsl_headers): $(srcdir)/shaders/taa_common.glsl $(srcdir)/shaders/taa_resolve.glsl \
	$(srcdir)/shaders/taa_converge.glsl $(srcdir)/shaders/resolve_weight.glsl

# asaa and t2msaa (seed 000)
libaaengine_a_SOURCES += engine/methods/asaa.c engine/methods/t2msaa.c
temporal2_glsl = shaders/asaa.comp shaders/t2msaa.comp
glsl_files += $(temporal2_glsl)
EXTRA_DIST += shaders/asaa_t2msaa.glsl
$(patsubst shaders/%,shaders/%.h,$(temporal2_glsl)): $(srcdir)/shaders/asaa_t2msaa.glsl

# fxaa and fxaa-cs (FXAA 3.11, pixel shader and compute variants)
libaaengine_a_SOURCES += engine/methods/fxaa.h engine/methods/fxaa.c engine/methods/fxaa_cs.c
fxaa_glsl = shaders/fxaa_luma.frag shaders/fxaa_edges.frag shaders/fxaa.frag \
	shaders/fxaa_cs_luma.comp shaders/fxaa_cs_classify.comp shaders/fxaa_cs_edges.comp
glsl_files += $(fxaa_glsl)
EXTRA_DIST += shaders/fxaa_common.glsl shaders/fxaa_cs_queue.glsl
$(patsubst shaders/%,shaders/%.h,$(fxaa_glsl)): $(srcdir)/shaders/fxaa_common.glsl \
	$(srcdir)/shaders/fxaa_cs_queue.glsl

# smaa (SMAA 1x, T2x, S2x, 4x with its generated look-up textures)
libaaengine_a_SOURCES += engine/methods/smaa.h engine/methods/smaa.c engine/methods/smaa_textures.h \
	engine/methods/smaa_textures.c
glsl_files += shaders/smaa_encode.frag shaders/smaa_edges.frag shaders/smaa_queue.comp \
	shaders/smaa_weights.comp shaders/smaa_blend.frag shaders/smaa_resolve.frag
EXTRA_DIST += shaders/smaa_queue.glsl
shaders/smaa_queue.comp.h shaders/smaa_weights.comp.h: $(srcdir)/shaders/smaa_queue.glsl

# cmaa2 (conservative morphological AA: edges, shapes, deferred blend)
libaaengine_a_SOURCES += engine/methods/cmaa2.c
glsl_files += shaders/cmaa2_edges.comp shaders/cmaa2_shapes.comp shaders/cmaa2_apply.comp
EXTRA_DIST += shaders/cmaa2_common.glsl
shaders/cmaa2_edges.comp.h shaders/cmaa2_shapes.comp.h: $(srcdir)/shaders/cmaa2_common.glsl

# rsaa (seed 002: resampling from geometric subsamples with a trained offset table)
libaaengine_a_SOURCES += engine/methods/rsaa.c engine/methods/rsaa_table.h engine/methods/rsaa_table.c
rsaa_glsl = shaders/rsaa_prepass.comp shaders/rsaa_resolve.comp
glsl_files += $(rsaa_glsl)
EXTRA_DIST += shaders/rsaa_common.glsl
$(patsubst shaders/%,shaders/%.h,$(rsaa_glsl)): $(srcdir)/shaders/rsaa_common.glsl

# user methods (docs/user-methods.md): method files of the user's GLSL, compiled at run time with
# glslangValidator through a SPIR-V cache; the compiler configure found is the one user shaders are
# compiled with ($AALAB_GLSLANG overrides it)
libaaengine_a_SOURCES += engine/methods/user_method.h engine/methods/user_method.c \
	engine/methods/user_method_file.c engine/methods/user_method_source.c engine/methods/user_method_glsl.c \
	engine/methods/glsl_compile.h engine/methods/glsl_compile.c
AM_CPPFLAGS += -DAA_GLSLANG='"$(GLSLANG)"'
# the examples users copy, installed under pkgdatadir
examplesdir = $(pkgdatadir)/examples/methods
dist_examples_DATA = examples/methods/edge_blur.json examples/methods/edge_blur.frag \
	examples/methods/simple_taa.json examples/methods/simple_taa_resolve.frag \
	examples/methods/simple_taa_sharpen.comp

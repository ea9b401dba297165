# engine/reference: the ground truth: sums of jittered renders (a batch per summing pass, also used by
# virtual MSAA), the self-measuring auto reference, and exact coverage of 2D test patterns.
libaaengine_a_SOURCES += engine/reference/reference.h engine/reference/reference.c \
	engine/reference/owen_sobol.h engine/reference/owen_sobol.c \
	engine/reference/reference_auto.c engine/reference/sample_accumulator.h \
	engine/reference/sample_accumulator.c engine/reference/exact_coverage.h engine/reference/exact_coverage.c
glsl_files += shaders/accumulate.frag shaders/accumulate_batch.frag
# The stored references (a folder of entries keyed by content: reference_key.c, reference_cache.c).
libaaengine_a_SOURCES += engine/reference/reference_key.h engine/reference/reference_key.c \
	engine/reference/reference_cache.h engine/reference/reference_cache.c \
	engine/reference/reference_store.h engine/reference/reference_store.c
# The key's "code" part: the SHA-256 of the C that decides a reference's pixels (every layer up to this
# one), so that a build with other rendering code never reads this one's entries. Written at build time.
reference_code_files = $(filter engine/util/% engine/image/% engine/scene/% engine/gpu/% engine/render/% \
	engine/reference/%,$(libaaengine_a_SOURCES))
BUILT_SOURCES += engine/reference/reference_code.h
CLEANFILES += engine/reference/reference_code.h
AM_CPPFLAGS += -I$(builddir)/engine/reference
engine/reference/reference_code.h: $(reference_code_files:%=$(srcdir)/%)
	@$(MKDIR_P) engine/reference
	$(AM_V_GEN)d=$$(cd $(srcdir) && cat $(reference_code_files) | sha256sum | cut -c1-64) && \
	  echo "#define AA_REFERENCE_CODE_SHA256 \"$$d\"" >$@.tmp && mv $@.tmp $@
engine/reference/reference_key.$(OBJEXT): engine/reference/reference_code.h

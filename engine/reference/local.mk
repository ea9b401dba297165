# engine/reference: the ground truth: sums of jittered renders (a batch per summing pass, also used by
# virtual MSAA), the self-measuring auto reference, and exact coverage of 2D test patterns.
libaaengine_a_SOURCES += engine/reference/reference.h engine/reference/reference.c \
	engine/reference/reference_auto.c engine/reference/sample_accumulator.h \
	engine/reference/sample_accumulator.c engine/reference/exact_coverage.h engine/reference/exact_coverage.c
glsl_files += shaders/accumulate.frag shaders/accumulate_batch.frag

# engine/reference: sums of jittered renders, a batch per summing pass (the reference, virtual MSAA).
libaaengine_a_SOURCES += engine/reference/sample_accumulator.h engine/reference/sample_accumulator.c
glsl_files += shaders/accumulate_batch.frag
libaaengine_a_SOURCES += engine/reference/reference_auto.c

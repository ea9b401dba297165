# engine/gpu: Vulkan behind a few functions: the device, images and buffers, pipelines, compute passes,
# timestamp queries, standard sample positions and the table of embedded shaders.
libaaengine_a_SOURCES += \
	engine/gpu/gpu.h engine/gpu/gpu_device.c engine/gpu/gpu_resources.c \
	engine/gpu/gpu_pipeline.c engine/gpu/gpu_timer.c engine/gpu/shader_table.c \
	engine/gpu/sample_positions.h engine/gpu/sample_positions.c \
	engine/gpu/compute_pass.h engine/gpu/compute_pass.c

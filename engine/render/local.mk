# engine/render: a scene on the GPU and the frame methods render into: the frame plan, uploads, the scene
# and shadow passes with their cascades, full-screen passes, and the debug targets' readback.
libaaengine_a_SOURCES += \
	engine/render/frame_plan.h engine/render/frame_plan.c engine/render/renderer.h engine/render/renderer.c \
	engine/render/renderer_frame.c engine/render/scene_upload.h engine/render/scene_upload.c \
	engine/render/shadow_fit.h engine/render/shadow_fit.c \
	engine/render/debug_targets.h engine/render/debug_targets.c
glsl_files += shaders/scene.vert shaders/scene.frag shaders/shadow.vert shaders/shadow_cutout.frag \
	shaders/fullscreen.vert shaders/resolve_box.frag shaders/copy.frag
EXTRA_DIST += shaders/shading.glsl shaders/shading_point.glsl
$(glsl_headers): $(srcdir)/shaders/shading.glsl $(srcdir)/shaders/shading_point.glsl

# The rasterizer's floor (bench/floor, bench/methods): the scene's geometry with a constant colour.
libaaengine_a_SOURCES += engine/methods/floor.c
glsl_files += shaders/floor.frag

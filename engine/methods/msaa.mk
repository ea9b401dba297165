# MSAA's shading point (one rule for hardware and virtual samples) and its tests: Makefile fragment,
# included from Makefile.am.
glsl_files += shaders/virtual_sample.geom shaders/virtual_sample_gbuffer.geom
EXTRA_DIST += shaders/shading_point.glsl
$(glsl_headers): $(srcdir)/shaders/shading_point.glsl

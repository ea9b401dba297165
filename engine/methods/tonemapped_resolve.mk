# tonemapped_resolve=true of ssaa and msaa (issue 17): Karis-weighted resolves. Included from Makefile.am.
glsl_files += shaders/resolve_karis.frag shaders/resolve_karis_ms.frag
EXTRA_DIST += engine/methods/tonemapped_resolve.mk

/* GLSL to SPIR-V at run time, for user methods: glslangValidator run as a child process (a compiler that
 * crashes or never ends on a user's shader cannot take aalab with it, and is stopped at a time limit),
 * through a cache of SPIR-V files named by the SHA-256 of the compiler's version, the stage and the
 * source, so that each distinct shader is compiled once. */
#ifndef AA_GLSL_COMPILE_H
#define AA_GLSL_COMPILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "util/error.h"

/* Compiles glsl (size bytes) as a fragment or compute shader. shown_name is the user's file, which
 * compiler messages name: a compile error is AA_ERR_INVALID, "FILE:LINE: message" (up to three errors).
 * *words is malloc'ed, *bytes its size; *cached tells whether it came from the cache. */
int aa_glsl_compile(const char *glsl, size_t size, bool compute, const char *shown_name, uint32_t **words,
		    size_t *bytes, bool *cached, struct aa_error *err);

/* The cache folder: DIR/spirv/ holds SHA256.spv. NULL restores the default: $AALAB_CACHE_DIR, else
 * $XDG_CACHE_HOME/aalab, else $HOME/.cache/aalab; "" turns the cache off. The folder is created when
 * first written; when it cannot be, shaders are compiled every time. */
void aa_glsl_set_cache_dir(const char *dir);
/* The SPIR-V cache folder in use ("" when there is none). */
void aa_glsl_cache_dir(char *out, size_t size);

#endif

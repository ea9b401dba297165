/* The contract of an AA method: a name, its parameters and what it needs from the frame plan, plus four
 * functions. The methods themselves are one file each in engine/methods/ (methods.h: the registry). */
#ifndef AA_METHOD_H
#define AA_METHOD_H

#include <stdbool.h>
#include <stddef.h>

#include "util/error.h"

#define AA_MAX_PARAMS 12

enum aa_param_type { AA_PARAM_INT, AA_PARAM_FLOAT, AA_PARAM_ENUM, AA_PARAM_BOOL };

struct aa_param_def {
	const char *name;
	enum aa_param_type type;
	double def;                      /* default; for enums the index into choices */
	double min, max;                 /* numeric range (inclusive) */
	const int *allowed;              /* INT only: if not NULL, the only valid values, terminated by 0 */
	const char *const *choices;      /* ENUM only: NULL-terminated names */
	const char *help;
};

/* What a method asks of the frame plan (render/frame_plan.h). */
enum aa_need {
	AA_NEED_DEPTH = 1u << 0,
	AA_NEED_VELOCITY = 1u << 1,
	AA_NEED_IDS = 1u << 2,
	AA_NEED_SUBSAMPLES = 1u << 3,
	AA_NEED_HISTORY = 1u << 4,
	AA_NEED_MSAA = 1u << 5,
	AA_NEED_GBUFFER = 1u << 6,
	AA_NEED_SUPERSAMPLED = 1u << 7,
};

/* How a method treats alpha-tested (cut-out) geometry (docs/methods.md, "Alpha-tested geometry"). */
enum aa_alpha_rule {
	AA_ALPHA_FROM_NEEDS = 0, /* not stated: per sample with history or supersampling, else per pixel */
	AA_ALPHA_PER_PIXEL,      /* once per pixel and triangle, at its shading point (MSAA-style, 1-spp) */
	AA_ALPHA_PER_SAMPLE,     /* every sample tested (supersampling, temporal accumulation) */
	AA_ALPHA_TO_COVERAGE,    /* alpha sets the share of samples covered (a method's alpha_to_coverage) */
};

/* Parsed parameter values, in the order of the method's params table (enums as indices). */
struct aa_method_params {
	double v[AA_MAX_PARAMS];
};

struct aa_renderer;       /* engine/render/renderer.h */
struct aa_method_state;   /* private to each method */
struct aa_frame_ctx;      /* engine/render/renderer.h: the frame being rendered */
struct aa_method_result;  /* engine/types/job.h: create() records path_taken and every allocation there */

struct aa_method {
	const char *name;
	const char *summary;
	const char *seed;                 /* the source document, e.g. "seed 001" */
	const struct aa_param_def *params;
	int param_count;
	const char *main_param;           /* the parameter a bare number sets ("ssaa:16"), or NULL */
	unsigned needs;                   /* AA_NEED_* bits, may depend on params: see needs_fn */
	unsigned (*needs_fn)(const struct aa_method_params *p);
	enum aa_alpha_rule alpha_rule;    /* AA_ALPHA_FROM_NEEDS unless stated; see aa_method_alpha_rule */

	int (*create)(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		      struct aa_method_state **out, struct aa_error *err);
	/* Records frame ctx into ctx->cmd, timing each of its passes with ctx->timer, and sets ctx->output
	 * to its result: a linear RGBA16F (or RGBA32F) image of the frame size. */
	int (*render)(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err);
	void (*reset)(struct aa_method_state *s); /* camera cut: forget history */
	void (*destroy)(struct aa_method_state *s);
	/* Methods defined at run time (user methods, user_method.h) create through this instead of create:
	 * it is given the method itself, whose definition it reads. */
	int (*create_self)(const struct aa_method *self, struct aa_renderer *r, const struct aa_method_params *p,
			   struct aa_method_result *info, struct aa_method_state **out, struct aa_error *err);
};

#endif

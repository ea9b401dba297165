/* An AA method: a name, its parameters and what it needs from the frame plan, plus four functions.
 * One method per file in engine/methods/; methods_registry.c lists them. */
#ifndef AA_METHOD_H
#define AA_METHOD_H

#include <stdbool.h>
#include <stddef.h>

#include "../error.h"

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

/* What a method asks of the frame plan (DESIGN.md rule 3). */
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

struct aa_renderer;       /* engine/renderer.h */
struct aa_method_state;   /* private to each method */
struct aa_frame_ctx;      /* engine/renderer.h: the frame being rendered */
struct aa_method_result;  /* engine/job.h: create() records path_taken and every allocation there */

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

/* Creates an instance of m: create_self when m has one, else create. */
int aa_method_create(const struct aa_method *m, struct aa_renderer *r, const struct aa_method_params *p,
		     struct aa_method_result *info, struct aa_method_state **out, struct aa_error *err);

extern const struct aa_method *const aa_methods[];
extern const int aa_method_count;

const struct aa_method *aa_method_find(const char *name);
int aa_method_param_index(const struct aa_method *m, const char *name);

/* Longest method text ("name:key=value,...") the parser accepts, in bytes including the NUL. */
#define AA_METHOD_TEXT_MAX 512

/* Parses "name", "name:N" (main parameter) or "name:key=value,key=value"; whitespace around items is
 * ignored. path names the field for errors (e.g. "methods[2]") and goes to err->path. Unknown method:
 * AA_ERR_NOT_FOUND; anything else: AA_ERR_INVALID. aa_method_label gives the canonical text. */
int aa_method_parse(const char *text, const char *path, const struct aa_method **method,
		    struct aa_method_params *params, struct aa_error *err);
/* The part after ':' for a known method m ("16", "preset=39,subpix=0.75"): resets params to m's
 * defaults, then sets each item; refuses unknown keys, bad values, duplicates and bare values for
 * methods without a main parameter. aa_method_parse uses it; tests call it with their own tables. */
int aa_method_parse_params(const struct aa_method *m, const char *list, const char *path,
			   struct aa_method_params *params, struct aa_error *err);
/* "none, ssaa, ...": the registry's method names, for messages. */
void aa_method_list_names(char *out, size_t size);
/* Sets one parameter from text, validating type, range and allowed values. */
int aa_method_set_param(const struct aa_method *m, struct aa_method_params *params, const char *key,
			const char *value, const char *path, struct aa_error *err);
void aa_method_defaults(const struct aa_method *m, struct aa_method_params *params);
/* Canonical label: the name; then the main parameter's value, always ("ssaa:16", "msaa:4"); then the other
 * non-default parameters in table order as key=value joined by ',' ("fxaa:preset=12,subpix=0.5",
 * "msaa:8,resolve=box"). The label parses back to the same parameters. */
void aa_method_label(const struct aa_method *m, const struct aa_method_params *p, char *out, size_t size);
/* Every registered method as JSON: [{name, summary, seed, params: [{name, type, default, valid, help,
 * main}]}] (the caller owns the array). `aalab methods --json` and aalabd's `methods` reply. */
struct json_t;
struct json_t *aa_methods_describe(void);
/* The alpha rule a method runs with: alpha to coverage when its `alpha_to_coverage` parameter is true,
 * else the stated rule, else per sample for methods with history or supersampling and per pixel for the
 * rest. aa_alpha_rule_name: "per-pixel", "per-sample", "alpha-to-coverage". */
enum aa_alpha_rule aa_method_alpha_rule(const struct aa_method *m, const struct aa_method_params *p);
const char *aa_alpha_rule_name(enum aa_alpha_rule rule);
/* Writes the value of parameter i as text ("16", "0.75", "high", "true"). */
void aa_method_param_text(const struct aa_method *m, const struct aa_method_params *p, int i, char *out,
			  size_t size);

#endif

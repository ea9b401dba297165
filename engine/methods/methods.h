/* The registry of built-in methods (methods_registry.c) and what works on any method: finding one by name,
 * parsing "name:key=value", canonical labels, parameters as text, the alpha rule a method runs with. */
#ifndef AA_METHODS_H
#define AA_METHODS_H

#include "types/method.h"

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
/* " (did you mean 'smaa'?)" for a misspelt method name, or "". */
void aa_method_suggest(const char *name, char *out, size_t size);
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
 * else the stated rule, else per pixel for methods on MSAA samples, per sample for methods with history or
 * supersampling and per pixel for the rest. aa_alpha_rule_name: "per-pixel", "per-sample", "alpha-to-coverage". */
enum aa_alpha_rule aa_method_alpha_rule(const struct aa_method *m, const struct aa_method_params *p);
const char *aa_alpha_rule_name(enum aa_alpha_rule rule);
/* Writes the value of parameter i as text ("16", "0.75", "high", "true"). */
void aa_method_param_text(const struct aa_method *m, const struct aa_method_params *p, int i, char *out,
			  size_t size);

#endif

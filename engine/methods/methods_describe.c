/* The registry described as JSON: what `aalab methods` prints and aalabd's `methods` answers, from one
 * place. */
#include <stdio.h>
#include <string.h>

#include <jansson.h>

#include "types/method.h"
#include "methods/user_method.h"
#include "methods/methods.h"

static const char *type_name(enum aa_param_type t)
{
	switch (t) {
	case AA_PARAM_INT: return "int";
	case AA_PARAM_FLOAT: return "float";
	case AA_PARAM_ENUM: return "enum";
	case AA_PARAM_BOOL: return "bool";
	}
	return "?";
}

static void valid_values(const struct aa_param_def *d, char *out, size_t size)
{
	size_t n = 0;
	out[0] = 0;
	if (d->allowed) {
		for (int i = 0; d->allowed[i]; i++)
			n += (size_t)snprintf(out + n, n < size ? size - n : 0, "%s%d", i ? ", " : "", d->allowed[i]);
	} else if (d->choices) {
		for (int i = 0; d->choices[i]; i++)
			n += (size_t)snprintf(out + n, n < size ? size - n : 0, "%s%s", i ? ", " : "", d->choices[i]);
	} else if (d->type == AA_PARAM_BOOL) {
		snprintf(out, size, "true, false");
	} else {
		snprintf(out, size, "%g..%g", d->min, d->max);
	}
}

json_t *aa_methods_describe(void)
{
	json_t *arr = json_array();
	for (int i = 0; i < aa_method_count; i++) {
		const struct aa_method *m = aa_methods[i];
		struct aa_method_params defaults;
		aa_method_defaults(m, &defaults);
		json_t *params = json_array();
		for (int p = 0; p < m->param_count; p++) {
			const struct aa_param_def *d = &m->params[p];
			char def[64], valid[256];
			aa_method_param_text(m, &defaults, p, def, sizeof def);
			valid_values(d, valid, sizeof valid);
			json_array_append_new(params, json_pack("{ss ss ss ss ss sb}", "name", d->name, "type",
								type_name(d->type), "default", def, "valid", valid,
								"help", d->help ? d->help : "", "main",
								m->main_param && !strcmp(m->main_param, d->name)));
		}
		json_array_append_new(arr, json_pack("{ss ss ss so}", "name", m->name, "summary", m->summary, "seed",
						     m->seed, "params", params));
	}
	/* a user method's parameters are its method file's: file=FILE.json, then those */
	const struct aa_method *user = &aa_method_user;
	json_array_append_new(arr, json_pack("{ss ss ss s[{ss ss ss ss ss sb}]}", "name", user->name, "summary",
					     user->summary, "seed", user->seed, "params", "name", "file", "type", "file",
					     "default", "", "valid", "a method file (docs/user-methods.md)", "help",
					     "the method file; its own parameters follow as name=value", "main", 0));
	return arr;
}

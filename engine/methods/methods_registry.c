/* The list of AA methods: adding a method adds one line here. User methods (`user`, user_method.h) are
 * not listed: each is made from its method file, and `aalab methods` describes `user` after these. */
#include <string.h>

#include "types/method.h"

extern const struct aa_method aa_method_none;
extern const struct aa_method aa_method_ssaa;
extern const struct aa_method aa_method_msaa;
extern const struct aa_method aa_method_gbaa;
extern const struct aa_method aa_method_copy;
extern const struct aa_method aa_method_floor;
extern const struct aa_method aa_method_taa;
extern const struct aa_method aa_method_taa_sobel;
extern const struct aa_method aa_method_smaa;
extern const struct aa_method aa_method_cmaa2;
extern const struct aa_method aa_method_fxaa;
extern const struct aa_method aa_method_fxaa_cs;
extern const struct aa_method aa_method_asaa;
extern const struct aa_method aa_method_t2msaa;
extern const struct aa_method aa_method_rsaa;

const struct aa_method *const aa_methods[] = {
	&aa_method_none,
	&aa_method_ssaa,
	&aa_method_msaa,
	&aa_method_gbaa,
	&aa_method_taa,
	&aa_method_taa_sobel,
	&aa_method_copy,
	&aa_method_floor,
	&aa_method_smaa,
	&aa_method_cmaa2,
	&aa_method_fxaa,
	&aa_method_fxaa_cs,
	&aa_method_asaa,
	&aa_method_t2msaa,
	&aa_method_rsaa,
};
const int aa_method_count = (int)(sizeof aa_methods / sizeof aa_methods[0]);

const struct aa_method *aa_method_find(const char *name)
{
	for (int i = 0; i < aa_method_count; i++)
		if (strcmp(aa_methods[i]->name, name) == 0)
			return aa_methods[i];
	return NULL;
}

int aa_method_param_index(const struct aa_method *m, const char *name)
{
	for (int i = 0; i < m->param_count; i++)
		if (strcmp(m->params[i].name, name) == 0)
			return i;
	return -1;
}

int aa_method_create(const struct aa_method *m, struct aa_renderer *r, const struct aa_method_params *p,
		     struct aa_method_result *info, struct aa_method_state **out, struct aa_error *err)
{
	return m->create_self ? m->create_self(m, r, p, info, out, err) : m->create(r, p, info, out, err);
}

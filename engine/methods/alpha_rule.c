/* Which alpha rule a method runs with: one rule per method family, so that a ranking on cut-out
 * geometry says something about the methods rather than about how each one happened to test alpha. */
#include <string.h>

#include "types/method.h"
#include "methods/methods.h"

enum aa_alpha_rule aa_method_alpha_rule(const struct aa_method *m, const struct aa_method_params *p)
{
	int a2c = aa_method_param_index(m, "alpha_to_coverage");
	if (a2c >= 0 && p && p->v[a2c] != 0)
		return AA_ALPHA_TO_COVERAGE;
	if (m->alpha_rule != AA_ALPHA_FROM_NEEDS)
		return m->alpha_rule;
	unsigned needs = m->needs_fn && p ? m->needs_fn(p) : m->needs;
	if (needs & AA_NEED_MSAA) /* one test per pixel and frame at the shading point, as MSAA */
		return AA_ALPHA_PER_PIXEL;
	return needs & (AA_NEED_HISTORY | AA_NEED_SUPERSAMPLED) ? AA_ALPHA_PER_SAMPLE : AA_ALPHA_PER_PIXEL;
}

const char *aa_alpha_rule_name(enum aa_alpha_rule rule)
{
	switch (rule) {
	case AA_ALPHA_PER_SAMPLE: return "per-sample";
	case AA_ALPHA_TO_COVERAGE: return "alpha-to-coverage";
	case AA_ALPHA_PER_PIXEL:
	case AA_ALPHA_FROM_NEEDS: break;
	}
	return "per-pixel";
}

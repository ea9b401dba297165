/* The gate grammar of `aalab compare --fail-if` (docs/compare.md, "Gates"):
 *     gate   = metric op change
 *     metric = psnr | ssim | flip | flicker | gpu_ms | cpu_ms | memory
 *     op     = "<" | "<=" | ">" | ">="
 *     change = ["+" | "-"] decimal ["%"]
 * with optional spaces between the parts. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare/compare.h"

static const char *const metric_names[AA_GATE_METRIC_COUNT] = {
	"psnr", "ssim", "flip", "flicker", "gpu_ms", "cpu_ms", "memory",
};

const char *aa_gate_metric_name(enum aa_gate_metric m)
{
	return m < AA_GATE_METRIC_COUNT ? metric_names[m] : "?";
}

static const char *op_text(enum aa_gate_op op)
{
	switch (op) {
	case AA_GATE_LT: return "<";
	case AA_GATE_LE: return "<=";
	case AA_GATE_GT: return ">";
	case AA_GATE_GE: return ">=";
	}
	return "?";
}

static int bad(struct aa_error *err, const char *path, const char *text, const char *why)
{
	char shown[64];
	size_t n = 0;
	for (; text[n] && n + 1 < sizeof shown; n++)
		shown[n] = iscntrl((unsigned char)text[n]) ? '?' : text[n];
	shown[n] = '\0';
	return aa_error_set(err, AA_ERR_INVALID, path, "\"%s\" is not a gate: %s; write METRIC OP CHANGE, e.g. "
			    "'psnr < -0.1', 'gpu_ms > +10%%' or 'flip > +0.005' (metrics: psnr, ssim, flip, flicker, "
			    "gpu_ms, cpu_ms, memory)", shown, why);
}

int aa_gate_parse(const char *text, struct aa_gate *out, const char *path, struct aa_error *err)
{
	const char *p = text;
	struct aa_gate g = {0};
	while (isspace((unsigned char)*p))
		p++;
	size_t len = strspn(p, "abcdefghijklmnopqrstuvwxyz_");
	int m = -1;
	for (int i = 0; i < AA_GATE_METRIC_COUNT; i++)
		if (strlen(metric_names[i]) == len && !strncmp(p, metric_names[i], len))
			m = i;
	if (len == 12 && !strncmp(p, "memory_bytes", 12))
		m = AA_GATE_MEMORY;
	if (m < 0)
		return bad(err, path, text, len ? "unknown metric" : "it does not start with a metric");
	g.metric = (enum aa_gate_metric)m;
	p += len;
	while (isspace((unsigned char)*p))
		p++;
	if (*p == '<' || *p == '>') {
		bool less = *p == '<', equal = p[1] == '=';
		g.op = less ? (equal ? AA_GATE_LE : AA_GATE_LT) : (equal ? AA_GATE_GE : AA_GATE_GT);
		p += equal ? 2 : 1;
	} else {
		return bad(err, path, text, "expected <, <=, > or >= after the metric");
	}
	while (isspace((unsigned char)*p))
		p++;
	/* a plain decimal number: strtod alone would also take "nan", "inf" and hex */
	const char *num = p;
	if (*p == '+' || *p == '-')
		p++;
	size_t digits = strspn(p, "0123456789");
	p += digits;
	if (*p == '.') {
		size_t frac = strspn(p + 1, "0123456789");
		digits += frac;
		p += 1 + frac;
	}
	if (digits == 0)
		return bad(err, path, text, "expected a number after the operator");
	char number[64];
	if ((size_t)(p - num) >= sizeof number)
		return bad(err, path, text, "the number is too long");
	memcpy(number, num, (size_t)(p - num));
	number[p - num] = '\0';
	g.threshold = strtod(number, NULL);
	while (isspace((unsigned char)*p))
		p++;
	if (*p == '%') {
		g.percent = true;
		p++;
	}
	while (isspace((unsigned char)*p))
		p++;
	if (*p)
		return bad(err, path, text, "unexpected text after the number");
	if (!isfinite(g.threshold))
		return bad(err, path, text, "the number is out of range");
	snprintf(g.text, sizeof g.text, "%s %s %s%g%s", metric_names[g.metric], op_text(g.op),
		 g.threshold >= 0 ? "+" : "", g.threshold, g.percent ? "%" : "");
	*out = g;
	return 0;
}

/* What a farm wants to hear about: any real loss of quality, more flicker, a cost rise beyond the
 * runs' spread, more memory. Quality numbers are deterministic (the same commit renders the same
 * images), so their thresholds are small. Time is noisy: on a shared 2-core machine running lavapipe,
 * two runs of one commit differed by up to +40% in a method's judged change (interval's lower end,
 * docs/compare.md), so the default cost gate sits at +50%, below the +100% of a 2x slowdown. */
static const char *const default_gates[] = {
	"psnr < -0.1", "ssim < -0.001", "flip > +0.005", "flicker > +0.1", "gpu_ms > +50%", "memory > +10%",
};

int aa_gates_default(struct aa_gate *out, int max)
{
	int n = 0;
	for (size_t i = 0; i < sizeof default_gates / sizeof default_gates[0] && n < max; i++)
		if (aa_gate_parse(default_gates[i], &out[n], "", NULL) == 0)
			n++;
	return n;
}

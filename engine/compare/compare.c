/* Compares two runs' results.json documents (docs/compare.md): pairs their cases by id and their methods
 * by label (or, for a label found in one run only, by method name), measures the change of each metric,
 * and judges it by the gates. Quality numbers are deterministic and compared exactly; times are noisy,
 * so a cost change counts only when a bootstrap interval of it lies past the gate. */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare/compare.h"
#include "compare/compare_cost.h"

/* Bounds on what a results document may hold: the engine writes far less, but input is input. */
#define MAX_DOC_CASES 4096
#define MAX_DOC_METHODS 256
#define MAX_TIMED 1000000

struct side_method {
	const char *label, *name;
	json_t *obj, *params;
	char path[160];            /* "cases[1].methods[2]" */
	double quality[4];         /* psnr (+inf when identical), ssim, flip, flicker; NAN when missing */
	double memory;
	double *gpu, *cpu;         /* every timed render */
	int gpu_n, cpu_n;
	int paired;                /* index of the method it pairs with in the other run, or -1 */
	bool by_name;
};

struct side_case {
	char id[512];
	char path[48];
	json_t *obj;
	int frames;
	int method_count;
	struct side_method *methods;
	int paired;                /* index of the case in the other run, or -1 */
};

struct side {
	const char *name;          /* "BASE" or "NEW" */
	json_t *doc;
	int case_count;
	struct side_case *cases;
};

static void side_free(struct side *s)
{
	for (int c = 0; s->cases && c < s->case_count; c++) {
		for (int m = 0; s->cases[c].methods && m < s->cases[c].method_count; m++) {
			free(s->cases[c].methods[m].gpu);
			free(s->cases[c].methods[m].cpu);
		}
		free(s->cases[c].methods);
	}
	free(s->cases);
}

static int invalid(struct aa_error *err, const struct side *s, const char *path, const char *fmt, const char *what)
{
	char where[256];
	snprintf(where, sizeof where, "%.5s%s%.240s", s->name, *path ? " " : "", path);
	return aa_error_set(err, AA_ERR_INVALID, where, fmt, what);
}

/* A number, or NAN for null or a missing key; anything else is an error naming the field. */
static int get_number(const struct side *s, json_t *obj, const char *key, const char *path, double *out,
		      struct aa_error *err)
{
	json_t *v = json_is_object(obj) ? json_object_get(obj, key) : NULL;
	*out = NAN;
	if (!v || json_is_null(v))
		return 0;
	if (!json_is_number(v)) {
		char where[256];
		snprintf(where, sizeof where, "%s.%s", path, key);
		return invalid(err, s, where, "expected a number or null%s", "");
	}
	*out = json_number_value(v);
	return 0;
}

/* metrics.NAME.mean */
static int get_metric(const struct side *s, json_t *metrics, const char *name, const char *path, double *out,
		      struct aa_error *err)
{
	char where[256];
	snprintf(where, sizeof where, "%s.metrics.%s", path, name);
	json_t *m = json_object_get(metrics, name);
	if (m && !json_is_object(m))
		return invalid(err, s, where, "expected an object with \"mean\"%s", "");
	return get_number(s, m, "mean", where, out, err);
}

/* Every timed render's time (results without timed_renders: every frame's). */
static int get_times(const struct side *s, struct side_method *m, const char *key, double **out, int *n,
		     struct aa_error *err)
{
	json_t *list = json_object_get(m->obj, "timed_renders");
	const char *list_name = "timed_renders";
	if (!list) {
		list = json_object_get(m->obj, "frames");
		list_name = "frames";
	}
	*out = NULL;
	*n = 0;
	if (!list)
		return 0;
	char where[256];
	snprintf(where, sizeof where, "%s.%s", m->path, list_name);
	if (!json_is_array(list))
		return invalid(err, s, where, "expected an array%s", "");
	size_t count = json_array_size(list);
	if (count > MAX_TIMED)
		return invalid(err, s, where, "holds more than a million entries%s", "");
	*out = malloc((count ? count : 1) * sizeof **out);
	if (!*out)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	for (size_t i = 0; i < count; i++) {
		char item[300];
		snprintf(item, sizeof item, "%s[%zu]", where, i);
		double v;
		if (!json_is_object(json_array_get(list, i)))
			return invalid(err, s, item, "expected an object%s", "");
		if (get_number(s, json_array_get(list, i), key, item, &v, err) < 0)
			return -1;
		if (isfinite(v) && v >= 0)
			(*out)[(*n)++] = v;
	}
	return 0;
}

static int load_method(struct side *s, struct side_method *m, struct aa_error *err)
{
	if (!json_is_object(m->obj))
		return invalid(err, s, m->path, "expected a method object%s", "");
	json_t *label = json_object_get(m->obj, "label"), *name = json_object_get(m->obj, "name");
	if (!json_is_string(label) || !json_string_length(label)) {
		char where[200];
		snprintf(where, sizeof where, "%s.label", m->path);
		return invalid(err, s, where, "expected the method's label, a non-empty string%s", "");
	}
	if (name && !json_is_string(name)) {
		char where[200];
		snprintf(where, sizeof where, "%s.name", m->path);
		return invalid(err, s, where, "expected a string%s", "");
	}
	m->label = json_string_value(label);
	m->name = name ? json_string_value(name) : NULL;
	m->params = json_object_get(m->obj, "params");
	json_t *metrics = json_object_get(m->obj, "metrics");
	if (metrics && !json_is_object(metrics)) {
		char where[200];
		snprintf(where, sizeof where, "%s.metrics", m->path);
		return invalid(err, s, where, "expected an object%s", "");
	}
	static const char *const names[4] = {"psnr", "ssim", "flip", "flicker"};
	for (int i = 0; i < 4; i++)
		if (get_metric(s, metrics, names[i], m->path, &m->quality[i], err) < 0)
			return -1;
	/* an identical image has an infinite PSNR, written as null with identical: true */
	if (isnan(m->quality[0]) && json_is_true(json_object_get(json_object_get(metrics, "psnr"), "identical")))
		m->quality[0] = INFINITY;
	if (get_number(s, m->obj, "memory_bytes", m->path, &m->memory, err) < 0 ||
	    get_times(s, m, "gpu_ms", &m->gpu, &m->gpu_n, err) < 0 ||
	    get_times(s, m, "cpu_ms", &m->cpu, &m->cpu_n, err) < 0)
		return -1;
	m->paired = -1;
	return 0;
}

/* The id of a job's one case, as aa_case_id writes it: SCENE/PATH/WxH[@FIRST]. */
static int job_case_id(const struct side *s, json_t *doc, char *out, size_t size, struct aa_error *err)
{
	json_t *job = json_object_get(doc, "job");
	const char *scene = json_string_value(json_object_get(job, "scene"));
	const char *path = json_string_value(json_object_get(job, "path"));
	const char *wh = json_string_value(json_object_get(job, "size"));
	json_t *first = json_object_get(job, "first_frame");
	if (!json_is_object(job) || !scene || !path || !wh || (first && !json_is_integer(first)))
		return invalid(err, s, "job", "expected the job as run, with scene, path, size and first_frame "
			       "(is this a results.json?)%s", "");
	int n = snprintf(out, size, "%s/%s/%s", scene, path, wh);
	if (first && json_integer_value(first) != 0 && n > 0 && (size_t)n < size)
		snprintf(out + n, size - (size_t)n, "@%lld", (long long)json_integer_value(first));
	return 0;
}

static int load_side(struct side *s, json_t *doc, struct aa_error *err)
{
	s->doc = doc;
	if (!json_is_object(doc))
		return invalid(err, s, "", "is not a results.json document (expected a JSON object)%s", "");
	json_t *cases = json_object_get(doc, "cases");
	bool suite = cases != NULL;
	if (suite && !json_is_array(cases))
		return invalid(err, s, "cases", "expected an array of cases%s", "");
	if (!suite && !json_is_array(json_object_get(doc, "methods")))
		return invalid(err, s, "", "is not a results.json document: it has neither \"methods\" nor \"cases\"%s", "");
	size_t count = suite ? json_array_size(cases) : 1;
	if (count > MAX_DOC_CASES)
		return invalid(err, s, "cases", "holds too many cases%s", "");
	s->cases = calloc(count ? count : 1, sizeof *s->cases);
	if (!s->cases)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->case_count = (int)count;
	for (size_t c = 0; c < count; c++) {
		struct side_case *sc = &s->cases[c];
		sc->paired = -1;
		sc->obj = suite ? json_array_get(cases, c) : doc;
		if (suite)
			snprintf(sc->path, sizeof sc->path, "cases[%zu]", c);
		if (!json_is_object(sc->obj))
			return invalid(err, s, sc->path, "expected a case object%s", "");
		if (suite) {
			const char *id = json_string_value(json_object_get(sc->obj, "id"));
			char where[64];
			snprintf(where, sizeof where, "%s.id", sc->path);
			if (!id || !*id || strlen(id) >= sizeof sc->id)
				return invalid(err, s, where, "expected the case's id, a string like "
					       "\"thin-wires/default/160x90\"%s", "");
			snprintf(sc->id, sizeof sc->id, "%s", id);
		} else if (job_case_id(s, doc, sc->id, sizeof sc->id, err) < 0) {
			return -1;
		}
		for (size_t k = 0; k < c; k++)
			if (!strcmp(s->cases[k].id, sc->id))
				return invalid(err, s, sc->path, "has the id of an earlier case (%s)", sc->id);
		json_t *frames = json_object_get(sc->obj, "frames");
		sc->frames = json_is_integer(frames) ? (int)json_integer_value(frames) : -1;
		json_t *methods = json_object_get(sc->obj, "methods");
		char where[64];
		snprintf(where, sizeof where, "%s%smethods", sc->path, *sc->path ? "." : "");
		if (!json_is_array(methods))
			return invalid(err, s, where, "expected an array of methods%s", "");
		if (json_array_size(methods) > MAX_DOC_METHODS)
			return invalid(err, s, where, "holds too many methods%s", "");
		sc->method_count = (int)json_array_size(methods);
		sc->methods = calloc((size_t)(sc->method_count ? sc->method_count : 1), sizeof *sc->methods);
		if (!sc->methods)
			return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		for (int m = 0; m < sc->method_count; m++) {
			struct side_method *sm = &sc->methods[m];
			sm->obj = json_array_get(methods, (size_t)m);
			snprintf(sm->path, sizeof sm->path, "%s[%d]", where, m);
			if (load_method(s, sm, err) < 0)
				return -1;
			for (int k = 0; k < m; k++)
				if (!strcmp(sc->methods[k].label, sm->label))
					return invalid(err, s, sm->path, "has the label of an earlier method (%s)", sm->label);
		}
	}
	return 0;
}

/* The method's name: "name", else the label up to ':'. */
static void method_name(const struct side_method *m, char *out, size_t size)
{
	snprintf(out, size, "%s", m->name ? m->name : m->label);
	out[strcspn(out, ":")] = '\0';
}

/* Methods pair by label; a label found in one run only pairs with the one unpaired method of the same
 * name in the other run, when there is exactly one on each side. */
static void pair_methods(struct side_case *b, struct side_case *n)
{
	for (int i = 0; i < b->method_count; i++)
		for (int j = 0; j < n->method_count; j++)
			if (n->methods[j].paired < 0 && !strcmp(b->methods[i].label, n->methods[j].label)) {
				b->methods[i].paired = j;
				n->methods[j].paired = i;
				break;
			}
	for (int j = 0; j < n->method_count; j++) {
		if (n->methods[j].paired >= 0)
			continue;
		char name[128], other[128];
		method_name(&n->methods[j], name, sizeof name);
		int in_base = 0, in_new = 0, found = -1;
		for (int i = 0; i < b->method_count; i++) {
			method_name(&b->methods[i], other, sizeof other);
			if (b->methods[i].paired < 0 && !strcmp(name, other)) {
				in_base++;
				found = i;
			}
		}
		for (int k = 0; k < n->method_count; k++) {
			method_name(&n->methods[k], other, sizeof other);
			in_new += n->methods[k].paired < 0 && !strcmp(name, other);
		}
		if (in_base == 1 && in_new == 1) {
			b->methods[found].paired = j;
			n->methods[j].paired = found;
			b->methods[found].by_name = n->methods[j].by_name = true;
		}
	}
}

/* ---------------------------------------------------------------------------------------- output */

/* JSON has no NaN or Infinity: such values are null. */
static json_t *num(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

static bool gate_compare(enum aa_gate_op op, double v, double t)
{
	switch (op) {
	case AA_GATE_LT: return v < t;
	case AA_GATE_LE: return v <= t;
	case AA_GATE_GT: return v > t;
	case AA_GATE_GE: return v >= t;
	}
	return false;
}

static const char *const unit_of[AA_GATE_METRIC_COUNT] = {" dB", "", "", "", " ms", " ms", " bytes"};

/* A change as text: "+0.12 dB", "-3.4%", "-inf dB (was identical)". */
static void change_text(double v, bool percent, enum aa_gate_metric m, char *out, size_t size)
{
	if (isinf(v))
		snprintf(out, size, "%s", v > 0 ? "+inf (now identical)" : "-inf (was identical)");
	else if (percent)
		snprintf(out, size, "%+.1f%%", v);
	else if (m == AA_GATE_MEMORY)
		snprintf(out, size, "%+.0f%s", v, unit_of[m]);
	else
		snprintf(out, size, "%+.4g%s", v, unit_of[m]);
}

struct counts {
	int gates, held, tripped, unknown;
};

static json_t *quality_json(double b, double n)
{
	json_t *o = json_object();
	json_object_set_new(o, "base", num(b));
	json_object_set_new(o, "new", num(n));
	double change = n - b;
	if (isinf(b) && isinf(n))
		change = 0; /* both identical to the reference */
	json_object_set_new(o, "change", num(change));
	json_object_set_new(o, "change_pct", num(isfinite(b) && b != 0 ? 100.0 * change / fabs(b) : NAN));
	return o;
}

static json_t *cost_json(const struct cost_change *c)
{
	return json_pack("{s:{s:o, s:o, s:o, s:i}, s:{s:o, s:o, s:o, s:i}, s:o, s:o, s:o, s:o, s:o, s:o, s:[o, o], "
			 "s:[o, o]}",
			 "base", "median", num(c->base_median), "p10", num(c->base_p10), "p90", num(c->base_p90), "n",
			 c->base_n, "new", "median", num(c->new_median), "p10", num(c->new_p10), "p90",
			 num(c->new_p90), "n", c->new_n, "change_median_pct", num(c->change_median_pct), "change",
			 num(c->change), "change_pct", num(c->change_pct), "machine_factor", num(c->factor), "judged",
			 num(c->judged), "judged_pct", num(c->judged_pct), "interval", num(c->interval[0]),
			 num(c->interval[1]), "interval_pct", num(c->interval_pct[0]), num(c->interval_pct[1]));
}

/* Judges one gate on one pair of methods; appends the verdict to gates (and to tripped). */
static void judge(const struct aa_gate *g, const double quality_change[4], const double quality_pct[4],
		  double base_value[4], double new_value[4], double memory[2], const struct cost_change cost[2],
		  const char *case_id, const char *label, json_t *gates, json_t *tripped, struct counts *k)
{
	double value = NAN, lo = NAN, hi = NAN, b = NAN, n = NAN;
	bool cost_metric = g->metric == AA_GATE_GPU_MS || g->metric == AA_GATE_CPU_MS;
	const char *why_unknown = NULL;
	if (g->metric <= AA_GATE_FLICKER) {
		value = g->percent ? quality_pct[g->metric] : quality_change[g->metric];
		b = base_value[g->metric];
		n = new_value[g->metric];
		if (isnan(value))
			why_unknown = "a run has no value for it (flicker needs two frames; PSNR of an identical "
				      "image has no relative change)";
	} else if (g->metric == AA_GATE_MEMORY) {
		b = memory[0];
		n = memory[1];
		value = g->percent ? (b > 0 ? 100.0 * (n - b) / b : NAN) : n - b;
		if (isnan(value))
			why_unknown = "a run has no memory_bytes";
	} else {
		const struct cost_change *c = &cost[g->metric == AA_GATE_CPU_MS];
		b = c->base_p10;
		n = c->new_p10;
		value = g->percent ? c->judged_pct : c->judged;
		lo = g->percent ? c->interval_pct[0] : c->interval[0];
		hi = g->percent ? c->interval_pct[1] : c->interval[1];
		if (c->base_n < MIN_TIMED_RENDERS || c->new_n < MIN_TIMED_RENDERS)
			why_unknown = "fewer than 5 timed renders in a run, too few to tell a change from noise: raise "
				      "frames or timing.repeat";
		else if (isnan(lo) || isnan(hi))
			why_unknown = "no interval (a run has no time)";
	}
	bool trips = false;
	if (!why_unknown) {
		/* a cost change counts only when the whole interval is past the threshold */
		if (cost_metric)
			trips = (g->op == AA_GATE_GT || g->op == AA_GATE_GE) ? gate_compare(g->op, lo, g->threshold)
									      : gate_compare(g->op, hi, g->threshold);
		else
			trips = gate_compare(g->op, value, g->threshold);
	}
	const char *result = why_unknown ? "unknown" : trips ? "tripped" : "held";
	char text[96], message[512];
	change_text(value, g->percent, g->metric, text, sizeof text);
	const char *metric = aa_gate_metric_name(g->metric);
	if (why_unknown) {
		snprintf(message, sizeof message, "%s: not judged: %s", g->text, why_unknown);
	} else if (cost_metric) {
		char lo_text[48], hi_text[48], raw_text[48];
		change_text(lo, g->percent, g->metric, lo_text, sizeof lo_text);
		change_text(hi, g->percent, g->metric, hi_text, sizeof hi_text);
		const struct cost_change *c = &cost[g->metric == AA_GATE_CPU_MS];
		change_text(g->percent ? c->change_pct : c->change, g->percent, g->metric, raw_text, sizeof raw_text);
		/* what was measured, then what was judged: the two differ by the machine factor */
		snprintf(message, sizeof message, "%s p10 %.3g -> %.3g ms (%s as measured); judged over the machine factor "
			 "x%.2f: %s, %.0f%% interval %s to %s: %s %s", metric, b, n, raw_text, c->factor, text,
			 100 * INTERVAL_LEVEL, lo_text, hi_text,
			 trips ? "the whole interval is past the gate" : "within the gate or the runs' spread", g->text);
	} else {
		snprintf(message, sizeof message, "%s changed by %s (%.6g -> %.6g): %s %s", metric, text, b, n,
			 trips ? "past the gate" : "within the gate", g->text);
	}
	json_t *o = json_pack("{s:s, s:s, s:s, s:o, s:s}", "gate", g->text, "metric", metric, "result", result,
			      "change", num(value), "message", message);
	if (cost_metric)
		json_object_set_new(o, "interval", json_pack("[o, o]", num(lo), num(hi)));
	if (isinf(value))
		json_object_set_new(o, "change_text", json_string(text));
	json_array_append_new(gates, o);
	k->gates++;
	if (why_unknown)
		k->unknown++;
	else if (trips)
		k->tripped++;
	else
		k->held++;
	if (trips)
		json_array_append_new(tripped, json_pack("{s:s, s:s, s:s, s:s}", "case", case_id, "method", label,
							 "gate", g->text, "message", message));
}

static json_t *param_changes(json_t *base, json_t *new_params)
{
	json_t *out = json_array();
	const char *key;
	json_t *v;
	if (json_is_object(base))
		json_object_foreach(base, key, v) {
			json_t *w = json_is_object(new_params) ? json_object_get(new_params, key) : NULL;
			if (!w || !json_equal(v, w))
				json_array_append_new(out, json_pack("{s:s, s:O, s:O}", "param", key, "base", v, "new",
								     w ? w : json_null()));
		}
	if (json_is_object(new_params))
		json_object_foreach(new_params, key, v)
			if (!json_is_object(base) || !json_object_get(base, key))
				json_array_append_new(out, json_pack("{s:s, s:n, s:O}", "param", key, "new", v));
	return out;
}

static int compare_pair(const struct side_case *bc, const struct side_method *bm, const struct side_method *nm,
			const struct cost_change cost[2], const struct aa_compare_options *o, json_t *tripped,
			struct counts *k, json_t **out)
{
	double change[4], pct[4], bv[4], nv[4];
	static const char *const names[4] = {"psnr", "ssim", "flip", "flicker"};
	json_t *metrics = json_object();
	for (int i = 0; i < 4; i++) {
		bv[i] = bm->quality[i];
		nv[i] = nm->quality[i];
		change[i] = isinf(bv[i]) && isinf(nv[i]) ? 0 : nv[i] - bv[i];
		pct[i] = isfinite(bv[i]) && bv[i] != 0 ? 100.0 * change[i] / fabs(bv[i]) : NAN;
		json_t *q = quality_json(bv[i], nv[i]);
		if (i == 0) {
			json_object_set_new(q, "base_identical", json_boolean(isinf(bv[0])));
			json_object_set_new(q, "new_identical", json_boolean(isinf(nv[0])));
		}
		json_object_set_new(metrics, names[i], q);
	}
	json_object_set_new(metrics, "gpu_ms", cost_json(&cost[0]));
	json_object_set_new(metrics, "cpu_ms", cost_json(&cost[1]));
	double memory[2] = {bm->memory, nm->memory};
	json_t *mem = json_pack("{s:o, s:o, s:o, s:o}", "base", num(memory[0]), "new", num(memory[1]), "change",
				num(memory[1] - memory[0]), "change_pct",
				num(memory[0] > 0 ? 100.0 * (memory[1] - memory[0]) / memory[0] : NAN));
	json_object_set_new(metrics, "memory_bytes", mem);
	json_t *gates = json_array();
	for (int g = 0; g < o->gate_count; g++)
		judge(&o->gates[g], change, pct, bv, nv, memory, cost, bc->id, nm->label, gates, tripped, k);
	*out = json_pack("{s:s, s:s, s:s, s:o, s:o, s:o}", "label", nm->label, "base_label", bm->label, "paired_by",
			 bm->by_name ? "name" : "label", "params_changed", param_changes(bm->params, nm->params),
			 "metrics", metrics, "gates", gates);
	return 0;
}

/* One shared case: its methods paired, their costs judged together, every gate on every pair. */
static json_t *compare_case(struct side_case *bc, struct side_case *nc, const struct aa_compare_options *o,
			    json_t *tripped, struct counts *k, struct aa_error *err)
{
	pair_methods(bc, nc);
	int count = nc->method_count > 0 ? nc->method_count : 1;
	struct cost_input *gpu = calloc((size_t)count * 2, sizeof *gpu);
	struct cost_change *cost = calloc((size_t)count * 2, sizeof *cost);
	if (!gpu || !cost) {
		free(gpu);
		free(cost);
		aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		return NULL;
	}
	struct cost_input *cpu = gpu + count;
	for (int j = 0; j < nc->method_count; j++) {
		const struct side_method *nm = &nc->methods[j];
		if (nm->paired < 0)
			continue; /* no renders: never eligible, never counted in the factor */
		const struct side_method *bm = &bc->methods[nm->paired];
		gpu[j] = (struct cost_input){bm->gpu, nm->gpu, bm->gpu_n, nm->gpu_n};
		cpu[j] = (struct cost_input){bm->cpu, nm->cpu, bm->cpu_n, nm->cpu_n};
	}
	double factor[2], factor_interval[2][2];
	json_t *c = NULL;
	if (aa_compare_case_costs(gpu, nc->method_count, o->raw_cost, aa_compare_seed(bc->id, "gpu_ms", ""), cost, &factor[0],
		       factor_interval[0], err) == 0 &&
	    aa_compare_case_costs(cpu, nc->method_count, o->raw_cost, aa_compare_seed(bc->id, "cpu_ms", ""), cost + count, &factor[1],
		       factor_interval[1], err) == 0) {
		json_t *methods = json_array(), *only_b = json_array(), *only_n = json_array();
		for (int j = 0; j < nc->method_count; j++) {
			struct side_method *nm = &nc->methods[j];
			if (nm->paired < 0) {
				json_array_append_new(only_n, json_string(nm->label));
				continue;
			}
			struct cost_change pair_cost[2] = {cost[j], cost[count + j]};
			json_t *pair;
			compare_pair(bc, &bc->methods[nm->paired], nm, pair_cost, o, tripped, k, &pair);
			json_array_append_new(methods, pair);
		}
		for (int j = 0; j < bc->method_count; j++)
			if (bc->methods[j].paired < 0)
				json_array_append_new(only_b, json_string(bc->methods[j].label));
		c = json_pack("{s:s, s:o, s:{s:o, s:o}, s:{s:{s:o, s:[o, o]}, s:{s:o, s:[o, o]}}}", "id", bc->id,
			      "methods", methods, "unpaired", "base", only_b, "new", only_n, "machine_factor", "gpu_ms",
			      "value", num(factor[0]), "interval", num(factor_interval[0][0]), num(factor_interval[0][1]),
			      "cpu_ms", "value", num(factor[1]), "interval", num(factor_interval[1][0]),
			      num(factor_interval[1][1]));
		/* each run's verdict of the case (results.json's cost-quality front), as it is */
		json_t *vb = json_object_get(bc->obj, "verdict"), *vn = json_object_get(nc->obj, "verdict");
		if (c)
			json_object_set_new(c, "verdict", json_pack("{s:O, s:O}", "base", vb ? vb : json_null(), "new",
								     vn ? vn : json_null()));
		if (c && bc->frames != nc->frames)
			json_object_set_new(c, "frames_changed", json_pack("{s:i, s:i}", "base", bc->frames, "new",
									   nc->frames));
		if (!c)
			aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	}
	free(gpu);
	free(cost);
	return c;
}

static json_t *run_json(const struct side *s, const char *source)
{
	json_t *d = s->doc;
	json_t *labels = json_object_get(d, "labels");
	/* a document without labels gets an empty object of its own ("o" takes it, "O" would keep a reference) */
	return json_pack("{s:s, s:o, s:s, s:O, s:s, s:s, s:i}", "source", source ? source : "", "labels",
			 json_is_object(labels) ? json_incref(labels) : json_object(), "suite",
			 json_string_value(json_object_get(d, "suite")) ? json_string_value(json_object_get(d, "suite")) : "",
			 "job_hash", json_object_get(d, "job_hash") ? json_object_get(d, "job_hash") : json_null(),
			 "name", json_string_value(json_object_get(d, "name")) ? json_string_value(json_object_get(d, "name")) : "",
			 "started_at", json_string_value(json_object_get(d, "started_at")) ?
			 json_string_value(json_object_get(d, "started_at")) : "", "cases", s->case_count);
}

/* "a, b, c" of the ids of unpaired cases (bounded). */
static void missing_list(const struct side *s, char *out, size_t size, json_t *arr)
{
	size_t used = 0;
	out[0] = '\0';
	for (int c = 0; c < s->case_count; c++)
		if (s->cases[c].paired < 0) {
			if (arr)
				json_array_append_new(arr, json_string(s->cases[c].id));
			if (used < size)
				used += (size_t)snprintf(out + used, size - used, "%s%s", used ? ", " : "", s->cases[c].id);
		}
}

/* Why no gate judged anything: when no method paired, each shared case's methods ("case X: BASE has fxaa,
 * smaa; NEW has taa"); otherwise why the first gate was not judged. */
static void nothing_judged(const struct side *b, const struct side *n, json_t *cases, char *out, size_t size)
{
	bool pairs = false;
	for (int i = 0; i < b->case_count; i++)
		for (int m = 0; b->cases[i].paired >= 0 && m < b->cases[i].method_count; m++)
			pairs = pairs || b->cases[i].methods[m].paired >= 0;
	if (pairs) {
		const char *why = "no gates";
		size_t i, j;
		json_t *c, *m;
		json_array_foreach(cases, i, c)
			json_array_foreach(json_object_get(c, "methods"), j, m)
				if (!strcmp(why, "no gates") && json_array_size(json_object_get(m, "gates")))
					why = json_string_value(json_object_get(json_array_get(json_object_get(m, "gates"), 0),
										"message"));
		snprintf(out, size, "nothing was judged, so nothing can pass: the methods paired, but no gate could judge "
			 "them (%s); choose gates these runs can judge", why ? why : "no gates");
		return;
	}
	size_t used = (size_t)snprintf(out, size, "nothing was judged, so nothing can pass: no method pairs by label or "
				       "by name;");
	for (int i = 0; i < b->case_count && used < size; i++) {
		const struct side_case *bc = &b->cases[i];
		if (bc->paired < 0)
			continue;
		const struct side_case *nc = &n->cases[bc->paired];
		used += (size_t)snprintf(out + used, size - used, " case %s: BASE has", bc->id);
		for (int m = 0; m < bc->method_count && used < size; m++)
			used += (size_t)snprintf(out + used, size - used, "%s %s", m ? "," : "", bc->methods[m].label);
		for (int m = 0; m < nc->method_count && used < size; m++)
			used += (size_t)snprintf(out + used, size - used, "%s %s", m ? "," : "; NEW has", nc->methods[m].label);
		if (used < size)
			used += (size_t)snprintf(out + used, size - used, ";");
	}
	if (used < size)
		snprintf(out + used, size - used, " compare runs of the same methods");
}

json_t *aa_compare_results(const json_t *base, const json_t *new_run, const struct aa_compare_options *opts,
			   struct aa_error *err)
{
	struct aa_compare_options o = *opts;
	if (o.gate_count <= 0)
		o.gate_count = aa_gates_default(o.gates, AA_MAX_GATES);
	struct side b = {.name = "BASE"}, n = {.name = "NEW"};
	json_t *result = NULL;
	if (load_side(&b, (json_t *)base, err) < 0 || load_side(&n, (json_t *)new_run, err) < 0)
		goto done;
	int shared = 0;
	for (int i = 0; i < b.case_count; i++)
		for (int j = 0; j < n.case_count; j++)
			if (n.cases[j].paired < 0 && !strcmp(b.cases[i].id, n.cases[j].id)) {
				b.cases[i].paired = j;
				n.cases[j].paired = i;
				shared++;
				break;
			}
	char only_base[600], only_new[600];
	json_t *missing_base = json_array(), *missing_new = json_array();
	missing_list(&b, only_base, sizeof only_base, missing_new); /* in BASE only: missing from NEW */
	missing_list(&n, only_new, sizeof only_new, missing_base);
	if (shared == 0 || (!o.allow_missing && (only_base[0] || only_new[0]))) {
		aa_error_set(err, AA_ERR_INVALID, "", "the runs do not share their cases:%s%s%s%s%s%s",
			     only_base[0] ? " missing from NEW: " : "", only_base, only_base[0] && only_new[0] ? ";" : "",
			     only_new[0] ? " missing from BASE: " : "", only_new,
			     shared ? " (compare runs of the same suite, or pass --allow-missing to compare the cases "
				      "both have)" : " (no case in common)");
		json_decref(missing_base);
		json_decref(missing_new);
		goto done;
	}
	json_t *cases = json_array(), *tripped = json_array(), *gates = json_array();
	struct counts k = {0};
	for (int g = 0; g < o.gate_count; g++)
		json_array_append_new(gates, json_string(o.gates[g].text));
	for (int i = 0; i < b.case_count; i++) {
		if (b.cases[i].paired < 0)
			continue;
		json_t *c = compare_case(&b.cases[i], &n.cases[b.cases[i].paired], &o, tripped, &k, err);
		if (!c)
			goto drop;
		json_array_append_new(cases, c);
	}
	/* a comparison that judged nothing must not pass: name what did not pair, or why no gate could judge */
	if (k.held + k.tripped == 0) {
		char why[1500];
		nothing_judged(&b, &n, cases, why, sizeof why);
		aa_error_set(err, AA_ERR_INVALID, "", "%s", why);
		goto drop;
	}
	result = json_pack("{s:i, s:s, s:o, s:o, s:o, s:{s:s, s:s, s:f, s:i, s:i}, s:{s:i, s:i, s:i, s:i}, s:o, "
			   "s:o, s:{s:o, s:o}}",
			   "version", 1, "verdict", k.tripped ? "tripped" : "held", "base", run_json(&b, o.base_source),
			   "new", run_json(&n, o.new_source), "gates", gates, "cost_rule", "statistic", "p10",
			   "machine_factor", o.raw_cost ? "none" : "median over the case's methods", "interval_level",
			   INTERVAL_LEVEL, "resamples", RESAMPLES, "min_timed_renders", MIN_TIMED_RENDERS, "counts", "gates", k.gates, "held", k.held, "tripped", k.tripped, "unknown",
			   k.unknown, "tripped", tripped, "cases", cases, "missing", "base", missing_base, "new",
			   missing_new);
	if (!result)
		aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory building the comparison");
	goto done;
drop: /* the parts of a comparison that will not be made */
	json_decref(cases);
	json_decref(tripped);
	json_decref(gates);
	json_decref(missing_base);
	json_decref(missing_new);
done:
	side_free(&b);
	side_free(&n);
	return result;
}

int aa_compare_tripped(const json_t *comparison)
{
	const char *v = json_string_value(json_object_get(comparison, "verdict"));
	return v && !strcmp(v, "tripped");
}

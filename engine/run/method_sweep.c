/* Sweeps: a method item naming several values of its parameters, expanded into one item per configuration
 * (method_sweep.h). Only the expansion is done here; every configuration is then checked by the method
 * parser, so a sweep's values are validated, and their errors worded, as a single method's are. */
#include <stdio.h>
#include <string.h>

#include "types/job.h"
#include "methods/methods.h"
#include "run/method_sweep.h"
#include "util/json_text.h"

/* The most parameter items a method string is split into here; a longer list is left to the parser. */
#define SWEEP_MAX_ITEMS 32

static json_t *single(const json_t *item)
{
	json_t *list = json_array();
	if (list)
		json_array_append(list, (json_t *)item);
	return list;
}


/* Whether name (a method's name as a job gives it) is a user method's: those are read from their files
 * and cannot be swept. */
static bool is_user(const char *name)
{
	return !strcmp(name, "user");
}

/* The limit: a sweep whose configurations, counted up to the parameter named by field, pass room. */
static int past_room(struct aa_error *err, const char *path, const char *method, const char *field, int values,
		     long configurations, int room)
{
	const int before = AA_MAX_METHODS - room;
	char taken[96] = "";
	if (before > 0)
		snprintf(taken, sizeof taken, " (%d taken by the methods before it)", before);
	return aa_error_set(err, AA_ERR_LIMIT, path,
		   "%s: %s lists %d value%s, which makes the sweep %ld configurations; the job has room for %d%s: a "
		   "job compares at most %d methods, each configuration of a sweep counted as one", method, field,
		   values, values == 1 ? "" : "s", configurations, room, taken, AA_MAX_METHODS);
}

/* One parameter item of a method string: "key=" (or "" for a bare value of the main parameter) and its
 * values, one unless the item is a sweep. */
struct axis {
	const char *key; /* without '=', "" for a bare value */
	int count;
	const char *values[AA_MAX_METHODS];
};

/* "fxaa:preset=10|20|39,subpix=0.5|1": each comma item split at '|'. */
static json_t *expand_text(const json_t *item, const char *path, int room, struct aa_error *err)
{
	const char *text = json_string_value(item);
	char buf[AA_METHOD_TEXT_MAX], shown[64];
	if (!strchr(text, '|') || strlen(text) >= sizeof buf)
		return single(item); /* no sweep; an over-long text is the parser's error */
	memcpy(buf, text, strlen(text) + 1);
	char *colon = strchr(buf, ':');
	if (!colon || strchr(buf, '|') < colon) {
		aa_error_set(err, AA_ERR_INVALID, path, "\"%s\": '|' separates values of one parameter (fxaa:preset=10|39, "
		    "msaa:2|4|8), not methods; list each method apart", aa_shown_text(text, shown, sizeof shown));
		return NULL;
	}
	*colon = '\0';
	const char *name = aa_trim(buf);
	if (is_user(name)) {
		aa_error_set(err, AA_ERR_INVALID, path, "user: a user method cannot be swept; list each of its configurations "
		    "as a method of its own");
		return NULL;
	}
	struct axis axes[SWEEP_MAX_ITEMS];
	int n = 0;
	long configurations = 1;
	for (char *next = colon + 1, *part; next;) {
		part = next;
		char *comma = strchr(part, ',');
		next = comma ? comma + 1 : NULL;
		if (comma)
			*comma = '\0';
		if (n == SWEEP_MAX_ITEMS)
			return single(item); /* more items than any method has parameters: the parser says so */
		struct axis *a = &axes[n++];
		char *eq = strchr(part, '='), *values = part;
		a->key = "";
		if (eq) {
			*eq = '\0';
			a->key = aa_trim(part);
			values = eq + 1;
		}
		if (strchr(a->key, '|')) {
			aa_error_set(err, AA_ERR_INVALID, path, "%s: \"%s\": '|' separates values, not parameter names: write "
			    "key=V1|V2", name, aa_shown_text(a->key, shown, sizeof shown));
			return NULL;
		}
		/* the values are counted before they are kept: more than the job has room for is the limit's error,
		 * and a kept list never outgrows values[] (room is at most AA_MAX_METHODS) */
		const char *field = *a->key ? a->key : "the main parameter";
		int total = 1;
		for (const char *t = values; (t = strchr(t, '|')) != NULL; t++)
			total++;
		if (configurations * total > room) {
			past_room(err, path, name, field, total, configurations * total, room);
			return NULL;
		}
		a->count = 0;
		for (char *v = values, *bar; v; v = bar) {
			bar = strchr(v, '|');
			if (bar)
				*bar++ = '\0';
			v = aa_trim(v);
			if (!*v && total > 1) {
				aa_error_set(err, AA_ERR_INVALID, path, "%s: %s: an empty value in a sweep; write V1|V2 with a value "
				    "on each side of every '|'", name, field);
				return NULL;
			}
			a->values[a->count++] = v;
		}
		configurations *= total;
	}
	/* configuration c: axis k's value is digit k of c in the mixed radix of the counts, the last fastest */
	json_t *list = json_array();
	for (long c = 0; list && c < configurations; c++) {
		char out[AA_METHOD_TEXT_MAX];
		size_t used = (size_t)snprintf(out, sizeof out, "%s:", name);
		long rest = c, stride = configurations;
		for (int k = 0; k < n && used < sizeof out; k++) {
			stride /= axes[k].count;
			const char *value = axes[k].values[(rest / stride) % axes[k].count];
			used += (size_t)snprintf(out + used, sizeof out - used, "%s%s%s%s", k ? "," : "", axes[k].key,
						 *axes[k].key ? "=" : "", value);
		}
		json_array_append_new(list, json_string(out));
	}
	return list;
}

/* {"name": "fxaa", "params": {"preset": [10, 20, 39]}}: each array-valued parameter is an axis. */
static json_t *expand_object(const json_t *item, const char *path, int room, struct aa_error *err)
{
	const json_t *params = json_object_get(item, "params"), *name = json_object_get(item, "name");
	if (!json_is_object(params))
		return single(item);
	const char *key;
	json_t *value;
	const char *keys[SWEEP_MAX_ITEMS];
	const json_t *lists[SWEEP_MAX_ITEMS];
	int n = 0;
	long configurations = 1;
	char where[300], shown[64];
	json_object_foreach((json_t *)params, key, value) {
		snprintf(where, sizeof where, "%s.params.%s", path, aa_shown_text(key, shown, sizeof shown));
		if (json_is_string(value) && strchr(json_string_value(value), '|')) {
			aa_error_set(err, AA_ERR_INVALID, where, "\"%s\": in the object form a sweep is a list of values, "
			    "[10, 20, 39]", aa_shown_text(json_string_value(value), shown, sizeof shown));
			return NULL;
		}
		if (!json_is_array(value))
			continue;
		const char *method = json_is_string(name) ? json_string_value(name) : "method";
		if (is_user(method)) {
			aa_error_set(err, AA_ERR_INVALID, where, "user: a user method cannot be swept; list each of its "
			    "configurations as a method of its own");
			return NULL;
		}
		const int count = (int)(json_array_size(value) < 1000 ? json_array_size(value) : 1000);
		if (count == 0) {
			aa_error_set(err, AA_ERR_INVALID, where, "%s: an empty list; a sweep names at least one value", method);
			return NULL;
		}
		if (n == SWEEP_MAX_ITEMS || configurations * count > room) {
			past_room(err, where, method, key, count, configurations * count, room);
			return NULL;
		}
		keys[n] = key;
		lists[n++] = value;
		configurations *= count;
	}
	if (n == 0)
		return single(item);
	json_t *list = json_array();
	for (long c = 0; list && c < configurations; c++) {
		json_t *one = json_deep_copy(item), *p = json_object_get(one, "params");
		long stride = configurations;
		for (int k = 0; p && k < n; k++) {
			const long count = (long)json_array_size(lists[k]);
			stride /= count;
			json_object_set(p, keys[k], json_array_get(lists[k], (size_t)((c / stride) % count)));
		}
		json_array_append_new(list, one);
	}
	return list;
}

json_t *aa_method_sweep_expand(const json_t *item, const char *path, int room, struct aa_error *err)
{
	if (json_is_string(item))
		return expand_text(item, path, room, err);
	if (json_is_object(item))
		return expand_object(item, path, room, err);
	return single(item);
}

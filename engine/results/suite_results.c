/* results.json and report.html of a whole job: for a suite, one document whose "cases" hold each case's
 * results as a job of its own would have them (docs/results-format.md, "Suites"), and a report whose
 * table runs across cases and links each case's own report. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "run/farm.h"
#include "results/results.h"
#include "results/verdicts.h"
#include "run/job_spec.h"

static json_t *num(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

/* Image paths of a case are written relative to the case's directory; in the suite's results.json they
 * are relative to the job directory, as every path in the file is. */
static void prefix_image_paths(json_t *v, const char *prefix)
{
	const char *key;
	json_t *item;
	size_t i;
	if (json_is_object(v)) {
		json_object_foreach(v, key, item) {
			if (json_is_string(item) && (!strcmp(key, "image") || !strcmp(key, "diff") || !strcmp(key, "flip_map"))) {
				size_t n = strlen(prefix) + json_string_length(item) + 2;
				char *path = malloc(n);
				if (path) {
					snprintf(path, n, "%s/%s", prefix, json_string_value(item));
					json_string_set(item, path);
					free(path);
				}
			} else {
				prefix_image_paths(item, prefix);
			}
		}
	} else if (json_is_array(v)) {
		json_array_foreach(v, i, item)
			prefix_image_paths(item, prefix);
	}
}

static json_t *labels_json(const struct aa_job_spec *spec)
{
	json_t *o = json_object();
	for (int i = 0; i < spec->label_count && i < AA_MAX_LABELS; i++)
		json_object_set_new(o, spec->labels[i].key, json_string(spec->labels[i].value));
	return o;
}

json_t *aa_suite_results_to_json(const struct aa_suite_result *r)
{
	if (!r->spec.is_suite) { /* a job's own results.json, with the verdicts of its one case when asked */
		json_t *one = r->case_count > 0 ? aa_results_to_json(r->cases[0]) : NULL;
		if (one && r->spec.verdicts)
			json_object_set_new(one, "verdicts", aa_verdicts_json(r, NULL));
		return one;
	}
	char hash[80];
	aa_job_hash(&r->spec, hash, sizeof hash);
	const struct aa_job_result *first = r->case_count > 0 ? r->cases[0] : NULL;
	json_t *root = json_pack("{s:i, s:s, s:s, s:o, s:s, s:s, s:o, s:o}", "version", 1, "name", r->spec.name,
				 "suite", r->spec.suite, "labels", labels_json(&r->spec), "job_hash", hash,
				 "started_at", r->started_at, "wall_seconds", num(r->wall_seconds), "job",
				 aa_job_spec_to_json(&r->spec));
	json_t *cases = json_array();
	if (!root || !cases) {
		json_decref(root);
		json_decref(cases);
		return NULL;
	}
	if (first)
		json_object_set_new(root, "device", json_pack("{s:s, s:s, s:o}", "name", first->device_name, "driver",
							      first->driver_info, "timestamp_period_ns",
							      num(first->timestamp_period_ns)));
	for (int i = 0; i < r->case_count; i++) {
		json_t *c = aa_results_to_json(r->cases[i]);
		if (!c) {
			json_decref(cases);
			json_decref(root);
			return NULL;
		}
		char id[512], dir[600];
		aa_case_id(&r->spec, i, id, sizeof id);
		aa_case_relpath(&r->spec, i, dir, sizeof dir);
		/* the job's names are the suite's, given once above; the case is known by its id */
		json_object_del(c, "labels");
		json_object_del(c, "suite");
		json_object_del(c, "job_hash");
		prefix_image_paths(c, dir);
		json_object_set_new(c, "id", json_string(id));
		json_object_set_new(c, "dir", json_string(dir));
		json_array_append_new(cases, c);
	}
	json_object_set_new(root, "cases", cases);
	if (r->spec.verdicts)
		json_object_set_new(root, "verdicts", aa_verdicts_json(r, NULL));
	return root;
}

int aa_suite_write_event_images(const char *dir, const struct aa_job_spec *spec, const struct aa_event *ev,
				struct aa_error *err)
{
	if (!spec->is_suite)
		return aa_results_write_event_images(dir, ev, err);
	char rel[600], path[4200];
	aa_case_relpath(spec, ev->case_index, rel, sizeof rel);
	if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, rel) >= sizeof path)
		return aa_error_set(err, AA_ERR_IO, "", "path %s/%s is too long", dir, rel);
	return aa_results_write_event_images(path, ev, err);
}

/* Build farms on the jobs side: a job's suite key, label matching, its baseline (a job id, or the latest
 * finished job of the same suite with some labels) and the verdict of comparing with it, which the worker
 * records when a job ends (docs/protocol.md, "Build farms"). */
#include <stdio.h>
#include <string.h>

#include "compare/compare.h"
#include "jobs.h"
#include "run/farm.h"
#include "run/job_spec.h"

void farm_suite_key(const struct job *job, char *out, size_t size)
{
	if (job->spec.suite[0])
		snprintf(out, size, "%s", job->spec.suite);
	else
		aa_job_hash(&job->spec, out, size); /* a job without a suite name: the same work is the same suite */
}

bool farm_job_matches(const struct job *job, const struct aa_label *labels, int label_count, const char *suite)
{
	for (int i = 0; i < label_count; i++) {
		const char *v = aa_job_label(&job->spec, labels[i].key);
		if (!v || strcmp(v, labels[i].value))
			return false;
	}
	if (suite) {
		char key[80];
		farm_suite_key(job, key, sizeof key);
		if (strcmp(key, suite))
			return false;
	}
	return true;
}

/* The job a baseline names, for job (lock held): an id of a job that is done, or the latest done job
 * submitted before job in its suite with every label of "latest:KEY=VALUE,...". */
static int find_baseline(struct store *s, const struct job *job, const char *text, char *id, size_t size,
			 struct aa_error *err)
{
	struct aa_baseline b;
	if (aa_baseline_parse(text, &b, "baseline", err))
		return -1;
	if (!b.latest) {
		const struct job *base = store_find(s, b.job);
		if (!base)
			return aa_error_set(err, AA_ERR_NOT_FOUND, "baseline", "no job '%s'", b.job);
		if (base->state != JOB_DONE)
			return aa_error_set(err, AA_ERR_INVALID, "baseline", "job %s is %s; a baseline must be done", b.job,
					    job_state_name(base->state));
		snprintf(id, size, "%s", b.job);
		return 0;
	}
	char suite[80];
	farm_suite_key(job, suite, sizeof suite);
	const struct job *found = NULL;
	for (const struct job *j = s->jobs; j; j = j->next)
		if (j != job && j->state == JOB_DONE && strcmp(j->id, job->id) < 0 &&
		    farm_job_matches(j, b.labels, b.label_count, suite))
			found = j; /* the list is oldest first: the last match is the latest */
	if (!found)
		return aa_error_set(err, AA_ERR_NOT_FOUND, "baseline", "no finished job of suite %s%s%s before job %s",
				    suite, b.label_count ? " with labels " : "", b.label_count ? text + 7 : "", job->id);
	snprintf(id, size, "%s", found->id);
	return 0;
}

static json_t *load_results(struct store *s, const char *id, struct aa_error *err)
{
	char path[1400];
	json_error_t jerr;
	snprintf(path, sizeof path, "%s/%s/results.json", s->dir, id);
	json_t *doc = json_load_file(path, 0, &jerr);
	if (!doc)
		aa_error_set(err, AA_ERR_IO, "", "job %s: cannot read results.json: %s", id, jerr.text);
	return doc;
}

/* Compares job (NEW) with the job its baseline names (BASE). *base_id is set once found. */
json_t *farm_compare_with(struct store *s, struct job *job, const char *baseline, const struct aa_compare_options *opts,
			    char *base_id, size_t size, struct aa_error *err)
{
	pthread_mutex_lock(&s->lock);
	int rc = find_baseline(s, job, baseline, base_id, size, err);
	char new_id[16];
	snprintf(new_id, sizeof new_id, "%s", job->id);
	pthread_mutex_unlock(&s->lock);
	if (rc)
		return NULL;
	struct aa_compare_options o = *opts;
	/* the ids, as `aalab compare BASE NEW` given job ids names them: the same JSON either way */
	o.base_source = base_id;
	o.new_source = new_id;
	json_t *base = load_results(s, base_id, err), *fresh = base ? load_results(s, new_id, err) : NULL;
	json_t *cmp = fresh ? aa_compare_results(base, fresh, &o, err) : NULL;
	json_decref(base);
	json_decref(fresh);
	return cmp;
}

json_t *farm_judge_baseline(struct store *s, struct job *job)
{
	if (!job->spec.baseline[0])
		return NULL;
	struct aa_compare_options o = {0}; /* the default gates */
	struct aa_error err = {0};
	char base_id[16] = "";
	json_t *cmp = farm_compare_with(s, job, job->spec.baseline, &o, base_id, sizeof base_id, &err);
	if (!cmp)
		/* the first run of a suite has nothing to compare with: that is no failure of the job */
		return json_pack("{ss ss ss}", "baseline", job->spec.baseline, "verdict",
				 err.code == AA_ERR_NOT_FOUND ? "no_baseline" : "error", "message", err.message);
	json_t *tripped = json_array(), *t;
	size_t i;
	json_array_foreach(json_object_get(cmp, "tripped"), i, t)
		if (i < 20) /* the first few; /v1/jobs/ID/compare has them all */
			json_array_append(tripped, t);
	json_t *v = json_pack("{ss ss sO sO so}", "baseline", job->spec.baseline, "job", base_id, "verdict",
			      json_object_get(cmp, "verdict"), "counts", json_object_get(cmp, "counts"), "tripped",
			      tripped);
	json_decref(cmp);
	return v;
}

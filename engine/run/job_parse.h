/* Inside the engine: the field checks of engine/run/job_spec.c, shared with engine/run/job_suite.c so that suite
 * keys are validated (and their errors worded) exactly as the single-case keys are. */
#ifndef AA_JOB_PARSE_H
#define AA_JOB_PARSE_H

#include "types/job.h"

int aa_job_parse_int(const json_t *v, const char *path, long long min, long long max, int *out,
		     struct aa_error *err);
int aa_job_parse_string(const json_t *v, const char *path, bool allow_empty, char *out, size_t size,
			struct aa_error *err);
int aa_job_parse_keys(const json_t *obj, const char *path, const char *const *valid, struct aa_error *err);
int aa_job_parse_scene(const char *scene, const char *path, struct aa_error *err);

/* engine/run/job_suite.c: after the single-case keys are parsed into s (they are the defaults of every
 * case), reads suite, scenes, paths, sizes, cases, labels and baseline. */
int aa_job_suite_from_json(const json_t *job, struct aa_job_spec *s, struct aa_error *err);
/* Adds them to a canonical job object; for a suite, cases replace the single-case keys. */
void aa_job_suite_to_json(const struct aa_job_spec *spec, json_t *job);

#endif

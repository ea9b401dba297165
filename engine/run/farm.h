/* What build farms use (docs/job-format.md "Suites", "Labels", "Baselines"; docs/results-format.md
 * "Suites"): running every case of a suite, its results, labels, baselines and case directories. */
#ifndef AA_FARM_H
#define AA_FARM_H

#include "run/engine.h"

/* ---- labels and baselines ---- */

/* Sets key=value in labels (replacing a value of the same key); the error names path. */
int aa_label_set(struct aa_label *labels, int *count, const char *key, const char *value, const char *path,
		 struct aa_error *err);
/* "KEY=VALUE" (a --label flag, a filter, an item of a baseline). */
int aa_label_parse(const char *text, struct aa_label *labels, int *count, const char *path, struct aa_error *err);

/* A baseline names the job a new job is compared with: a job id, or the latest finished job of the
 * same suite that has every one of the labels ("latest:branch=main"). */
struct aa_baseline {
	char job[16];              /* a job id, or "" */
	bool latest;
	int label_count;
	struct aa_label labels[AA_MAX_LABELS];
};
int aa_baseline_parse(const char *text, struct aa_baseline *out, const char *path, struct aa_error *err);

/* ---- cases ---- */

/* Case i's directory name inside a job directory ("thin-wires_default_160x90"). */
void aa_case_dirname(const struct aa_job_spec *spec, int i, char *out, size_t size);
/* Where case i's images and report go, relative to the job directory: "cases/DIRNAME" for a suite,
 * "" for a job that is not one. */
void aa_case_relpath(const struct aa_job_spec *spec, int i, char *out, size_t size);

/* ---- suite files (engine/run/suite_files.c) ---- */

/* The job file of the suite called name ("smoke"): $AALAB_SUITE_DIR, the source tree's suites/, the
 * installed suites. */
int aa_suite_resolve(const char *name, char *out, size_t size, struct aa_error *err);
/* The names of every suite found there, sorted (free each and the array). */
int aa_suite_list(char ***names, int *count);

/* ---- running a suite ---- */

struct aa_suite_result {
	struct aa_job_spec spec;   /* the whole job */
	int case_count;
	struct aa_job_result *cases[AA_MAX_CASES]; /* each with its case's spec (aa_job_case) */
	char started_at[32];       /* ISO 8601 UTC */
	double wall_seconds;
};
void aa_suite_result_free(struct aa_suite_result *r); /* frees r too */

/* Gives the scene of a case (the daemon's scene cache); NULL from aa_suite_run's caller means each case
 * loads its scene file. */
typedef const struct aa_scene *(*aa_scene_source_fn)(const struct aa_job_spec *case_spec, void *user,
						      struct aa_error *err);

/* Runs every case of the job, one after another, as aa_job_run runs one. Events carry case_index, and
 * PROGRESS counts the units of the whole job. A job that is not a suite runs as its one case. */
int aa_suite_run(struct aa_engine *engine, const struct aa_job_spec *spec, aa_scene_source_fn scenes,
		 void *scene_user, aa_event_fn on_event, void *user, struct aa_suite_result **out,
		 struct aa_error *err);
/* Units of work of the whole job: per case frames x (1 + methods x timing.repeat). */
long aa_suite_total_units(const struct aa_job_spec *spec);

#endif

/* A job spec from and to JSON (docs/job-format.md), its cases and its hash (job_spec.c, job_suite.c). */
#ifndef AA_JOB_SPEC_H
#define AA_JOB_SPEC_H

#include "types/job.h"

/* Fills defaults: scene thin-wires, path default, 640x360, 1 frame, 64 reference samples, methods none and
 * ssaa:16, each timed once. A job parsed from JSON has timing.repeat "auto" instead (aa_timing_auto_repeat). */
void aa_job_spec_defaults(struct aa_job_spec *spec);
/* Parses and validates a job object; every error names its field ("methods[1]", "size"). User methods
 * ("user:file=...") are refused: they need the _files form. */
int aa_job_spec_from_json(const json_t *job, struct aa_job_spec *spec, struct aa_error *err);
/* The same, reading the method files of user methods through files (NULL: refused), and their shaders
 * (docs/user-methods.md). The spec then holds a reference to each user method: aa_job_spec_release
 * drops them; a copy of the spec borrows them, or takes its own with aa_job_spec_retain. */
struct aa_file_source;
int aa_job_spec_from_json_files(const json_t *job, const struct aa_file_source *files, struct aa_job_spec *spec,
				struct aa_error *err);
void aa_job_spec_release(struct aa_job_spec *spec);
/* Whether an item of a job's "methods" names a user method ("user:file=...", {"name": "user", ...}). */
bool aa_job_method_is_user(const json_t *method);
void aa_job_spec_retain(const struct aa_job_spec *spec);
json_t *aa_job_spec_to_json(const struct aa_job_spec *spec);
/* timing.repeat "auto": the fewest repeats that give each method AA_MIN_TIMED_RENDERS timed renders over
 * frames (5 for one frame, 2 for three, 1 from five on). */
int aa_timing_auto_repeat(int frames);
/* Parses "WIDTHxHEIGHT" ("640x360"), each 1..AA_MAX_SIZE; errors have path "size" (the CLI's --size). */
int aa_parse_size(const char *text, int *w, int *h, struct aa_error *err);
/* engine/run/job_suite.c: the parts of a job that make it a suite or name it for a farm. */
/* The number of cases (1 for a job that is not a suite). */
int aa_job_case_count(const struct aa_job_spec *spec);
/* Case i as a job of its own: the single-case fields set from the case, no cases, labels kept. */
void aa_job_case(const struct aa_job_spec *spec, int i, struct aa_job_spec *out);
/* The case's stable id, "SCENE/PATH/WxH" (with "@FIRST" when it starts past frame 0): what pairs cases
 * between two runs. */
void aa_case_id(const struct aa_job_spec *spec, int i, char *out, size_t size);
/* The value of label key, or NULL. */
const char *aa_job_label(const struct aa_job_spec *spec, const char *key);
/* "sha256:HEX" of what decides the numbers (cases, reference, methods, timing), not of names, labels
 * or where images go: equal for two runs of the same job, and for the shards of one job. */
void aa_job_hash(const struct aa_job_spec *spec, char *out, size_t size);
#endif

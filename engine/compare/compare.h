/* Comparing two runs (docs/compare.md): per case and method the change in quality and cost, judged by
 * gates ("psnr < -0.1", "gpu_ms > +10%"). One implementation for `aalab compare` and aalabd's
 * /v1/jobs/ID/compare: both take results.json documents and give the same JSON. */
#ifndef AA_COMPARE_H
#define AA_COMPARE_H

#include <stdbool.h>
#include <stdio.h>

#include <jansson.h>

#include "util/error.h"

enum aa_gate_metric {
	AA_GATE_PSNR, AA_GATE_SSIM, AA_GATE_FLIP, AA_GATE_FLICKER, AA_GATE_GPU_MS, AA_GATE_CPU_MS, AA_GATE_MEMORY,
	AA_GATE_METRIC_COUNT
};

enum aa_gate_op { AA_GATE_LT, AA_GATE_LE, AA_GATE_GT, AA_GATE_GE };

/* "METRIC OP CHANGE[%]": trips when the change from BASE to NEW (NEW - BASE, or relative to BASE in
 * percent with '%') compares true. Cost metrics count only a change outside the runs' spread. */
struct aa_gate {
	enum aa_gate_metric metric;
	enum aa_gate_op op;
	double threshold;
	bool percent;
	char text[64];             /* normalised: "gpu_ms > +10%" */
};

#define AA_MAX_GATES 32

/* Parses one gate; the error's path is `path` (e.g. "--fail-if"). */
int aa_gate_parse(const char *text, struct aa_gate *out, const char *path, struct aa_error *err);
/* The default gate set (docs/compare.md); returns how many were written. */
int aa_gates_default(struct aa_gate *out, int max);
const char *aa_gate_metric_name(enum aa_gate_metric m);

struct aa_compare_options {
	struct aa_gate gates[AA_MAX_GATES];
	int gate_count;            /* 0: the default set */
	bool allow_missing;        /* compare the cases both runs have instead of refusing */
	bool raw_cost;             /* judge times as measured, without the case's machine factor */
	const char *base_source, *new_source; /* shown in the output: a folder, file or job id */
};

/* Compares two results.json documents (a job's or a suite's). Returns the comparison (the JSON of
 * `aalab compare --json`), or NULL with err: AA_ERR_INVALID for a document that is not results.json (the
 * path names "BASE ..." or "NEW ..." and the field) or for runs that do not share their cases. */
json_t *aa_compare_results(const json_t *base, const json_t *new_run, const struct aa_compare_options *opts,
			   struct aa_error *err);
/* 1 when the comparison tripped a gate, 0 when every gate held. */
int aa_compare_tripped(const json_t *comparison);

/* The comparison as a text table, a JUnit XML file (one test case per case x method x gate) and a
 * markdown summary for a merge-request comment. */
void aa_compare_print_table(const json_t *comparison, FILE *out);
int aa_compare_write_junit(const json_t *comparison, FILE *out);
int aa_compare_write_markdown(const json_t *comparison, FILE *out);

#endif

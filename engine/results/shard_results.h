/* Results of shards (docs/farm.md): a shard's results.json names the whole job it is part of, and
 * aa_shard_merge joins the shards' folders into the results of the whole job, as an unsharded run writes
 * them. */
#ifndef AA_SHARD_RESULTS_H
#define AA_SHARD_RESULTS_H

#include <jansson.h>

#include "../job.h"

/* Writes results.json (with "shard": aa_shard_json) and report.html of shard index of count of whole. */
int aa_shard_results_write(const struct aa_job_result *r, const struct aa_job_spec *whole, int index, int count,
			   const char *dir, struct aa_error *err);

/* A results.json document of a job that is not a suite, read back into a result: what its writer
 * (results_json.c) stores per frame and per timed render. Per-frame error-threshold curves are not stored;
 * every frame gets the job's mean curve. The error names the key at fault. */
int aa_results_from_json(const json_t *doc, struct aa_job_result *out, struct aa_error *err);

/* Joins shard folders into one result of the whole job. Refuses (AA_ERR_INVALID, the message naming the
 * folders or the missing frames) folders of another job, duplicated shards and missing ones; a folder
 * without results.json counts as a missing shard. notes receives what the merge could not compute (a
 * border frame's flicker without images), one line each; it may be NULL. */
struct aa_shard_merge {
	struct aa_job_result *result; /* the whole job's, frames in order */
	int shard_count;
	char **dirs;                  /* the folder of shard i, [shard_count] */
};
int aa_shard_merge(const char *const *dirs, int dir_count, struct aa_shard_merge *out, FILE *notes,
		   struct aa_error *err);
/* Links (or copies) every shard's images into dir under the whole job's frame ordinals. */
int aa_shard_merge_images(const struct aa_shard_merge *m, const char *dir, struct aa_error *err);
void aa_shard_merge_free(struct aa_shard_merge *m);

#endif

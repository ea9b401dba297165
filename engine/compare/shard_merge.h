/* Results of shards (docs/farm.md): a shard's results.json names the whole job it is part of, and
 * aa_shard_merge joins the shards' folders into the results of the whole job, as an unsharded run writes
 * them. */
#ifndef AA_SHARD_RESULTS_H
#define AA_SHARD_RESULTS_H

#include <jansson.h>

#include "types/job.h"

struct aa_suite_result;

/* Writes results.json (with "shard": aa_shard_json and each frame's error-threshold curve) and the
 * reports of shard index of count of whole: r holds the shard's one case, or a suite shard's cases. */
int aa_shard_results_write(const struct aa_suite_result *r, const struct aa_job_spec *whole, int index, int count,
			   const char *dir, struct aa_error *err);


/* Joins shard folders into one result of the whole job. Refuses (AA_ERR_INVALID, the message naming the
 * folders or the missing frames) folders of another job, duplicated shards and missing ones; a folder
 * without results.json counts as a missing shard. notes receives what the merge could not compute (a
 * border frame's flicker without images), one line each; it may be NULL. */
struct aa_shard_merge {
	struct aa_suite_result *result; /* the whole job's: its one case with frames in order, or a suite's cases */
	int shard_count;
	char **dirs;                  /* the folder of shard i, [shard_count] */
};
int aa_shard_merge(const char *const *dirs, int dir_count, struct aa_shard_merge *out, FILE *notes,
		   struct aa_error *err);
/* Links (or copies) every shard's images into dir under the whole job's frame ordinals. */
int aa_shard_merge_images(const struct aa_shard_merge *m, const char *dir, struct aa_error *err);
void aa_shard_merge_free(struct aa_shard_merge *m);

#endif

/* Shards of a job (docs/farm.md): a job split into contiguous runs of frames that run anywhere (a Slurm
 * array task, a Kubernetes indexed job, a CI matrix entry), each an ordinary result folder, and merged
 * into the results an unsharded run gives. */
#ifndef AA_SHARD_H
#define AA_SHARD_H

#include <jansson.h>

#include "types/job.h"

#define AA_MAX_SHARDS 10000
/* Default warm-up frames per method with history (aa_method_shard_warmup; docs/farm.md, "Warm-up") */
#define AA_TAA_SHARD_WARMUP 32
#define AA_T2MSAA_SHARD_WARMUP 48
#define AA_ASAA_SHARD_WARMUP 48
#define AA_HISTORY_SHARD_WARMUP 64

/* "I/N": shard I (0-based) of N; errors have path "shard" and say what is valid. */
int aa_shard_parse(const char *text, int *index, int *count, struct aa_error *err);
/* Shard index of count over frames: job ordinals [*begin, *end), contiguous, in order, sizes differing by
 * at most one (the first frames % count shards have one more). */
void aa_shard_range(int frames, int index, int count, int *begin, int *end);
/* Frames a method with history needs before its first scored frame so that its history is that of the
 * unsharded run within the tolerance docs/farm.md states; 0 for methods without history. */
int aa_method_shard_warmup(const struct aa_method_spec *ms);
/* The job's warm-up: shard.warmup when given, else the largest default of its methods. */
int aa_job_shard_warmup(const struct aa_job_spec *spec);
/* Shard index of count of a suite: its whole cases [*begin, *end), contiguous, in order, at least one
 * each, cut where the running cost (frames x pixels) is nearest to index/count of the whole. */
void aa_shard_cases(const struct aa_job_spec *suite, int index, int count, int *begin, int *end);
/* The job shard index of count runs: the frames of aa_shard_range with its warm-up before them (never
 * before the job's first frame: shard 0 starts as the unsharded run does); for a suite, the whole cases
 * of aa_shard_cases (no warm-up: every case starts where it starts in the suite). */
int aa_shard_job(const struct aa_job_spec *whole, int index, int count, struct aa_job_spec *out,
		 struct aa_error *err);
/* results.json's "shard": which shard of which job this folder is. */
json_t *aa_shard_json(const struct aa_job_spec *whole, int index, int count);

#endif

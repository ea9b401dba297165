/* Stored references: a folder of entries, one file per reference frame named by its key (reference_key.h),
 * shared by every process that points at it (the CLI, aalabd, the shards of a farm). Writes are atomic
 * (a file beside, fsync, rename), so writers of one key on several nodes leave one whole entry; reads
 * check the CRC-32 stored with the entry, and an entry that fails any check is removed and reported,
 * never used. The folder is kept under a size by removing the least recently used entries. The format is
 * in docs/reference-cache.md. */
#ifndef AA_REFERENCE_CACHE_H
#define AA_REFERENCE_CACHE_H

#include <stdbool.h>
#include <stdint.h>

#include "util/error.h"

#define AA_REFERENCE_CACHE_DEFAULT_BYTES (4ull << 30)
#define AA_REFERENCE_CACHE_MIN_BYTES (1ull << 20)

/* What a process did with the store. */
struct aa_reference_cache_stats {
	uint64_t hits, misses;         /* entry lookups */
	uint64_t bytes_read, bytes_written;
	uint64_t evictions;            /* entries removed to stay under the size */
	uint64_t discarded;            /* entries that failed their checks, removed */
};

/* A reference frame as stored: the running sums of its renders (linear RGBA32F, what the metrics read
 * once divided by the count), one or two of them. */
#define AA_REFERENCE_ENTRY_PLANES 2
#define AA_REFERENCE_RECIPE_MAX 2048
struct aa_reference_entry {
	int width, height;
	int plane_count;
	int samples[AA_REFERENCE_ENTRY_PLANES]; /* the number of renders each plane sums */
	float *planes[AA_REFERENCE_ENTRY_PLANES];
	double gpu_ms, cpu_ms;         /* what rendering these sums cost */
	char recipe[AA_REFERENCE_RECIPE_MAX]; /* JSON: the job of one frame that renders it again (verify) */
};
void aa_reference_entry_free(struct aa_reference_entry *e);

struct aa_reference_cache;
/* Opens (creating) the folder; max_bytes 0 is the default. An error names the folder. */
int aa_reference_cache_open(const char *dir, uint64_t max_bytes, struct aa_reference_cache **out,
			    struct aa_error *err);
/* Adds this process's counts to the folder's totals (the stats file) and frees c. */
void aa_reference_cache_close(struct aa_reference_cache *c);
const char *aa_reference_cache_dir(const struct aa_reference_cache *c);
uint64_t aa_reference_cache_max_bytes(const struct aa_reference_cache *c);

/* 1: stored and whole (e filled, free it with aa_reference_entry_free); 0: not stored; -1: a stored entry
 * failed a check: it is removed and warning says which and why. */
int aa_reference_cache_get(struct aa_reference_cache *c, const uint8_t key[32], struct aa_reference_entry *e,
			   char *warning, size_t warning_size);
/* Stores e under key (replacing an entry of that key), then removes the least recently used entries while
 * the folder is over its size. */
int aa_reference_cache_put(struct aa_reference_cache *c, const uint8_t key[32], const struct aa_reference_entry *e,
			   struct aa_error *err);
/* This process's counts so far (thread-safe). */
struct aa_reference_cache_stats aa_reference_cache_stats(struct aa_reference_cache *c);

/* The folder as a whole: entries and bytes now, and the counts every process added at close. */
struct aa_reference_cache_usage {
	uint64_t entries, bytes;
	struct aa_reference_cache_stats total;
};
int aa_reference_cache_usage(struct aa_reference_cache *c, struct aa_reference_cache_usage *u, struct aa_error *err);
/* Removes every entry (and the totals); *removed: how many. */
int aa_reference_cache_clear(struct aa_reference_cache *c, uint64_t *removed, struct aa_error *err);
/* The keys of every entry, as hex (malloc'ed array of 65-byte strings), most recently used first. */
int aa_reference_cache_keys(struct aa_reference_cache *c, char (**keys)[65], int *count, struct aa_error *err);
/* Removes least recently used entries until the folder holds at most max_bytes. */
int aa_reference_cache_trim(struct aa_reference_cache *c, uint64_t max_bytes, struct aa_error *err);
/* Removes the temporary files of writers that died (every scan of the folder does, this scans only). */
int aa_reference_cache_remove_stale(struct aa_reference_cache *c, struct aa_error *err);

/* Reads a size setting: a whole number of bytes, or with K, M, G or T (powers of 1024); at least
 * AA_REFERENCE_CACHE_MIN_BYTES. -1 with err naming field. */
int aa_reference_cache_parse_size(const char *field, const char *text, uint64_t *out, struct aa_error *err);

#endif

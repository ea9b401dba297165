/* aalab cache: the store of reference frames that aalab run reads before rendering a reference (stats,
 * clear, verify), and where that store is. */
#include <getopt.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <jansson.h>

#include "client.h"
#include "reference/reference_cache.h"
#include "run/engine.h"
#include "run/job_spec.h"
#include "util/sha256.h"

const char aa_cache_help[] =
	"usage: aalab cache stats|clear|verify [--sample N] [--reference-cache DIR] [--json]\n"
	"\n"
	"The store of reference frames: aalab run looks each frame's reference up by the hash of everything\n"
	"that decides its pixels before rendering it, and stores the ones it renders (docs/reference-cache.md).\n"
	"\n"
	"  stats             entries, bytes, and the hits, misses and evictions of every run so far\n"
	"  clear             remove every entry\n"
	"  verify            render entries again and compare them bit for bit: one that differs means a\n"
	"                    part of what decides the pixels is missing from the key\n"
	"  --sample N        verify N entries chosen at random (default 20; 0: all)\n"
	"  --reference-cache DIR   the store (default $XDG_CACHE_HOME/aalab/references, or\n"
	"                    ~/.cache/aalab/references)\n"
	"  --json            print the figures as JSON\n"
	"\n"
	"Exit status: 0 done (verify: every entry identical), 1 an entry differed or the work failed, 2 bad\n"
	"arguments.\n";

int aa_reference_cache_location(const char *given, char *out, size_t size)
{
	out[0] = 0;
	if (given && strcmp(given, "off") == 0)
		return 0;
	if (given) {
		if (!given[0]) {
			fprintf(stderr, "aalab: --reference-cache: expected a folder or 'off', got an empty value\n");
			return -1;
		}
		if ((size_t)snprintf(out, size, "%s", given) >= size) {
			fprintf(stderr, "aalab: --reference-cache: the folder name is too long\n");
			return -1;
		}
		return 0;
	}
	const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
	/* the XDG rule: a relative $XDG_CACHE_HOME is to be ignored */
	if (xdg && xdg[0] == '/')
		snprintf(out, size, "%s/aalab/references", xdg);
	else if (home && home[0])
		snprintf(out, size, "%s/.cache/aalab/references", home);
	return 0;
}

static int open_store(const char *given, struct aa_reference_cache **c)
{
	char dir[2048];
	struct aa_error err = {0};
	if (aa_reference_cache_location(given, dir, sizeof dir))
		return AA_EXIT_USAGE;
	if (!dir[0]) {
		fprintf(stderr, "aalab cache: no store: --reference-cache is off (and $HOME is not set)\n");
		return AA_EXIT_USAGE;
	}
	if (aa_reference_cache_open(dir, 0, c, &err)) {
		fprintf(stderr, "aalab cache: %s: %s\n", err.path, err.message);
		return AA_EXIT_FAILED;
	}
	return AA_EXIT_OK;
}

static int stats(struct aa_reference_cache *c, bool json)
{
	struct aa_reference_cache_usage u;
	struct aa_error err = {0};
	if (aa_reference_cache_usage(c, &u, &err)) {
		fprintf(stderr, "aalab cache: %s\n", err.message);
		return AA_EXIT_FAILED;
	}
	const uint64_t lookups = u.total.hits + u.total.misses;
	if (json) {
		json_t *j = json_pack("{s:s, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:I, s:o}", "folder",
				      aa_reference_cache_dir(c), "entries", (json_int_t)u.entries, "bytes", (json_int_t)u.bytes,
				      "hits", (json_int_t)u.total.hits, "misses", (json_int_t)u.total.misses, "bytes_read",
				      (json_int_t)u.total.bytes_read, "bytes_written", (json_int_t)u.total.bytes_written,
				      "evictions", (json_int_t)u.total.evictions, "discarded",
				      (json_int_t)u.total.discarded, "size_limit", (json_int_t)aa_reference_cache_max_bytes(c),
				      "hit_rate", lookups ? json_real((double)u.total.hits / (double)lookups) : json_null());
		json_dumpf(j, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
		json_decref(j);
		return AA_EXIT_OK;
	}
	printf("folder     %s\nentries    %" PRIu64 "\nbytes      %" PRIu64 " (%.1f MiB)\n", aa_reference_cache_dir(c),
	       u.entries, u.bytes, u.bytes / 1048576.0);
	printf("hits       %" PRIu64 "\nmisses     %" PRIu64 "\n", u.total.hits, u.total.misses);
	if (lookups)
		printf("hit rate   %.1f%%\n", 100.0 * (double)u.total.hits / (double)lookups);
	else
		printf("hit rate   -\n");
	printf("read       %.1f MiB\nwritten    %.1f MiB\nevictions  %" PRIu64 "\ndiscarded  %" PRIu64
	       " (failed their check)\n", u.total.bytes_read / 1048576.0, u.total.bytes_written / 1048576.0,
	       u.total.evictions, u.total.discarded);
	return AA_EXIT_OK;
}

/* The job of one frame that renders the entry again, from its recipe; -1 when it cannot (not a file). */
static int recipe_job(const char *recipe, struct aa_job_spec *spec, char *why, size_t why_size)
{
	json_error_t je;
	json_t *r = json_loads(recipe, 0, &je);
	const char *scene = json_string_value(json_object_get(r, "scene"));
	int rc = -1;
	if (!r || !scene || !scene[0]) {
		snprintf(why, why_size, "%s", r ? "its scene is not a file" : "its recipe is not JSON");
		goto out;
	}
	json_t *job = json_pack("{s:s, s:O, s:O, s:O, s:I, s:[s], s:b, s:{s:O}}", "scene", scene, "path",
				json_object_get(r, "path"), "width", json_object_get(r, "width"), "height",
				json_object_get(r, "height"), "first_frame", json_integer_value(json_object_get(r, "frame")),
				"methods", "none", "keep_frames", 0, "reference", "samples",
				json_is_true(json_object_get(r, "auto")) ? json_string("auto") : json_object_get(r, "samples"));
	struct aa_error err = {0};
	if (!job || aa_job_spec_from_json(job, spec, &err)) {
		snprintf(why, why_size, "%.200s%s%.300s", err.path, err.path[0] ? ": " : "", job ? err.message : "a bad recipe");
		json_decref(job);
		goto out;
	}
	json_decref(job);
	if (spec->reference_auto) { /* every level up to the cap, each compared with its entry */
		spec->reference_samples = (int)json_integer_value(json_object_get(r, "samples"));
		spec->reference_target_psnr = 80.0;
	}
	spec->reference_verify = true;
	rc = 0;
out:
	json_decref(r);
	return rc;
}

static int verify(struct aa_reference_cache *c, int sample, bool json)
{
	char (*keys)[65];
	int n;
	struct aa_error err = {0};
	if (aa_reference_cache_keys(c, &keys, &n, &err)) {
		fprintf(stderr, "aalab cache: %s\n", err.message);
		return AA_EXIT_FAILED;
	}
	/* a random sample: Fisher-Yates over the first `sample` places */
	srand((unsigned)time(NULL) ^ (unsigned)getpid());
	const int count = sample > 0 && sample < n ? sample : n;
	for (int i = 0; i < count; i++) {
		const int j = i + rand() % (n - i);
		char t[65];
		memcpy(t, keys[i], 65);
		memcpy(keys[i], keys[j], 65);
		memcpy(keys[j], t, 65);
	}
	struct aa_engine *engine = NULL;
	struct aa_engine_options eo = {0};
	if (count > 0 && (aa_engine_create(&eo, &engine, &err) ||
			  aa_engine_set_reference_cache(engine, aa_reference_cache_dir(c), aa_reference_cache_max_bytes(c),
							&err))) {
		fprintf(stderr, "aalab cache: %s\n", err.message);
		aa_engine_destroy(engine);
		free(keys);
		return AA_EXIT_FAILED;
	}
	int identical = 0, differed = 0, skipped = 0;
	json_t *list = json_array();
	for (int i = 0; i < count; i++) {
		uint8_t key[32];
		for (int b = 0; b < 32; b++)
			sscanf(keys[i] + 2 * b, "%2hhx", &key[b]);
		struct aa_reference_entry e;
		char why[512] = "";
		const char *outcome = "skipped";
		struct aa_job_spec spec;
		struct aa_job_result *result = NULL;
		if (aa_reference_cache_get(c, key, &e, why, sizeof why) <= 0) {
			if (!why[0])
				snprintf(why, sizeof why, "removed meanwhile");
		} else if (recipe_job(e.recipe, &spec, why, sizeof why) == 0) {
			if (aa_job_run(engine, &spec, NULL, NULL, &result, &err)) {
				snprintf(why, sizeof why, "%.500s", err.message);
			} else {
				const struct aa_reference_cache_result *v = &result->reference.cache;
				/* an entry whose inputs changed since (the scene's files) has another key now */
				const bool same_key = v->verified && strcmp(v->verified_key, keys[i]) == 0;
				outcome = !same_key ? "skipped" : v->mismatched ? "differs" : "identical";
				if (!same_key)
					snprintf(why, sizeof why, "what decides its pixels changed since it was stored "
						 "(scene files, code, device or driver: another key now)");
				else if (v->mismatched)
					snprintf(why, sizeof why, "%s", v->warning_count ? v->warnings[0] : "");
				aa_job_result_free(result);
				free(result);
			}
			aa_job_spec_release(&spec);
		}
		aa_reference_entry_free(&e);
		identical += strcmp(outcome, "identical") == 0;
		differed += strcmp(outcome, "differs") == 0;
		skipped += strcmp(outcome, "skipped") == 0;
		json_array_append_new(list, json_pack("{s:s, s:s, s:s}", "key", keys[i], "outcome", outcome, "why", why));
		if (!json)
			printf("%.16s  %-9s %s\n", keys[i], outcome, why);
	}
	aa_engine_destroy(engine);
	free(keys);
	if (json) {
		json_t *j = json_pack("{s:i, s:i, s:i, s:i, s:o}", "checked", count, "identical", identical, "differed",
				      differed, "skipped", skipped, "entries", list);
		json_dumpf(j, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
		json_decref(j);
	} else {
		json_decref(list);
		printf("%d of %d identical", identical, count);
		if (differed)
			printf(", %d differ", differed);
		if (skipped)
			printf(", %d skipped", skipped);
		printf("\n");
	}
	return differed ? AA_EXIT_FAILED : AA_EXIT_OK;
}

int cmd_cache(int argc, char **argv)
{
	enum { OPT_SAMPLE = 256, OPT_DIR, OPT_JSON, OPT_HELP };
	static const struct option opts[] = {
		{"sample", required_argument, 0, OPT_SAMPLE}, {"reference-cache", required_argument, 0, OPT_DIR},
		{"json", no_argument, 0, OPT_JSON}, {"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0},
	};
	const char *dir = NULL;
	bool json = false;
	int sample = 20, c;
	bool sample_given = false;
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
		switch (c) {
		case OPT_SAMPLE: {
			char *end;
			const long v = strtol(optarg, &end, 10);
			if (end == optarg || *end || v < 0 || v > 1000000) {
				fprintf(stderr, "aalab cache: --sample: expected a number of entries from 0 to 1000000, got "
					"'%s'\n", optarg);
				return AA_EXIT_USAGE;
			}
			sample = (int)v;
			sample_given = true;
			break;
		}
		case OPT_DIR: dir = optarg; break;
		case OPT_JSON: json = true; break;
		case OPT_HELP: fputs(aa_cache_help, stdout); return AA_EXIT_OK;
		default: fputs(aa_cache_help, stderr); return AA_EXIT_USAGE;
		}
	}
	const char *what = optind < argc ? argv[optind] : NULL;
	if (!what || optind + 1 < argc ||
	    (strcmp(what, "stats") != 0 && strcmp(what, "clear") != 0 && strcmp(what, "verify") != 0)) {
		fprintf(stderr, what ? "aalab cache: expected stats, clear or verify, got '%s'\n" :
			"aalab cache: expected stats, clear or verify%s\n", what ? what : "");
		return AA_EXIT_USAGE;
	}
	if (sample_given && strcmp(what, "verify") != 0) {
		fprintf(stderr, "aalab cache: --sample goes with verify only\n");
		return AA_EXIT_USAGE;
	}
	struct aa_reference_cache *store;
	int status = open_store(dir, &store);
	if (status != AA_EXIT_OK)
		return status;
	if (strcmp(what, "stats") == 0) {
		status = stats(store, json);
	} else if (strcmp(what, "verify") == 0) {
		status = verify(store, sample, json);
	} else {
		uint64_t removed;
		struct aa_error err = {0};
		if (aa_reference_cache_clear(store, &removed, &err)) {
			fprintf(stderr, "aalab cache: %s\n", err.message);
			status = AA_EXIT_FAILED;
		} else if (json) {
			printf("{\"removed\": %" PRIu64 "}\n", removed);
		} else {
			printf("removed %" PRIu64 " entries from %s\n", removed, aa_reference_cache_dir(store));
		}
	}
	aa_reference_cache_close(store);
	return status;
}

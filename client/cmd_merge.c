/* aalab merge: joins the result folders of a job's shards into the results of the whole job, as an
 * unsharded run writes them (docs/farm.md, "Merging"). */
#include <getopt.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "run/engine.h"
#include "client.h"
#include "out_dir.h"
#include "results/results.h"
#include "run/farm.h"
#include "compare/shard_merge.h"
#include "report/report.h"

const char aa_merge_help[] =
	"usage: aalab merge --out DIR SHARD_DIR... [--force] [--json] [--quiet]\n"
	"\n"
	"Joins the result folders that 'aalab run JOB --shard I/N' wrote for every shard of one job into\n"
	"DIR: results.json, report.html and the images, as an unsharded run writes them. Summaries (PSNR from\n"
	"the mean MSE, timing medians, best and worst frames, flicker, also across shard borders) are\n"
	"computed over the merged frames. The shards must be of one job (the same job hash, shard count and\n"
	"warm-up), each given once; a folder without results.json is a shard that did not finish, and merge\n"
	"names the frames that are missing.\n"
	"\n"
	"  --out DIR               where the merged results go (required; refused if DIR holds something\n"
	"                          that is not an aalab result; an earlier result only with --force)\n"
	"  --force                 replace the earlier aalab result in DIR\n"
	"  --json                  print the merged results.json instead of the tables\n"
	"  --quiet                 no notes on standard error (border frames without images)\n"
	"\n"
	"Exit status: 0 merged, 1 writing failed, 2 bad arguments, missing, duplicated or foreign shards.\n";

int cmd_merge(int argc, char **argv)
{
	enum { OPT_OUT = 256, OPT_FORCE, OPT_JSON, OPT_QUIET, OPT_HELP };
	static const struct option opts[] = {
		{"out", required_argument, 0, OPT_OUT}, {"force", no_argument, 0, OPT_FORCE},
		{"json", no_argument, 0, OPT_JSON}, {"quiet", no_argument, 0, OPT_QUIET},
		{"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0},
	};
	const char *out_dir = NULL;
	bool force = false, print_json = false, quiet = false;
	int c;
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
		switch (c) {
		case OPT_OUT: out_dir = optarg; break;
		case OPT_FORCE: force = true; break;
		case OPT_JSON: print_json = true; break;
		case OPT_QUIET: quiet = true; break;
		case OPT_HELP: fputs(aa_merge_help, stdout); return AA_EXIT_OK;
		default: fputs(aa_merge_help, stderr); return AA_EXIT_USAGE;
		}
	}
	if (!out_dir || optind >= argc) {
		fprintf(stderr, "aalab merge: %s\n%s", !out_dir ? "--out DIR is required" : "give the shards' folders",
			aa_merge_help);
		return AA_EXIT_USAGE;
	}
	struct aa_shard_merge m;
	struct aa_error err = {0};
	FILE *notes = quiet ? NULL : stderr;
	if (aa_shard_merge((const char *const *)argv + optind, argc - optind, &m, notes, &err)) {
		fprintf(stderr, "aalab merge: %s%s%s\n", err.path, err.path[0] ? ": " : "", err.message);
		return err.code == AA_ERR_INVALID ? AA_EXIT_USAGE : AA_EXIT_FAILED;
	}
	struct aa_out_dir od = {0};
	char cerr[1200];
	int status = AA_EXIT_FAILED;
	if (aa_out_dir_prepare(&od, out_dir, force, cerr, sizeof cerr)) {
		fprintf(stderr, "aalab merge: %s\n", cerr);
		aa_shard_merge_free(&m);
		return AA_EXIT_USAGE;
	}
	if (aa_shard_merge_images(&m, od.work, &err) || aa_suite_results_write(m.result, od.work, &err)) {
		fprintf(stderr, "aalab merge: %s\n", err.message);
		status = err.code == AA_ERR_INVALID ? AA_EXIT_USAGE : AA_EXIT_FAILED;
	} else if (aa_out_dir_commit(&od, cerr, sizeof cerr)) {
		fprintf(stderr, "aalab merge: %s\n", cerr);
	} else {
		status = AA_EXIT_OK;
	}
	if (status != AA_EXIT_OK) {
		aa_out_dir_discard(&od);
	} else {
		json_t *j = aa_suite_results_to_json(m.result);
		if (print_json) {
			json_dumpf(j, stdout, JSON_INDENT(2));
			fputc('\n', stdout);
		} else {
			aa_print_results(j, stdout);
			printf("\nmerged %d shards\nresults: %s/results.json\nreport:  %s/report.html\n", m.shard_count,
			       od.final, od.final);
		}
		json_decref(j);
	}
	aa_shard_merge_free(&m);
	return status;
}

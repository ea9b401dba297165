/* aalab run: builds a job from a job file and/or flags, runs it in this process, prints the
 * cost-vs-accuracy table and writes results.json, images and report.html. */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "run/engine.h"
#include "client.h"
#include "run/farm.h"
#include "methods/user_method.h"
#include "out_dir.h"
#include "results/results.h"
#include "compare/shard_merge.h"
#include "run/shard.h"
#include "report/report.h"
#include "run/job_spec.h"

const char aa_run_help[] =
	"usage: aalab run [JOB.json|SUITE] [options]\n"
	"\n"
	"Renders every frame of a camera path with each AA method and with a supersampled reference, and\n"
	"compares them. Flags override the fields of JOB.json (docs/job-format.md). A job file may be a suite,\n"
	"a matrix of scenes, paths and sizes; a suite is also found by name ('aalab suites' lists them).\n"
	"Prints the verdict first (the methods on the cost-quality front, ties, what beats each other method\n"
	"and by how much, and the front of each method family a sweep measured), then the table, then the\n"
	"warnings, each with what to do.\n"
	"\n"
	AA_JOB_OPTIONS_HELP
	"  --out DIR               where results go (default results/SCENE-YYYYMMDD-HHMMSS); written to a\n"
	"                          folder beside it and renamed when complete. A non-empty DIR that is not\n"
	"                          an aalab result is refused; an earlier aalab result only with --force\n"
	"  --force                 replace the earlier aalab result in --out DIR\n"
	"  --shard I/N             render shard I (0 to N-1) of N: a contiguous run of the frames, after the\n"
	"                          warm-up frames its temporal methods need (job field shard.warmup), or of\n"
	"                          a suite's whole cases; in this process. 'aalab merge' joins the shards\n"
	"                          (docs/farm.md; default: the whole job)\n"
	"  --device SEL            Vulkan device index or name substring (default $AALAB_DEVICE or the first)\n"
	"  --reference-cache DIR|off  the store of reference frames: each frame's reference is looked up by\n"
	"                          the hash of what decides its pixels and rendered only when it is not\n"
	"                          stored (default $XDG_CACHE_HOME/aalab/references or ~/.cache/aalab/\n"
	"                          references; off: render every reference, store none). Runs in this process\n"
	"  --reference-cache-size SIZE  keep the store under SIZE, least recently used out first (default\n"
	"                          4G; K, M, G, T)\n"
	"  --explain-key           print each frame's reference key and whether the store has it, the first\n"
	"                          frame's part by part (scene and file bytes, camera, time, size, samples,\n"
	"                          pattern, alpha rule, LOD bias, shaders, code, device, driver), on stderr\n"
	"  --no-images             write results.json and report.html but no per-frame PNGs\n"
	"  --no-viewer             keep the PNGs but leave report.html's image viewer out, and with it\n"
	"                          viewer/, the frames again as scripts (~1.3x their disk; job field viewer)\n"
	"  --exr                   also write every frame's linear colour as float EXR, exr/METHOD/NNNN.exr\n"
	"                          (for oiiotool, idiff, tev; job field exr_frames)\n"
	"  --debug-targets         after every frame read back each method's intermediate images (scene\n"
	"                          targets, histories, edge and blend targets) and count their NaN/Inf\n"
	"                          texels: results.json frames[].intermediates, the finite verdict (job\n"
	"                          field debug_targets; slower)\n"
	"  --json                  print results.json to standard output instead of the tables\n"
	"  --quiet                 no progress (a bar with an ETA on a terminal; otherwise a line on stderr\n"
	"                          each time another tenth of the renders is done)\n"
	"  --local                 run in this process even when aalabd is running\n"
	AA_CONNECT_OPTIONS_HELP
	"                          (without --connect and --local, a daemon on the default socket is used\n"
	"                          when one answers)\n"
	"\n"
	"Exit status: 0 done, 1 the job failed, 2 bad arguments or job (the message names the field).\n";

struct run_output {
	const char *dir;
	const struct aa_job_spec *spec;
	bool images;
	bool quiet;
	bool tty; /* stderr is a terminal: a progress bar, otherwise a line per tenth */
	volatile int frames_written; /* what Ctrl-C reports as kept */
	int failed_writes;
	struct aa_error write_err;
};

static int on_event(const struct aa_event *ev, void *user)
{
	struct run_output *o = user;
	if (o->images && aa_suite_write_event_images(o->dir, o->spec, ev, &o->write_err))
		o->failed_writes++;
	else if (o->images && (ev->type == AA_EVENT_REFERENCE_FRAME || ev->type == AA_EVENT_METHOD_FRAME))
		o->frames_written++;
	if (ev->type == AA_EVENT_REFERENCE_KEY && ev->text) {
		/* the first frame of each case part by part, the others a line each */
		const char *nl = strchr(ev->text, '\n');
		if (ev->frame_ordinal == 0 || !nl)
			fputs(ev->text, stderr);
		else
			fprintf(stderr, "%.*s\n", (int)(nl - ev->text), ev->text);
	}
	if (ev->type == AA_EVENT_PROGRESS && !o->quiet) {
		if (o->tty)
			aa_progress_update(ev->done, ev->total, "rendering");
		else
			aa_progress_line("run", ev->done, ev->total, "rendering");
	}
	/* a failed image write stops the job: carrying on would lose data silently */
	return o->failed_writes > 0;
}

static int make_default_dir(const char *scene, char *out, size_t size)
{
	time_t now = time(NULL);
	struct tm tm;
	localtime_r(&now, &tm);
	char stamp[32];
	strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
	const char *base = strrchr(scene, '/');
	base = base ? base + 1 : scene;
	char name[64];
	snprintf(name, sizeof name, "%.63s", base);
	char *dot = strstr(name, ".json");
	if (dot)
		*dot = 0;
	for (int n = 0; n < 100; n++) {
		if (n == 0)
			snprintf(out, size, "results/%s-%s", name, stamp);
		else
			snprintf(out, size, "results/%s-%s-%d", name, stamp, n);
		struct stat st;
		if (stat(out, &st) != 0)
			return 0; /* never write into an earlier run's directory */
	}
	return -1;
}

int cmd_run(int argc, char **argv)
{
	enum { OPT_OUT = 256, OPT_DEVICE, OPT_NO_IMAGES, OPT_JSON, OPT_QUIET, OPT_LOCAL, OPT_CONNECT, OPT_HELP, OPT_FORCE, OPT_SHARD, OPT_EXR,
	       OPT_NO_VIEWER, OPT_DEBUG_TARGETS, OPT_REFERENCE_CACHE, OPT_REFERENCE_CACHE_SIZE, OPT_EXPLAIN_KEY,
	       OPT_TOKEN_FILE };
	static const struct option opts[] = {
		AA_JOB_LONG_OPTIONS, {"out", required_argument, 0, OPT_OUT}, {"connect", required_argument, 0, OPT_CONNECT},
		{"device", required_argument, 0, OPT_DEVICE}, {"no-images", no_argument, 0, OPT_NO_IMAGES},
		{"json", no_argument, 0, OPT_JSON}, {"quiet", no_argument, 0, OPT_QUIET},
		{"local", no_argument, 0, OPT_LOCAL}, {"help", no_argument, 0, OPT_HELP},
		{"force", no_argument, 0, OPT_FORCE}, {"shard", required_argument, 0, OPT_SHARD},
		{"exr", no_argument, 0, OPT_EXR}, {"no-viewer", no_argument, 0, OPT_NO_VIEWER},
		{"debug-targets", no_argument, 0, OPT_DEBUG_TARGETS},
		{"reference-cache", required_argument, 0, OPT_REFERENCE_CACHE},
		{"reference-cache-size", required_argument, 0, OPT_REFERENCE_CACHE_SIZE},
		{"explain-key", no_argument, 0, OPT_EXPLAIN_KEY}, {"token-file", required_argument, 0, OPT_TOKEN_FILE},
		{0, 0, 0, 0},
	};
	json_t *overrides = json_object();
	const char *out_dir = NULL, *device = NULL, *connect = NULL, *shard_text = NULL, *cache_given = NULL;
	uint64_t cache_bytes = 0;
	bool explain_key = false;
	bool images = true, print_json = false, quiet = false, local = false, force = false, exr = false;
	struct aa_out_dir od = {0};
	struct aa_job_spec spec;
	bool spec_parsed = false;
	int status = AA_EXIT_USAGE, c, idx;
	bool verdicts_failed = false; /* the run succeeded and its results are kept, but it exits 1 */
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, &idx)) != -1) {
		switch (c) {
		case AA_OPT_JOB:
			if (aa_job_flag("run", opts[idx].name, optarg, overrides))
				goto out;
			break;
		case OPT_OUT: out_dir = optarg; break;
		case OPT_DEVICE: device = optarg; break;
		case OPT_NO_IMAGES: images = false; break;
		case OPT_JSON: print_json = true; break;
		case OPT_QUIET: quiet = true; break;
		case OPT_LOCAL: local = true; break;
		case OPT_CONNECT: connect = optarg; break;
		case OPT_TOKEN_FILE: aa_conn_set_token_file(optarg); break;
		case OPT_FORCE: force = true; break;
		case OPT_SHARD: shard_text = optarg; break;
		case OPT_EXR: exr = true; break;
		case OPT_NO_VIEWER: json_object_set_new(overrides, "viewer", json_false()); break;
		case OPT_DEBUG_TARGETS: json_object_set_new(overrides, "debug_targets", json_true()); break;
		case OPT_REFERENCE_CACHE: cache_given = optarg; break;
		case OPT_REFERENCE_CACHE_SIZE: {
			struct aa_error e = {0};
			if (aa_reference_cache_parse_size("--reference-cache-size", optarg, &cache_bytes, &e)) {
				fprintf(stderr, "aalab run: %s: %s\n", e.path, e.message);
				goto out;
			}
			break;
		}
		case OPT_EXPLAIN_KEY: explain_key = true; break;
		case OPT_HELP: fputs(aa_run_help, stdout); status = AA_EXIT_OK; goto out;
		default: fputs(aa_run_help, stderr); goto out;
		}
	}
	if (!images) /* the job field, so that results.json and the report name no image either */
		json_object_set_new(overrides, "keep_frames", json_false());
	if (exr) /* the job field: aalabd writes them as this process would (exr/METHOD/NNNN.exr) */
		json_object_set_new(overrides, "exr_frames", json_true());
	if (exr && !images) {
		fprintf(stderr, "aalab run: --exr writes images and cannot go with --no-images\n");
		goto out;
	}
	json_t *job = aa_job_build("run", argc, argv, optind, overrides);
	if (!job)
		goto out;
	struct aa_error err = {0};
	/* user methods read their method and shader files from here (docs/user-methods.md) */
	int rc = aa_job_spec_from_json_files(job, &aa_file_source_disk, &spec, &err);
	if (rc) {
		aa_print_error("run", &err);
		json_decref(job);
		goto out;
	}
	spec_parsed = true;
	bool user_methods = false;
	for (int i = 0; i < spec.method_count; i++)
		user_methods |= aa_method_is_user(spec.methods[i].method);
	/* A shard is the job's frames [begin, end) after its warm-up; its results.json names the whole job */
	struct aa_job_spec whole = spec;
	int shard_index = 0, shard_count = 0;
	if (shard_text && (aa_shard_parse(shard_text, &shard_index, &shard_count, &err) ||
			   aa_shard_job(&whole, shard_index, shard_count, &spec, &err))) {
		fprintf(stderr, "aalab run: --%s: %s\n", err.path, err.message);
		json_decref(job);
		goto out;
	}
	if ((cache_given || cache_bytes || explain_key) && connect) {
		fprintf(stderr, "aalab run: --reference-cache, --reference-cache-size and --explain-key are of a run in "
			"this process; aalabd has its own store (its reference-cache setting)\n");
		json_decref(job);
		goto out;
	}
	char cache_dir[2048];
	if (aa_reference_cache_location(cache_given, cache_dir, sizeof cache_dir)) {
		json_decref(job);
		goto out;
	}
	spec.explain_key = explain_key;
	if (shard_text && connect) {
		fprintf(stderr, "aalab run: --shard runs in this process; leave out --connect\n");
		json_decref(job);
		goto out;
	}
	/* A running aalabd does the work when one answers (or --connect names one). --local and --device run
	 * here, and so does a scene given as a file path: the daemon takes scene names only. User methods run
	 * here unless --connect names a daemon: their files are on this machine, and a daemon runs them only
	 * when its configuration allows (aalabd(8)). */
	struct aa_conn *conn = NULL;
	char cerr[1200];
	bool remote = !local && !device && !shard_text && !cache_given && !cache_bytes && !explain_key &&
		      (!user_methods || connect);
	for (int i = 0; i < aa_job_case_count(&spec); i++) {
		struct aa_job_spec one;
		aa_job_case(&spec, i, &one);
		remote = remote && !strchr(one.scene, '/');
	}
	if (remote && aa_conn_open(connect, &conn, cerr, sizeof cerr) && connect) {
		fprintf(stderr, "aalab run: %s\n", cerr);
		json_decref(job);
		status = AA_EXIT_FAILED;
		goto out;
	}
	if (!conn && spec.baseline[0]) {
		fprintf(stderr, "aalab run: baseline: names a job of aalabd, and this job runs in this process; "
			"compare the results afterwards with 'aalab compare BASE DIR'\n");
		json_decref(job);
		goto out;
	}
	char dir[1024];
	if (out_dir)
		snprintf(dir, sizeof dir, "%s", out_dir);
	else if (make_default_dir(!spec.is_suite ? spec.scene : spec.suite[0] ? spec.suite : "suite", dir, sizeof dir)) {
		fprintf(stderr, "aalab run: cannot choose an output directory under results/\n");
		aa_conn_close(conn);
		json_decref(job);
		goto out;
	}
	if (aa_out_dir_prepare(&od, dir, force, cerr, sizeof cerr)) {
		fprintf(stderr, "aalab run: %s\n", cerr);
		aa_conn_close(conn);
		json_decref(job);
		goto out;
	}
	snprintf(dir, sizeof dir, "%s", od.final);
	if (conn) {
		aa_out_dir_on_interrupt(&od, true, NULL, 0);
		status = aa_run_remote(conn, job, od.work, od.final, images, print_json, quiet);
		if (status == AA_EXIT_OK && aa_out_dir_commit(&od, cerr, sizeof cerr)) {
			fprintf(stderr, "aalab run: %s\n", cerr);
			status = AA_EXIT_FAILED;
		}
		aa_conn_close(conn);
		json_decref(job);
		goto out;
	}
	json_decref(job);
	/* a shader that does not compile is bad input: said before the scene is loaded and the device opened */
	for (int i = 0; i < spec.method_count; i++) {
		struct aa_user_method *um = (struct aa_user_method *)aa_user_method_of(spec.methods[i].method);
		if (um && aa_user_method_compile(um, &err)) {
			fprintf(stderr, "aalab run: methods[%d]: %s\n", i, err.message);
			status = err.code == AA_ERR_INVALID ? AA_EXIT_USAGE : AA_EXIT_FAILED;
			goto out;
		}
	}

	struct aa_engine *engine;
	struct aa_engine_options eo = {.device = device};
	if (aa_engine_create(&eo, &engine, &err)) {
		fprintf(stderr, "aalab run: %s\n", err.message);
		status = err.path[0] ? AA_EXIT_USAGE : AA_EXIT_FAILED;
		goto out;
	}
	/* the store: a folder given that cannot be used is an error; the default one only a warning */
	if (cache_dir[0] && aa_engine_set_reference_cache(engine, cache_dir, cache_bytes, &err)) {
		if (cache_given) {
			fprintf(stderr, "aalab run: --reference-cache: %s\n", err.message);
			aa_engine_destroy(engine);
			goto out;
		}
		fprintf(stderr, "aalab run: warning: the reference store %s cannot be used (%s): every reference is "
			"rendered\n", cache_dir, err.message);
	}
	struct run_output ro = {.dir = od.work, .spec = &spec, .images = images && spec.keep_frames,
				 .quiet = quiet, .tty = isatty(STDERR_FILENO)};
	int frames_total = 0; /* images of every case: each frame's reference and methods */
	for (int i = 0; i < aa_job_case_count(&spec); i++) {
		struct aa_job_spec one;
		aa_job_case(&spec, i, &one);
		frames_total += one.frames * (1 + one.method_count);
	}
	aa_out_dir_on_interrupt(&od, false, ro.images ? &ro.frames_written : NULL, frames_total);
	struct aa_suite_result *result = NULL;
	rc = aa_suite_run(engine, &spec, NULL, NULL, on_event, &ro, &result, &err);
	if (!quiet)
		aa_progress_finish();
	int validation_errors = aa_engine_validation_errors(engine);
	aa_engine_destroy(engine);
	if (rc) {
		if (ro.failed_writes)
			fprintf(stderr, "aalab run: writing images failed: %s\n", ro.write_err.message);
		else
			aa_print_error("run", &err);
		status = err.code == AA_ERR_INVALID || err.code == AA_ERR_NOT_FOUND || err.code == AA_ERR_LIMIT
				 ? AA_EXIT_USAGE : AA_EXIT_FAILED;
		goto out;
	}
	status = AA_EXIT_OK;
	for (int i = 0; i < result->case_count; i++) /* e.g. an entry that failed its check, rendered again */
		for (int w = 0; w < result->cases[i]->reference.cache.warning_count; w++)
			fprintf(stderr, "aalab run: warning: %s\n", result->cases[i]->reference.cache.warnings[w]);
	if (shard_text ? aa_shard_results_write(result, &whole, shard_index, shard_count, od.work, &err)
		       : aa_suite_results_write(result, od.work, &err)) {
		fprintf(stderr, "aalab run: %s\n", err.message);
		status = AA_EXIT_FAILED;
	} else if (aa_out_dir_commit(&od, cerr, sizeof cerr)) {
		fprintf(stderr, "aalab run: %s\n", cerr);
		status = AA_EXIT_FAILED;
	}
	if (print_json) {
		json_t *j = aa_suite_results_to_json(result);
		json_dumpf(j, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
		json_decref(j);
	} else {
		/* what the results folder says, printed as a run through aalabd or 'aalab get' prints it */
		json_t *j = aa_suite_results_to_json(result);
		aa_print_results(j, stdout);
		/* a verdict the docs say must hold that fails is a failed run (the results are kept) */
		const int failed = aa_print_verdict_table(j, stdout);
		json_decref(j);
		printf("\nresults: %s/results.json\nreport:  %s/report.html\n", dir, dir);
		if (failed) {
			fflush(stdout);
			fprintf(stderr, "aalab run: %d verdict%s failed (docs/hard-cases.md)\n", failed,
				failed == 1 ? "" : "s");
			verdicts_failed = true;
		}
	}
	if (validation_errors) {
		fprintf(stderr, "aalab run: %d Vulkan validation errors\n", validation_errors);
		status = AA_EXIT_FAILED;
	}
	aa_suite_result_free(result);
out:
	if (status != AA_EXIT_OK)
		aa_out_dir_discard(&od); /* half a result is no result; DIR stays as it was */
	if (spec_parsed)
		aa_job_spec_release(&spec);
	json_decref(overrides);
	return status == AA_EXIT_OK && verdicts_failed ? AA_EXIT_FAILED : status;
}

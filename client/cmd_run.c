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

#include "aa.h"
#include "client.h"
#include "results/results.h"

static const char run_help[] =
	"usage: aalab run [JOB.json] [options]\n"
	"\n"
	"Renders every frame of a camera path with each AA method and with a supersampled reference, and\n"
	"compares them. Flags override the fields of JOB.json (docs/job-format.md).\n"
	"\n"
	"  --scene NAME|FILE       scene name (see 'aalab scenes') or scene file (default thin-wires)\n"
	"  --path NAME             camera path: default, static, or one the scene defines (default default)\n"
	"  --methods LIST          comma-separated methods, e.g. none,ssaa:16 (see 'aalab methods')\n"
	"  --frames N              frames to render (default 1)\n"
	"  --first-frame N         frame index on the path to start at (default 0)\n"
	"  --size WxH              image size (default 640x360)\n"
	"  --reference-samples N   samples of the accumulated reference, even (default 64)\n"
	"  --out DIR               where results go (default results/SCENE-YYYYMMDD-HHMMSS)\n"
	"  --device SEL            Vulkan device index or name substring (default $AALAB_DEVICE or the first)\n"
	"  --no-images             write results.json and report.html but no per-frame PNGs\n"
	"  --json                  print results.json to standard output instead of the table\n"
	"  --quiet                 no progress display\n"
	"  --local                 run in this process (the only mode until the daemon exists)\n"
	"\n"
	"Exit status: 0 done, 1 the job failed, 2 bad arguments or job (the message names the field).\n";

struct run_output {
	const char *dir;
	bool images;
	bool quiet;
	int failed_writes;
	struct aa_error write_err;
};

static int on_event(const struct aa_event *ev, void *user)
{
	struct run_output *o = user;
	char rel[256];
	switch (ev->type) {
	case AA_EVENT_REFERENCE_FRAME:
		if (o->images) {
			aa_results_frame_relpath("frames", "reference", ev->frame_ordinal, rel, sizeof rel);
			if (aa_results_write_image(o->dir, rel, ev->image, &o->write_err))
				o->failed_writes++;
		}
		break;
	case AA_EVENT_METHOD_FRAME:
		if (o->images) {
			const char *label = ev->result->methods[ev->method_index].label;
			aa_results_frame_relpath("frames", label, ev->frame_ordinal, rel, sizeof rel);
			if (aa_results_write_image(o->dir, rel, ev->image, &o->write_err))
				o->failed_writes++;
			aa_results_frame_relpath("diff", label, ev->frame_ordinal, rel, sizeof rel);
			if (aa_results_write_image(o->dir, rel, ev->diff, &o->write_err))
				o->failed_writes++;
		}
		break;
	case AA_EVENT_PROGRESS:
		if (!o->quiet)
			aa_progress_update(ev->done, ev->total, "rendering");
		break;
	default:
		break;
	}
	/* a failed image write stops the job: carrying on would lose data silently */
	return o->failed_writes > 0;
}

static int parse_int(const char *flag, const char *text, json_int_t *out)
{
	char *end;
	errno = 0;
	long long v = strtoll(text, &end, 10);
	if (errno || end == text || *end) {
		fprintf(stderr, "aalab run: %s: expected an integer, got '%s'\n", flag, text);
		return -1;
	}
	*out = v;
	return 0;
}

static json_t *load_job_file(const char *path)
{
	json_error_t jerr;
	json_t *job = json_load_file(path, JSON_REJECT_DUPLICATES, &jerr);
	if (!job) {
		fprintf(stderr, "aalab run: %s:%d:%d: %s\n", path, jerr.line, jerr.column, jerr.text);
		return NULL;
	}
	if (!json_is_object(job)) {
		fprintf(stderr, "aalab run: %s: a job file holds a JSON object\n", path);
		json_decref(job);
		return NULL;
	}
	return job;
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

static int mkdir_p(const char *dir)
{
	char tmp[1024];
	snprintf(tmp, sizeof tmp, "%s", dir);
	for (char *p = tmp + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			if (mkdir(tmp, 0777) != 0 && errno != EEXIST)
				return -1;
			*p = '/';
		}
	return mkdir(tmp, 0777) != 0 && errno != EEXIST ? -1 : 0;
}

int cmd_run(int argc, char **argv)
{
	enum { OPT_SCENE = 256, OPT_PATH, OPT_METHODS, OPT_FRAMES, OPT_FIRST, OPT_SIZE, OPT_REF, OPT_OUT,
	       OPT_DEVICE, OPT_NO_IMAGES, OPT_JSON, OPT_QUIET, OPT_LOCAL, OPT_HELP };
	static const struct option opts[] = {
		{"scene", required_argument, 0, OPT_SCENE}, {"path", required_argument, 0, OPT_PATH},
		{"methods", required_argument, 0, OPT_METHODS}, {"frames", required_argument, 0, OPT_FRAMES},
		{"first-frame", required_argument, 0, OPT_FIRST}, {"size", required_argument, 0, OPT_SIZE},
		{"reference-samples", required_argument, 0, OPT_REF}, {"out", required_argument, 0, OPT_OUT},
		{"device", required_argument, 0, OPT_DEVICE}, {"no-images", no_argument, 0, OPT_NO_IMAGES},
		{"json", no_argument, 0, OPT_JSON}, {"quiet", no_argument, 0, OPT_QUIET},
		{"local", no_argument, 0, OPT_LOCAL}, {"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0},
	};
	json_t *overrides = json_object();
	const char *out_dir = NULL, *device = NULL;
	bool images = true, print_json = false, quiet = !isatty(STDERR_FILENO);
	int status = AA_EXIT_USAGE, c;
	json_int_t n;
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
		switch (c) {
		case OPT_SCENE: json_object_set_new(overrides, "scene", json_string(optarg)); break;
		case OPT_PATH: json_object_set_new(overrides, "path", json_string(optarg)); break;
		case OPT_SIZE: json_object_set_new(overrides, "size", json_string(optarg)); break;
		case OPT_METHODS: {
			char **list;
			int count;
			if (aa_split_methods(optarg, &list, &count)) {
				fprintf(stderr, "aalab run: methods: cannot parse '%s'\n", optarg);
				goto out;
			}
			json_t *arr = json_array();
			for (int i = 0; i < count; i++)
				json_array_append_new(arr, json_string(list[i]));
			aa_free_strings(list, count);
			json_object_set_new(overrides, "methods", arr);
			break;
		}
		case OPT_FRAMES:
			if (parse_int("frames", optarg, &n))
				goto out;
			json_object_set_new(overrides, "frames", json_integer(n));
			break;
		case OPT_FIRST:
			if (parse_int("first_frame", optarg, &n))
				goto out;
			json_object_set_new(overrides, "first_frame", json_integer(n));
			break;
		case OPT_REF:
			if (parse_int("reference.samples", optarg, &n))
				goto out;
			json_object_set_new(overrides, "reference", json_pack("{sI}", "samples", n));
			break;
		case OPT_OUT: out_dir = optarg; break;
		case OPT_DEVICE: device = optarg; break;
		case OPT_NO_IMAGES: images = false; break;
		case OPT_JSON: print_json = true; break;
		case OPT_QUIET: quiet = true; break;
		case OPT_LOCAL: break;
		case OPT_HELP: fputs(run_help, stdout); status = AA_EXIT_OK; goto out;
		default: fputs(run_help, stderr); goto out;
		}
	}
	json_t *job = NULL;
	if (optind < argc) {
		if (optind + 1 < argc) {
			fprintf(stderr, "aalab run: one job file at most, got '%s' and '%s'\n", argv[optind],
				argv[optind + 1]);
			goto out;
		}
		job = load_job_file(argv[optind]);
		if (!job)
			goto out;
	} else {
		job = json_object();
	}
	json_object_update(job, overrides);

	struct aa_job_spec spec;
	struct aa_error err = {0};
	int rc = aa_job_spec_from_json(job, &spec, &err);
	json_decref(job);
	if (rc) {
		fprintf(stderr, "aalab run: %s%s%s\n", err.path, err.path[0] ? ": " : "", err.message);
		goto out;
	}
	char dir[1024];
	if (out_dir)
		snprintf(dir, sizeof dir, "%s", out_dir);
	else if (make_default_dir(spec.scene, dir, sizeof dir)) {
		fprintf(stderr, "aalab run: cannot choose an output directory under results/\n");
		goto out;
	}
	if (mkdir_p(dir)) {
		fprintf(stderr, "aalab run: out: cannot create '%s': %s\n", dir, strerror(errno));
		goto out;
	}

	struct aa_engine *engine;
	struct aa_engine_options eo = {.device = device};
	if (aa_engine_create(&eo, &engine, &err)) {
		fprintf(stderr, "aalab run: %s\n", err.message);
		status = err.path[0] ? AA_EXIT_USAGE : AA_EXIT_FAILED;
		goto out;
	}
	struct run_output ro = {.dir = dir, .images = images && spec.keep_frames, .quiet = quiet};
	struct aa_job_result *result = NULL;
	rc = aa_job_run(engine, &spec, on_event, &ro, &result, &err);
	if (!quiet)
		aa_progress_finish();
	int validation_errors = aa_engine_validation_errors(engine);
	aa_engine_destroy(engine);
	if (rc) {
		if (ro.failed_writes)
			fprintf(stderr, "aalab run: writing images failed: %s\n", ro.write_err.message);
		else
			fprintf(stderr, "aalab run: %s%s%s\n", err.path, err.path[0] ? ": " : "", err.message);
		status = err.code == AA_ERR_INVALID || err.code == AA_ERR_NOT_FOUND || err.code == AA_ERR_LIMIT
				 ? AA_EXIT_USAGE : AA_EXIT_FAILED;
		goto out;
	}
	status = AA_EXIT_OK;
	if (aa_results_write_json(result, dir, &err) || aa_report_write_html(result, dir, &err)) {
		fprintf(stderr, "aalab run: %s\n", err.message);
		status = AA_EXIT_FAILED;
	}
	if (print_json) {
		json_t *j = aa_results_to_json(result);
		json_dumpf(j, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
		json_decref(j);
	} else {
		aa_print_table(result, stdout);
		printf("\nresults: %s/results.json\nreport:  %s/report.html\n", dir, dir);
	}
	if (validation_errors) {
		fprintf(stderr, "aalab run: %d Vulkan validation errors\n", validation_errors);
		status = AA_EXIT_FAILED;
	}
	aa_job_result_free(result);
	free(result);
out:
	json_decref(overrides);
	return status;
}

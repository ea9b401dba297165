/* Summaries (percentiles, sequence PSNR), results.json contents and atomic writing, the job directory
 * layout and report.html, on hand-made job results. */
#include <dirent.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "results/results.h"
#include "methods/methods.h"
#include "report/report.h"
#include "run/job_spec.h"

/* Methods local to the test, so the tables do not depend on which methods the registry lists. */
static const int preset_allowed[] = { 10, 12, 15, 20, 23, 25, 26, 29, 39, 0 };
static const char *const quality_choices[] = { "low", "medium", "high", "ultra", NULL };
static const struct aa_param_def fake_params[] = {
	{ .name = "preset", .type = AA_PARAM_INT, .def = 39, .min = 10, .max = 39, .allowed = preset_allowed },
	{ .name = "subpix", .type = AA_PARAM_FLOAT, .def = 0.75, .min = 0, .max = 1 },
	{ .name = "quality", .type = AA_PARAM_ENUM, .def = 2, .choices = quality_choices },
	{ .name = "auth", .type = AA_PARAM_BOOL, .def = 0, .min = 0, .max = 1 },
};
static const struct aa_method fake_fxaa = { .name = "fxaa", .params = fake_params, .param_count = 4,
					    .main_param = "preset" };
static const struct aa_method fake_plain = { .name = "plain" };

#define PEAK2 (255.0 * 255.0)

static void fill_frame(struct aa_frame_result *f, int frame, double mse, bool identical)
{
	f->frame = frame;
	f->pass_count = 2;
	snprintf(f->passes[0].name, sizeof f->passes[0].name, "scene");
	f->passes[0].gpu_ms = 2.0 + frame;
	snprintf(f->passes[1].name, sizeof f->passes[1].name, "resolve");
	f->passes[1].gpu_ms = 0.5;
	f->gpu_ms = f->passes[0].gpu_ms + f->passes[1].gpu_ms;
	f->cpu_ms = 3.0 + frame;
	struct aa_metrics *m = &f->metrics;
	m->identical = identical;
	m->mse = identical ? 0 : mse;
	m->rmsd = sqrt(m->mse);
	m->psnr = identical ? NAN : 10 * log10(PEAK2 / mse);
	m->snr = identical ? NAN : 20;
	m->ssim = identical ? 1.0 : 0.9;
	m->max_abs = identical ? 0 : 40 + frame;
	for (int t = 0; t < AA_THRESHOLD_COUNT; t++)
		m->exceed[t] = identical ? 0 : fmax(0, 0.4 * pow(0.7, t)) * (t < 60);
}

/* Three frames (10, 11, 12); method 0 has MSE 1, 3 and one identical frame; method 1 is identical
 * everywhere and has a label that must be escaped in HTML. */
static struct aa_job_result *make_result(bool keep_frames)
{
	struct aa_job_result *r = calloc(1, sizeof *r);
	aa_job_spec_defaults(&r->spec);
	r->spec.frames = 3;
	r->spec.first_frame = 10;
	r->spec.keep_frames = keep_frames;
	snprintf(r->spec.name, sizeof r->spec.name, "unit & <test>");
	snprintf(r->scene_name, sizeof r->scene_name, "thin-wires");
	snprintf(r->scene_file, sizeof r->scene_file, "/usr/share/aalab/scenes/thin-wires.json");
	r->scene_triangles = 2048;
	snprintf(r->device_name, sizeof r->device_name, "llvmpipe (LLVM 15.0.6, 256 bits)");
	snprintf(r->driver_info, sizeof r->driver_info, "Mesa 22.3.6");
	r->timestamp_period_ns = 1.0;
	r->wall_seconds = 1.25;
	snprintf(r->started_at, sizeof r->started_at, "2024-01-02T03:04:05Z");
	r->plan_count = 2;
	snprintf(r->plan[0].pass, sizeof r->plan[0].pass, "scene");
	snprintf(r->plan[0].reason, sizeof r->plan[0].reason, "always");
	r->plan[0].ran = true;
	snprintf(r->plan[1].pass, sizeof r->plan[1].pass, "shadow");
	snprintf(r->plan[1].reason, sizeof r->plan[1].reason, "no light casts shadows");

	r->reference.samples = 64;
	snprintf(r->reference.pattern, sizeof r->reference.pattern, "owen-sobol");
	r->reference.memory_bytes = 3686400;
	r->reference.frame_count = 3;
	r->reference.frames = calloc(3, sizeof *r->reference.frames);
	for (int i = 0; i < 3; i++) {
		struct aa_reference_frame *f = &r->reference.frames[i];
		f->frame = 10 + i;
		f->gpu_ms = 190 + i;
		f->cpu_ms = 200 + i;
		f->convergence_mse = 0.5 * (i + 1); /* 0.5, 1, 1.5: mean 1 */
		f->convergence_psnr = 10 * log10(PEAK2 / f->convergence_mse);
	}

	r->method_count = 2;
	struct aa_method_result *m = &r->methods[0];
	m->method = &fake_fxaa;
	aa_method_defaults(&fake_fxaa, &m->params);
	m->params.v[0] = 12;
	m->params.v[2] = 3;
	m->params.v[3] = 1;
	aa_method_label(&fake_fxaa, &m->params, m->label, sizeof m->label);
	snprintf(m->path_taken, sizeof m->path_taken, "full-screen pass");
	m->memory_count = 1;
	snprintf(m->memory[0].name, sizeof m->memory[0].name, "luma");
	m->memory[0].bytes = m->memory_bytes = 921600;
	m->frame_count = 3;
	m->frames = calloc(3, sizeof *m->frames);
	fill_frame(&m->frames[0], 10, 1.0, false);
	fill_frame(&m->frames[1], 11, 3.0, false);
	fill_frame(&m->frames[2], 12, 0.0, true);

	m = &r->methods[1];
	m->method = &fake_plain;
	snprintf(m->label, sizeof m->label, "<script>alert(1)</script>");
	m->frame_count = 3;
	m->frames = calloc(3, sizeof *m->frames);
	for (int i = 0; i < 3; i++)
		fill_frame(&m->frames[i], 10 + i, 0.0, true);
	return r;
}

static void free_result(struct aa_job_result *r)
{
	aa_job_result_free(r);
	free(r);
}

/* Walks "a.b.0.c" through objects and arrays. */
static json_t *at(json_t *root, const char *path)
{
	char buf[256];
	snprintf(buf, sizeof buf, "%s", path);
	json_t *v = root;
	for (char *save = NULL, *tok = strtok_r(buf, ".", &save); v && tok; tok = strtok_r(NULL, ".", &save))
		v = json_is_array(v) ? json_array_get(v, strtoul(tok, NULL, 10)) : json_object_get(v, tok);
	if (!v)
		fail_msg("results.json lacks %s", path);
	return v;
}

static void assert_all_finite(const json_t *v)
{
	const char *key;
	json_t *child;
	size_t i;
	switch (json_typeof(v)) {
	case JSON_REAL:
		assert_true(isfinite(json_real_value(v)));
		break;
	case JSON_OBJECT:
		json_object_foreach((json_t *)v, key, child) assert_all_finite(child);
		break;
	case JSON_ARRAY:
		json_array_foreach(v, i, child) assert_all_finite(child);
		break;
	default:
		break;
	}
}

static void test_percentile(void **state)
{
	(void)state;
	double odd[] = { 3, 1, 2 }, even[] = { 4, 1, 3, 2 }, ten[10];
	for (int i = 0; i < 10; i++)
		ten[i] = 10 - i;
	assert_true(aa_percentile(odd, 3, 50) == 2);
	assert_true(odd[0] == 3 && odd[1] == 1); /* not sorted in place */
	assert_true(aa_percentile(even, 4, 50) == 2.5);
	assert_true(fabs(aa_percentile(ten, 10, 90) - 9.1) < 1e-12);
	assert_true(aa_percentile(ten, 10, 0) == 1);
	assert_true(aa_percentile(ten, 10, 100) == 10);
	assert_true(aa_percentile(ten, 10, 250) == 10);
	assert_true(aa_percentile(odd, 1, 90) == 3);
	assert_true(isnan(aa_percentile(odd, 0, 50)));
	assert_true(isnan(aa_percentile(NULL, 3, 50)));
	double gaps[] = { NAN, 5, INFINITY, 1 };
	assert_true(aa_percentile(gaps, 4, 50) == 3); /* non-finite values are skipped */
	double none[] = { NAN, NAN };
	assert_true(isnan(aa_percentile(none, 2, 50)));
}

/* Timing distributions: median, p10, p90, min, mean and n, non-finite values skipped; the summary and
 * each pass take them from every timed render (repeats included), not from the scored frames alone. */
static void test_timing_stats(void **state)
{
	(void)state;
	double ten[] = { 10, 1, 9, 2, 8, 3, 7, 4, 6, 5, NAN };
	struct aa_timing_stats t;
	aa_timing_stats_of(ten, 11, &t);
	assert_int_equal(t.n, 10);
	assert_true(t.median == 5.5 && t.min == 1 && t.mean == 5.5);
	assert_true(fabs(t.p10 - 1.9) < 1e-12 && fabs(t.p90 - 9.1) < 1e-12);
	aa_timing_stats_of(NULL, 0, &t);
	assert_true(t.n == 0 && isnan(t.median) && isnan(t.min) && isnan(t.p10));

	struct aa_frame_result frames[2] = {
		{ .frame = 0, .pass_count = 2, .passes = { { "scene", 10 }, { "resolve", 2 } }, .gpu_ms = 12, .cpu_ms = 13 },
		{ .frame = 1, .pass_count = 2, .passes = { { "scene", 11 }, { "resolve", 3 } }, .gpu_ms = 14, .cpu_ms = 15 },
	};
	/* 2 frames x 3 repeats; the second frame's last repeat ran other passes: it keeps its total only */
	struct aa_timed_render timed[6] = {
		{ 0, 0, 0, 12, 13, 2, { 10, 2 } }, { 0, 1, 1, 20, 21, 2, { 18, 2 } }, { 0, 2, 2, 30, 31, 2, { 27, 3 } },
		{ 1, 0, 1, 14, 15, 2, { 11, 3 } }, { 1, 1, 2, 16, 17, 2, { 12, 4 } }, { 1, 2, 0, 40, 41, 0, { 0 } },
	};
	struct aa_method_result m = { .frame_count = 2, .frames = frames, .timed_count = 6, .timed = timed };
	struct aa_method_summary s;
	aa_method_summarize(&m, &s);
	assert_int_equal(s.gpu_ms.n, 6);
	assert_true(s.gpu_ms.median == 18 && s.gpu_ms.min == 12 && s.gpu_ms_median == 18);
	assert_true(fabs(s.gpu_ms.p90 - 35) < 1e-12 && fabs(s.gpu_ms.p10 - 13) < 1e-12);
	assert_true(s.cpu_ms.median == 19 && s.cpu_ms.n == 6);
	aa_pass_timing_stats(&m, "scene", &t);
	assert_int_equal(t.n, 5);
	assert_true(t.median == 12 && t.min == 10);
	aa_pass_timing_stats(&m, "resolve", &t);
	assert_true(t.n == 5 && t.median == 3);
	aa_pass_timing_stats(&m, "missing", &t);
	assert_true(t.n == 0 && isnan(t.median));
}

static void test_summarize(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(true);
	struct aa_method_summary s;
	aa_method_summarize(&r->methods[0], &s);
	/* PSNR of the mean MSE (4/3), not the mean of per-frame PSNRs (one of which is infinite). */
	assert_true(fabs(s.mse_mean - 4.0 / 3.0) < 1e-12);
	assert_true(fabs(s.psnr_mean - 10 * log10(PEAK2 * 3 / 4)) < 1e-9);
	assert_false(s.psnr_identical);
	assert_true(s.gpu_ms_median == 13.5 && s.cpu_ms_median == 14);
	assert_true(fabs(s.gpu_ms_mean - 13.5) < 1e-12);
	assert_true(fabs(s.gpu_ms_p90 - 14.3) < 1e-12);
	assert_true(fabs(s.ssim_mean - (0.9 + 0.9 + 1.0) / 3) < 1e-12);
	assert_int_equal(s.best_frame, 12); /* the identical frame counts as best */
	assert_true(isnan(s.best_psnr));
	assert_int_equal(s.worst_frame, 11);
	assert_true(fabs(s.worst_psnr - 10 * log10(PEAK2 / 3)) < 1e-9);

	aa_method_summarize(&r->methods[1], &s);
	assert_true(s.psnr_identical);
	assert_true(isnan(s.psnr_mean));
	assert_true(s.mse_mean == 0);
	assert_int_equal(s.best_frame, 10);

	/* No frames: NAN everywhere, no frame. */
	struct aa_method_result empty = { .frame_count = 0 };
	aa_method_summarize(&empty, &s);
	assert_true(isnan(s.gpu_ms_median) && isnan(s.psnr_mean) && !s.psnr_identical);
	assert_int_equal(s.best_frame, -1);
	free_result(r);
}

static void test_to_json(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(true);
	json_t *j = aa_results_to_json(r);
	assert_non_null(j);
	static const char *const keys[] = {
		"version", "job.scene", "job.methods", "scene.name", "scene.file", "scene.triangles", "device.name",
		"device.driver", "device.timestamp_period_ns", "size.width", "size.height", "frames", "passes.0.pass",
		"passes.0.reason", "passes.0.ran", "reference.samples", "reference.pattern", "reference.memory_bytes",
		"reference.gpu_ms.median", "reference.gpu_ms.p90", "reference.convergence_psnr",
		"reference.convergence_identical", "reference.per_frame.2.frame", "reference.per_frame.2.gpu_ms",
		"reference.per_frame.2.convergence_psnr", "methods.0.name", "methods.0.label", "methods.0.params",
		"methods.0.path_taken", "methods.0.gpu_ms.median", "methods.0.gpu_ms.p90", "methods.0.gpu_ms.mean",
		"methods.0.cpu_ms.median", "methods.0.memory_bytes", "methods.0.memory.0.name",
		"methods.0.memory.0.bytes", "methods.0.passes.1.name", "methods.0.passes.1.gpu_ms",
		"methods.0.metrics.psnr.mean", "methods.0.metrics.psnr.identical", "methods.0.metrics.psnr.per_frame",
		"methods.0.metrics.psnr.best.frame", "methods.0.metrics.psnr.best.value",
		"methods.0.metrics.psnr.worst.frame", "methods.0.metrics.psnr.worst.value", "methods.0.metrics.mse.mean",
		"methods.0.metrics.rmsd.mean", "methods.0.metrics.snr.mean", "methods.0.metrics.ssim.mean",
		"methods.0.metrics.ssim.per_frame", "methods.0.metrics.max_abs.max",
		"methods.0.metrics.error_threshold_curve.thresholds", "methods.0.metrics.error_threshold_curve.share",
		"methods.0.frames.1.frame", "methods.0.frames.1.gpu_ms", "methods.0.frames.1.cpu_ms",
		"methods.0.frames.1.passes", "methods.0.frames.1.psnr", "methods.0.frames.1.ssim",
		"methods.0.frames.1.mse", "methods.0.frames.1.nonfinite", "methods.0.frames.1.image",
		"methods.0.frames.1.diff", "reference.per_frame.0.nonfinite",
	};
	for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
		at(j, keys[i]);
	assert_all_finite(j);

	/* Typed parameter values. */
	assert_true(json_is_integer(at(j, "methods.0.params.preset")));
	assert_int_equal(json_integer_value(at(j, "methods.0.params.preset")), 12);
	assert_true(json_real_value(at(j, "methods.0.params.subpix")) == 0.75);
	assert_string_equal(json_string_value(at(j, "methods.0.params.quality")), "ultra");
	assert_true(json_is_true(at(j, "methods.0.params.auth")));
	assert_string_equal(json_string_value(at(j, "methods.0.name")), "fxaa");
	assert_string_equal(json_string_value(at(j, "methods.0.label")), "fxaa:12,quality=ultra,auth=true");

	/* Mean PSNR from the mean MSE; the identical frame is null + identical, and the best. */
	assert_true(fabs(json_real_value(at(j, "methods.0.metrics.psnr.mean")) - 10 * log10(PEAK2 * 3 / 4)) < 1e-9);
	assert_true(json_is_false(at(j, "methods.0.metrics.psnr.identical")));
	assert_true(json_is_null(at(j, "methods.0.metrics.psnr.per_frame.2")));
	assert_true(json_is_null(at(j, "methods.0.frames.2.psnr")));
	assert_true(json_is_true(at(j, "methods.0.frames.2.identical")));
	assert_int_equal(json_integer_value(at(j, "methods.0.metrics.psnr.best.frame")), 12);
	assert_true(json_is_null(at(j, "methods.0.metrics.psnr.best.value")));
	assert_true(json_is_true(at(j, "methods.0.metrics.psnr.best.identical")));
	assert_int_equal(json_integer_value(at(j, "methods.0.metrics.psnr.worst.frame")), 11);
	assert_true(fabs(json_real_value(at(j, "methods.0.metrics.rmsd.mean")) - sqrt(4.0 / 3)) < 1e-12);
	assert_true(json_real_value(at(j, "methods.0.metrics.max_abs.max")) == 51);
	assert_int_equal(json_array_size(at(j, "methods.0.metrics.error_threshold_curve.share")), AA_THRESHOLD_COUNT);
	assert_true(fabs(json_real_value(at(j, "methods.0.metrics.error_threshold_curve.share.0")) - 0.8 / 3) < 1e-12);
	assert_true(json_real_value(at(j, "methods.0.passes.0.gpu_ms")) == 13); /* median of 12, 13, 14 */
	assert_string_equal(json_string_value(at(j, "methods.0.frames.1.image")),
			    "frames/fxaa_12_quality-ultra_auth-true/0001.png");
	assert_string_equal(json_string_value(at(j, "methods.0.frames.1.diff")),
			    "diff/fxaa_12_quality-ultra_auth-true/0001.png");
	assert_string_equal(json_string_value(at(j, "reference.per_frame.1.image")), "frames/reference/0001.png");

	/* All identical: null + identical everywhere, never Infinity. */
	assert_true(json_is_null(at(j, "methods.1.metrics.psnr.mean")));
	assert_true(json_is_true(at(j, "methods.1.metrics.psnr.identical")));
	assert_true(json_is_null(at(j, "methods.1.metrics.snr.mean")));
	assert_true(json_is_null(at(j, "methods.1.metrics.psnr.worst.value")));
	assert_true(json_is_true(at(j, "methods.1.metrics.psnr.worst.identical")));
	assert_string_equal(json_string_value(at(j, "methods.1.name")), "plain");

	/* Reference convergence from the mean MSE (1.0). */
	assert_true(fabs(json_real_value(at(j, "reference.convergence_psnr")) - 10 * log10(PEAK2)) < 1e-9);
	assert_true(json_is_false(at(j, "reference.convergence_identical")));
	assert_true(json_real_value(at(j, "reference.gpu_ms.median")) == 191);

	char *text = json_dumps(j, 0);
	assert_null(strstr(text, "nan"));
	assert_null(strstr(text, "NaN"));
	assert_null(strstr(text, "Infinity"));
	free(text);
	json_decref(j);

	/* Identical reference, no frames kept, NaN timings: still no non-finite number. */
	for (int i = 0; i < 3; i++) {
		r->reference.frames[i].convergence_identical = true;
		r->reference.frames[i].convergence_mse = 0;
		r->reference.frames[i].convergence_psnr = NAN;
		r->methods[0].frames[i].gpu_ms = NAN;
		r->methods[0].frames[i].metrics.ssim = INFINITY;
	}
	r->spec.keep_frames = false;
	r->timestamp_period_ns = NAN;
	j = aa_results_to_json(r);
	assert_non_null(j);
	assert_all_finite(j);
	assert_true(json_is_null(at(j, "reference.convergence_psnr")));
	assert_true(json_is_true(at(j, "reference.convergence_identical")));
	assert_true(json_is_true(at(j, "reference.per_frame.0.convergence_identical")));
	assert_true(json_is_null(at(j, "methods.0.gpu_ms.median")));
	assert_true(json_is_null(at(j, "methods.0.frames.0.image")));
	assert_true(json_is_null(at(j, "device.timestamp_period_ns")));
	json_decref(j);
	free_result(r);
}

static char *make_tmpdir(void)
{
	char *dir = strdup("/tmp/aalab-test-results-XXXXXX");
	assert_non_null(mkdtemp(dir));
	return dir;
}

static void remove_tree(const char *path)
{
	struct stat st;
	if (lstat(path, &st) < 0)
		return;
	if (S_ISDIR(st.st_mode)) {
		DIR *d = opendir(path);
		struct dirent *e;
		while (d && (e = readdir(d))) {
			if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
				continue;
			char sub[4096];
			snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
			remove_tree(sub);
		}
		if (d)
			closedir(d);
		rmdir(path);
	} else {
		unlink(path);
	}
}

static int count_entries(const char *dir)
{
	int n = 0;
	DIR *d = opendir(dir);
	for (struct dirent *e; d && (e = readdir(d));)
		n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
	if (d)
		closedir(d);
	return n;
}

static char *read_all(const char *path)
{
	FILE *f = fopen(path, "rb");
	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	const long n = ftell(f);
	rewind(f);
	char *buf = malloc((size_t)n + 1);
	assert_int_equal(fread(buf, 1, (size_t)n, f), (size_t)n);
	buf[n] = '\0';
	fclose(f);
	return buf;
}

static void test_write_json(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(true);
	char *dir = make_tmpdir(), path[512];
	struct aa_error err = { 0 };
	snprintf(path, sizeof path, "%s/results.json", dir);
	assert_int_equal(aa_results_write_json(r, dir, &err), 0);
	struct stat first, second;
	assert_int_equal(stat(path, &first), 0);
	assert_int_equal(first.st_mode & 0777, 0644);

	/* Writing again replaces the file by rename (a new inode), never rewriting it in place, and leaves no
	 * temp file behind. */
	r->methods[0].frames[0].metrics.mse = 2.0;
	assert_int_equal(aa_results_write_json(r, dir, &err), 0);
	assert_int_equal(stat(path, &second), 0);
	assert_true(first.st_ino != second.st_ino);
	assert_int_equal(count_entries(dir), 1);

	/* a text file: it ends with a newline */
	FILE *f = fopen(path, "rb");
	assert_non_null(f);
	assert_int_equal(fseek(f, -1, SEEK_END), 0);
	assert_int_equal(fgetc(f), '\n');
	fclose(f);

	json_error_t jerr;
	json_t *j = json_load_file(path, 0, &jerr);
	assert_non_null(j);
	assert_int_equal(json_integer_value(at(j, "version")), 1);
	assert_true(json_real_value(at(j, "methods.0.frames.0.mse")) == 2.0);
	assert_all_finite(j);
	json_decref(j);

	/* A directory that does not exist: an IO error naming it, nothing written. */
	char missing[600];
	snprintf(missing, sizeof missing, "%s/no/such/dir", dir);
	assert_int_equal(aa_results_write_json(r, missing, &err), -1);
	assert_int_equal(err.code, AA_ERR_IO);
	assert_non_null(strstr(err.message, missing));
	assert_int_equal(count_entries(dir), 1);

	remove_tree(dir);
	free(dir);
	free_result(r);
}

static void test_output_dir(void **state)
{
	(void)state;
	char out[256];
	aa_label_dirname("ssaa:samples=16", out, sizeof out);
	assert_string_equal(out, "ssaa_samples-16");
	aa_label_dirname("fxaa:preset=12,subpix=0.5", out, sizeof out);
	assert_string_equal(out, "fxaa_preset-12_subpix-0.5");
	aa_label_dirname("a/../b c", out, sizeof out);
	assert_string_equal(out, "a_.._b_c");
	aa_label_dirname("..", out, sizeof out);
	assert_string_equal(out, "_");
	aa_label_dirname("", out, sizeof out);
	assert_string_equal(out, "_");
	aa_results_frame_relpath("frames", "reference", 3, out, sizeof out);
	assert_string_equal(out, "frames/reference/0003.png");
	aa_results_frame_relpath("diff", "ssaa:samples=4", 12, out, sizeof out);
	assert_string_equal(out, "diff/ssaa_samples-4/0012.png");

	char *dir = make_tmpdir(), path[512];
	struct aa_error err = { 0 };
	uint8_t pixels[2 * 2 * 4] = { 0 };
	const struct aa_image_rgba8 img = { .width = 2, .height = 2, .pixels = pixels };
	aa_results_frame_relpath("frames", "ssaa:samples=4", 0, out, sizeof out);
	assert_int_equal(aa_results_write_image(dir, out, &img, &err), 0);
	snprintf(path, sizeof path, "%s/%s", dir, out);
	assert_int_equal(access(path, R_OK), 0);
	assert_int_equal(aa_results_write_image(dir, "../escape.png", &img, &err), -1);
	assert_int_equal(err.code, AA_ERR_INVALID);
	assert_int_equal(aa_results_write_image(dir, "/abs.png", &img, &err), -1);
	remove_tree(dir);
	free(dir);
}

/* True if text holds "nan" or "inf" as a word of its own (as printf writes them), not inside
 * "luminance" or "infinite". */
static bool has_nonfinite_text(const char *text)
{
	static const char *const words[] = { "nan", "inf" };
	for (size_t w = 0; w < 2; w++)
		for (const char *p = text; (p = strstr(p, words[w])); p++) {
			const bool letter_before = p > text && ((p[-1] | 32) >= 'a' && (p[-1] | 32) <= 'z');
			const bool letter_after = (p[3] | 32) >= 'a' && (p[3] | 32) <= 'z';
			if (!letter_before && !letter_after)
				return true;
		}
	return false;
}

static void test_report_html(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(true);
	char *dir = make_tmpdir(), path[512];
	struct aa_error err = { 0 };
	assert_int_equal(aa_report_write_html(r, dir, &err), 0);
	snprintf(path, sizeof path, "%s/report.html", dir);
	char *html = read_all(path);
	assert_non_null(strstr(html, "<!DOCTYPE html>"));
	/* Scatter, GPU time by pass, threshold curves and (3 frames) PSNR per frame. */
	int svgs = 0;
	for (const char *p = html; (p = strstr(p, "<svg")); p++)
		svgs++;
	assert_int_equal(svgs, 4);
	/* The hostile label is text, never markup: escaped in HTML, \u003c in the viewer's JSON; the only
	 * scripts are the viewer's data and code, inline (test_report_viewer.c tests them). */
	assert_null(strstr(html, "<script>alert"));
	assert_null(strstr(html, "<script src"));
	assert_non_null(strstr(html, "&lt;script&gt;alert(1)&lt;/script&gt;"));
	assert_non_null(strstr(html, "\\u003cscript>alert(1)\\u003c/script>"));
	assert_non_null(strstr(html, "unit &amp; &lt;test&gt;"));
	assert_non_null(strstr(html, ">identical<"));
	/* The viewer names its methods' image folders; nothing comes from elsewhere. */
	assert_non_null(strstr(html, "\"dir\":\"fxaa_12_quality-ultra_auth-true\""));
	assert_non_null(strstr(html, "<section id=\"viewer\""));
	assert_null(strstr(html, "http://example"));
	assert_null(strstr(html, "src=\"http"));
	assert_null(strstr(html, "href=\"http"));
	/* No non-finite number reached a coordinate or a cell. */
	assert_false(has_nonfinite_text(html));
	assert_int_equal(count_entries(dir), 2); /* report.html and viewer/ (one script per frame) */
	free(html);

	/* One frame, no kept frames, no methods' data: still a page, and no per-frame chart. */
	r->spec.frames = 1;
	r->spec.keep_frames = false;
	r->methods[0].frame_count = 1;
	r->methods[1].frame_count = 0;
	assert_int_equal(aa_report_write_html(r, dir, &err), 0);
	html = read_all(path);
	assert_null(strstr(html, "<img"));
	assert_non_null(strstr(html, "\"images\":false"));
	assert_false(has_nonfinite_text(html));
	free(html);

	remove_tree(dir);
	free(dir);
	free_result(r);
}

static void test_result_free(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(true);
	aa_job_result_free(r);
	assert_null(r->methods[0].frames);
	assert_null(r->reference.frames);
	assert_int_equal(r->methods[1].frame_count, 0);
	aa_job_result_free(r); /* idempotent */
	free(r);
	aa_job_result_free(NULL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_percentile),
		cmocka_unit_test(test_timing_stats),
		cmocka_unit_test(test_summarize),
		cmocka_unit_test(test_to_json),
		cmocka_unit_test(test_write_json),
		cmocka_unit_test(test_output_dir),
		cmocka_unit_test(test_report_html),
		cmocka_unit_test(test_result_free),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}

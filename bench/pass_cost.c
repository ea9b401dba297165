/* pass_cost: what one frame of each method costs on this device, measured interleaved (round after round,
 * each method renders the same frame in its own submission, then the reference if asked). It reports the
 * GPU timestamps of each pass and, beside them, the process CPU time of each submission: lavapipe runs the
 * GPU work on this machine's cores, and on a shared 2-core machine a timestamp pair also counts the time
 * other processes held the cores, while CPU time counts only the work done (cache and core sharing still
 * move it a little). The shadow map is rendered once, before the rounds, and is in no figure.
 * Usage: bench/pass_cost [--scene S] [--size WxH] [--rounds N] [--reference-samples N] METHOD...
 * Prints one JSON object (bench/floor and bench/methods read it). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "run/engine.h"
#include "run/engine_internal.h"
#include "render/frame_plan.h"
#include "reference/reference.h"
#include "render/renderer.h"
#include "methods/methods.h"
#include "run/job_spec.h"

#define MAX_ROUNDS 200

struct sample_set {
	double cpu[MAX_ROUNDS], wall[MAX_ROUNDS], gpu[MAX_ROUNDS];
	char pass_names[AA_MAX_PASSES][32];
	double pass_gpu[AA_MAX_PASSES][MAX_ROUNDS];
	int pass_count, n;
};

static double cpu_now_ms(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int compare_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static double median(const double *v, int n)
{
	double s[MAX_ROUNDS];
	memcpy(s, v, sizeof *v * (size_t)n);
	qsort(s, (size_t)n, sizeof *s, compare_double);
	return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

static void print_values(const char *key, const double *v, int n, const char *after)
{
	printf("\"%s\": [", key);
	for (int i = 0; i < n; i++)
		printf("%s%.4f", i ? ", " : "", v[i]);
	printf("], \"%s_median\": %.4f%s", key, median(v, n), after);
}

static void print_set(const char *label, const struct sample_set *s, bool last)
{
	printf("  \"%s\": {", label);
	print_values("cpu_ms", s->cpu, s->n, ", ");
	print_values("wall_ms", s->wall, s->n, ", ");
	print_values("gpu_ms", s->gpu, s->n, ", \"passes\": {");
	for (int p = 0; p < s->pass_count; p++) {
		printf("\"%s\": {", s->pass_names[p]);
		print_values("gpu_ms", s->pass_gpu[p], s->n, p + 1 < s->pass_count ? "}, " : "}");
	}
	printf("}}%s\n", last ? "" : ",");
}

static int fail(const char *what, const struct aa_error *err)
{
	fprintf(stderr, "pass_cost: %s: %s\n", what, err->message);
	return 1;
}

int main(int argc, char **argv)
{
	struct aa_job_spec spec;
	aa_job_spec_defaults(&spec);
	snprintf(spec.scene, sizeof spec.scene, "hard-edges");
	snprintf(spec.path, sizeof spec.path, "static");
	spec.method_count = 0;
	spec.reference_samples = 0;
	int rounds = 10;
	struct aa_error err = {0};
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (strcmp(a, "--scene") == 0 && i + 1 < argc) {
			snprintf(spec.scene, sizeof spec.scene, "%s", argv[++i]);
		} else if (strcmp(a, "--size") == 0 && i + 1 < argc) {
			if (aa_parse_size(argv[++i], &spec.width, &spec.height, &err))
				return fail("--size", &err);
		} else if (strcmp(a, "--rounds") == 0 && i + 1 < argc) {
			rounds = atoi(argv[++i]);
		} else if (strcmp(a, "--reference-samples") == 0 && i + 1 < argc) {
			spec.reference_samples = atoi(argv[++i]);
		} else if (a[0] != '-' && spec.method_count < AA_MAX_METHODS) {
			struct aa_method_spec *m = &spec.methods[spec.method_count++];
			if (aa_method_parse(a, "methods", &m->method, &m->params, &err))
				return fail(a, &err);
			aa_method_label(m->method, &m->params, m->label, sizeof m->label);
		} else {
			fprintf(stderr, "usage: pass_cost [--scene S] [--size WxH] [--rounds N] "
					"[--reference-samples N] METHOD...\n");
			return 2;
		}
	}
	if (rounds < 1 || rounds > MAX_ROUNDS || spec.reference_samples < 0 || spec.reference_samples % 2) {
		fprintf(stderr, "pass_cost: rounds 1..%d, reference samples even\n", MAX_ROUNDS);
		return 2;
	}
	char file[1024];
	struct aa_scene *scene = NULL;
	struct aa_engine *engine = NULL;
	struct aa_engine_options opts = {0};
	if (aa_scene_resolve(spec.scene, file, sizeof file, &err) || aa_scene_load(file, &scene, &err))
		return fail("scene", &err);
	if (aa_engine_create(&opts, &engine, &err))
		return fail("engine", &err);
	struct aa_gpu *gpu = &engine->gpu;
	struct aa_frame_plan plan;
	aa_frame_plan_build(scene, &spec, &plan);
	struct aa_scene_upload *upload = aa_engine_scene_upload(engine, scene, &err);
	struct aa_renderer *r = NULL;
	struct aa_gpu_timer timer;
	struct aa_reference reference = {0};
	if (!upload || aa_renderer_create(gpu, scene, upload, &plan, spec.width, spec.height, &r, &err) ||
	    aa_gpu_timer_create(gpu, &timer, &err) ||
	    (spec.reference_samples && aa_reference_create(r, spec.reference_samples, &reference, &err)))
		return fail("set-up", &err);
	static struct aa_method_result infos[AA_MAX_METHODS];
	struct aa_method_state *states[AA_MAX_METHODS];
	for (int m = 0; m < spec.method_count; m++)
		if (aa_method_create(spec.methods[m].method, r, &spec.methods[m].params, &infos[m], &states[m], &err))
			return fail(spec.methods[m].label, &err);

	struct aa_frame_ctx ctx = {0};
	struct aa_camera camera;
	bool cut = false;
	aa_camera_path_eval(aa_scene_find_path(scene, "static"), true, -1.0, 0.0, &camera, &cut);
	aa_renderer_set_frame(r, &camera, 0.0, NULL, 0.0, &ctx);
	ctx.cut = true;
	VkCommandBuffer cmd;
	if (aa_gpu_begin(gpu, &cmd, &err))
		return fail("shadow map", &err);
	aa_renderer_record_shadow(r, cmd);
	if (aa_gpu_submit_wait(gpu, cmd, &err))
		return fail("shadow map", &err);

	static struct sample_set sets[AA_MAX_METHODS + 1];
	for (int round = -1; round < rounds; round++) { /* round -1: warm-up (shader variants compile) */
		for (int m = 0; m < spec.method_count; m++) {
			const struct aa_method *method = spec.methods[m].method;
			if (method->reset)
				method->reset(states[m]);
			if (aa_gpu_begin(gpu, &ctx.cmd, &err))
				return fail("begin", &err);
			aa_gpu_timer_reset(ctx.cmd, &timer);
			ctx.timer = &timer;
			ctx.output = NULL;
			double c0 = cpu_now_ms(), w0 = aa_now_ms();
			if (method->render(states[m], &ctx, &err) || aa_gpu_submit_wait(gpu, ctx.cmd, &err))
				return fail(spec.methods[m].label, &err);
			double cpu = cpu_now_ms() - c0, wall = aa_now_ms() - w0;
			double ms[AA_GPU_TIMER_MAX / 2];
			if (aa_gpu_timer_read(gpu, &timer, ms, &err))
				return fail("timer", &err);
			if (round < 0)
				continue;
			struct sample_set *s = &sets[m];
			s->cpu[s->n] = cpu;
			s->wall[s->n] = wall;
			s->gpu[s->n] = 0;
			s->pass_count = timer.span_count < AA_MAX_PASSES ? timer.span_count : AA_MAX_PASSES;
			for (int p = 0; p < s->pass_count; p++) {
				snprintf(s->pass_names[p], sizeof s->pass_names[p], "%s", timer.spans[p].name);
				s->pass_gpu[p][s->n] = ms[p];
				s->gpu[s->n] += ms[p];
			}
			s->n++;
		}
		if (spec.reference_samples && round >= 0) {
			struct aa_image_rgbaf full, half;
			if (aa_image_rgbaf_alloc(&full, spec.width, spec.height) ||
			    aa_image_rgbaf_alloc(&half, spec.width, spec.height))
				return 1;
			struct sample_set *s = &sets[spec.method_count];
			double gpu_ms, cpu_ms, c0 = cpu_now_ms();
			if (aa_reference_render(&reference, &timer, &full, &half, &gpu_ms, &cpu_ms, &err))
				return fail("reference", &err);
			s->cpu[s->n] = cpu_now_ms() - c0;
			s->wall[s->n] = cpu_ms;
			s->gpu[s->n] = gpu_ms;
			s->n++;
			aa_image_rgbaf_free(&full);
			aa_image_rgbaf_free(&half);
		}
	}

	printf("{\"scene\": \"%s\", \"width\": %d, \"height\": %d, \"rounds\": %d, \"reference_samples\": %d,\n"
	       " \"device\": \"%s\",\n \"methods\": {\n", scene->name, spec.width, spec.height, rounds,
	       spec.reference_samples, gpu->properties.deviceName);
	for (int m = 0; m < spec.method_count; m++)
		print_set(spec.methods[m].label, &sets[m], m + 1 == spec.method_count && !spec.reference_samples);
	if (spec.reference_samples)
		print_set("reference", &sets[spec.method_count], true);
	printf(" }\n}\n");

	for (int m = 0; m < spec.method_count; m++)
		spec.methods[m].method->destroy(states[m]);
	if (spec.reference_samples)
		aa_reference_destroy(&reference);
	aa_gpu_timer_destroy(gpu, &timer);
	aa_renderer_destroy(r);
	aa_engine_destroy(engine);
	aa_scene_free(scene);
	return 0;
}

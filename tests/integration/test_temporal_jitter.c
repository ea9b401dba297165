/* Jitter through the real renderer: two quads, one 2 units from the camera and one 20, rendered with
 * a sub-pixel jitter into the plain scene target (none, the reference, supersampling) and into the
 * G-buffer target (taa, asaa, t2msaa) must both move by exactly the jitter. A jitter added before the
 * projection (seed 000's bug) moves the near quad ten times as far as the far one and fails here. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "run/engine_internal.h"
#include "fixture.h"
#include "render/frame_plan.h"
#include "render/renderer.h"
#include "methods/jitter.h"

enum { WIDTH = 320, HEIGHT = 180 };

/* Unlit quads, red near and green far, each about 100 pixels across and turned 8 degrees about the view
 * axis so that their edges are slanted: the centroid of the covered pixel centres then follows a
 * sub-pixel shift closely (every row and column crosses an edge at a different fraction). */
static const char quads_scene[] =
	"{\"name\": \"jitter-quads\", \"background\": [0, 0, 0],"
	" \"materials\": {\"near\": {\"color\": [1, 0, 0], \"unlit\": true},"
	"                 \"far\": {\"color\": [0, 1, 0], \"unlit\": true}},"
	" \"objects\": ["
	"  {\"mesh\": {\"type\": \"plane\", \"size\": 0.8}, \"material\": \"near\", \"position\": [-0.55, 0, -2],"
	"   \"rotation\": [90, 0, 8]},"
	"  {\"mesh\": {\"type\": \"plane\", \"size\": 8}, \"material\": \"far\", \"position\": [5.5, 0, -20],"
	"   \"rotation\": [90, 0, 8]}],"
	" \"camera\": {\"position\": [0, 0, 0], \"target\": [0, 0, -1], \"fov\": 40, \"near\": 0.1, \"far\": 100}}";

struct quads {
	struct aa_scene *scene;
	struct aa_renderer *renderer;
	struct aa_scene_target plain, gbuffer;
	struct aa_gpu_buffer readback;
};

static void quads_open(struct quads *q)
{
	struct aa_error err = {0};
	memset(q, 0, sizeof *q);
	if (aa_scene_load_string(quads_scene, "jitter-quads", ".", &q->scene, &err))
		fail_msg("scene: %s: %s", err.path, err.message);
	const char *methods[] = {"none", "taa"};
	struct aa_job_spec spec;
	fixture_spec(&spec, NULL, methods, 2, WIDTH, HEIGHT, 1, 2);
	struct aa_frame_plan plan;
	aa_frame_plan_build(q->scene, &spec, &plan);
	struct aa_scene_upload *upload = aa_engine_scene_upload(fixture_engine, q->scene, &err);
	struct aa_scene_target_desc g = {.samples = 1, .outputs = AA_OUT_VELOCITY | AA_OUT_SURFACE};
	if (!upload ||
	    aa_renderer_create(&fixture_engine->gpu, q->scene, upload, &plan, WIDTH, HEIGHT, &q->renderer, &err) ||
	    aa_scene_target_create(q->renderer, &q->plain, WIDTH, HEIGHT, "plain", NULL, &err) ||
	    aa_scene_target_create_desc(q->renderer, &q->gbuffer, WIDTH, HEIGHT, &g, "gbuffer", NULL, &err))
		fail_msg("renderer: %s", err.message);
	struct aa_camera cam;
	struct aa_frame_ctx ctx = {0};
	aa_camera_path_eval(aa_scene_find_path(q->scene, "default"), true, -1.0, 0.0, &cam, NULL);
	aa_renderer_set_frame(q->renderer, &cam, 0.0, NULL, 0.0, &ctx);
}

static void quads_close(struct quads *q)
{
	aa_gpu_buffer_destroy(&fixture_engine->gpu, &q->readback);
	aa_scene_target_destroy(q->renderer, &q->plain);
	aa_scene_target_destroy(q->renderer, &q->gbuffer);
	aa_renderer_destroy(q->renderer);
	aa_scene_free(q->scene);
}

/* Renders with jitter (jx, jy) pixels and returns the centroids (x right, y down, pixel centres at
 * i + 0.5) of the pixels each quad covers: [0] near (red), [1] far (green). */
static void render_centroids(struct quads *q, struct aa_scene_target *t, float jx, float jy, double c[2][2])
{
	struct aa_gpu *gpu = &fixture_engine->gpu;
	struct aa_error err = {0};
	VkCommandBuffer cmd;
	if (aa_gpu_begin(gpu, &cmd, &err))
		fail_msg("%s", err.message);
	aa_renderer_draw_scene(q->renderer, cmd, t, jx, jy);
	if (aa_gpu_record_readback(gpu, cmd, t->output, &q->readback, &err) || aa_gpu_submit_wait(gpu, cmd, &err))
		fail_msg("%s", err.message);
	const uint16_t *half = q->readback.mapped; /* RGBA16F; 0x3800 is 0.5 */
	double sum[2][2] = {{0}}, count[2] = {0};
	for (int y = 0; y < HEIGHT; y++)
		for (int x = 0; x < WIDTH; x++)
			for (int k = 0; k < 2; k++)
				if (half[((size_t)y * WIDTH + (size_t)x) * 4 + (size_t)k] >= 0x3800) {
					sum[k][0] += x + 0.5;
					sum[k][1] += y + 0.5;
					count[k] += 1.0;
				}
	for (int k = 0; k < 2; k++) {
		/* each quad is about 100 pixels across and fully in view */
		if (count[k] < 5000 || count[k] > 15000)
			fail_msg("quad %d covers %.0f pixels: not in view as the test expects", k, count[k]);
		c[k][0] = sum[k][0] / count[k];
		c[k][1] = sum[k][1] / count[k];
	}
}

/* Every Halton(2,3) jitter of taa's 16-frame cycle and two jitters near the pixel's corners move both
 * quads by the jitter, in both kinds of scene target. */
static void test_jitter_moves_every_depth_alike(void **state)
{
	(void)state;
	struct quads q;
	quads_open(&q);
	struct aa_scene_target *targets[2] = {&q.plain, &q.gbuffer};
	const char *names[2] = {"plain target", "G-buffer target"};
	float jitters[18][2] = {{0.45f, -0.4f}, {-0.49f, 0.47f}};
	for (int f = 0; f < 16; f++)
		aa_jitter_halton(f, 16, jitters[2 + f]);
	double worst = 0.0;
	for (int t = 0; t < 2; t++) {
		double base[2][2];
		render_centroids(&q, targets[t], 0.0f, 0.0f, base);
		for (int j = 0; j < 18; j++) {
			double c[2][2];
			render_centroids(&q, targets[t], jitters[j][0], jitters[j][1], c);
			for (int k = 0; k < 2; k++)
				for (int a = 0; a < 2; a++) {
					double moved = c[k][a] - base[k][a], error = fabs(moved - jitters[j][a]);
					if (error > worst)
						worst = error;
					if (error > 0.05)
						fail_msg("%s, jitter (%.3f, %.3f): the %s quad moved %.3f px in %c, not %.3f",
							 names[t], (double)jitters[j][0], (double)jitters[j][1],
							 k ? "far" : "near", moved, a ? 'y' : 'x', (double)jitters[j][a]);
				}
		}
	}
	printf("  18 jitters x 2 targets: both quads moved by the jitter to within %.4f px\n", worst);
	quads_close(&q);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_jitter_moves_every_depth_alike),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}

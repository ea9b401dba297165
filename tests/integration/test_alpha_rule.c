/* Alpha-tested geometry follows one rule per method family (docs/methods.md): MSAA-style methods
 * (msaa on both paths, rsaa, t2msaa, gbaa) test alpha once per pixel and triangle, so on a cut-out quad
 * that covers the whole image their output is none's except along the quad's diagonal, where two
 * triangles share pixels; supersampling (ssaa) and alpha to coverage test each sample, so both differ from
 * none along every alpha edge; every rule cuts where glTF's cutoff says. Then the two msaa:4 paths score alike
 * on cutout-fence with either alpha rule, and each method reports the rule it ran with. */
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
#include "fixture.h"
#include "scene/texture.h"
#include "methods/methods.h"

#define SIZE 128
#define TEXELS 32 /* magnified 4x: every fetch reads mip level 0, so no method differs by its LOD */

static const char *const methods[] = {
	"none", "msaa:4,path=hardware", "msaa:4,path=virtual", "msaa:8", "rsaa:8", "t2msaa", "gbaa",
	"ssaa:4", "msaa:4,alpha_to_coverage=true", "msaa:8,alpha_to_coverage=true",
};
#define METHODS 10
#define PER_PIXEL_METHODS 7 /* methods[1..6] test alpha once per pixel */

/* A cut-out texture: diagonal wires and a ring, with alpha ramps that the linear filter turns into edges
 * at every angle. */
static void cutout_texels(uint8_t *px)
{
	for (int y = 0; y < TEXELS; y++)
		for (int x = 0; x < TEXELS; x++) {
			double wire = fabs(fmod(x + y + 0.5, 8.0) - 4.0) / 4.0;
			double ring = fabs(hypot(x - 15.3, y - 16.1) - 9.0) / 3.0;
			double a = fmax(1.0 - wire * 2.2, 1.0 - ring);
			uint8_t *p = &px[(y * TEXELS + x) * 4];
			p[0] = (uint8_t)(60 + 5 * x);
			p[1] = (uint8_t)(200 - 4 * y);
			p[2] = 90;
			p[3] = (uint8_t)lrint(fmin(fmax(a, 0.0), 1.0) * 255.0);
		}
}

/* One quad over the whole image (two triangles, split along a diagonal), unlit, alpha cut-out. */
static struct aa_scene *cutout_quad(void)
{
	struct aa_polygon2d quad = {4, {{0, 0}, {SIZE, 0}, {SIZE, SIZE}, {0, SIZE}}};
	struct aa_scene *scene;
	struct aa_error err = {0};
	float fg[3] = {1, 1, 1}, bg[3] = {0.1f, 0.2f, 0.4f};
	assert_int_equal(aa_scene_from_polygons(&quad, 1, SIZE, SIZE, fg, bg, &scene, &err), 0);
	uint8_t px[TEXELS * TEXELS * 4];
	cutout_texels(px);
	assert_non_null(scene->textures = calloc(1, sizeof *scene->textures));
	assert_int_equal(aa_texture_from_rgba8_as(&scene->textures[0], px, TEXELS, TEXELS, AA_TEXELS_COVERAGE, &err), 0);
	scene->texture_count = 1;
	struct aa_material *m = &scene->materials[0];
	m->pattern = AA_PATTERN_TEXTURE;
	m->texture_index = 0;
	m->alpha_cutout = true;
	m->alpha_cutoff = 0.5f;
	return scene;
}

struct capture {
	float *images[METHODS]; /* linear RGB of each method's frame */
};

static int capture_linear(const struct aa_event *ev, void *user)
{
	struct capture *c = user;
	if (ev->type != AA_EVENT_METHOD_FRAME)
		return 0;
	for (int i = 0; i < SIZE * SIZE; i++)
		for (int ch = 0; ch < 3; ch++)
			c->images[ev->method_index][i * 3 + ch] = ev->linear->pixels[i * 4 + ch];
	return 0;
}

static int capture_small(const struct aa_event *ev, void *user)
{
	struct capture *c = user;
	if (ev->type != AA_EVENT_METHOD_FRAME)
		return 0;
	for (int i = 0; i < ev->linear->width * ev->linear->height; i++)
		for (int ch = 0; ch < 3; ch++)
			c->images[ev->method_index][i * 3 + ch] = ev->linear->pixels[i * 4 + ch];
	return 0;
}

/* Pixels where method m's frame differs from none's; *off_diagonal counts those not on the diagonal. */
static int differing(const struct capture *c, int m, int *off_diagonal)
{
	int n = 0;
	*off_diagonal = 0;
	for (int y = 0; y < SIZE; y++)
		for (int x = 0; x < SIZE; x++) {
			double d = 0;
			for (int ch = 0; ch < 3; ch++)
				d = fmax(d, fabs(c->images[m][(y * SIZE + x) * 3 + ch] - c->images[0][(y * SIZE + x) * 3 + ch]));
			if (d > 2e-3) {
				n++;
				*off_diagonal += abs(x - y) > 1; /* the fan splits the quad from (0,0) to (SIZE,SIZE) */
			}
		}
	return n;
}

static void test_once_per_pixel_on_a_cutout_quad(void **state)
{
	(void)state;
	struct aa_scene *scene = cutout_quad();
	struct aa_job_spec spec;
	fixture_spec(&spec, NULL, methods, METHODS, SIZE, SIZE, 1, 2);
	struct capture c;
	for (int m = 0; m < METHODS; m++)
		assert_non_null(c.images[m] = calloc(SIZE * SIZE * 3, sizeof(float)));
	struct aa_job_result *r = fixture_run(&spec, scene, capture_linear, &c);
	int counts[METHODS], off[METHODS];
	printf("  cut-out quad %dx%d, pixels that differ from none (off the diagonal):\n", SIZE, SIZE);
	for (int m = 1; m < METHODS; m++) {
		counts[m] = differing(&c, m, &off[m]);
		printf("  %-32s %-18s %5d (%d)\n", methods[m],
		       aa_alpha_rule_name(aa_method_alpha_rule(r->methods[m].method, &r->methods[m].params)), counts[m],
		       off[m]);
	}
	for (int m = 1; m < PER_PIXEL_METHODS; m++) {
		assert_string_equal(aa_alpha_rule_name(aa_method_alpha_rule(r->methods[m].method, &r->methods[m].params)),
				    "per-pixel");
		assert_true(off[m] <= SIZE / 64); /* a stray float rounding at the cutoff, at most */
	}
	/* per-sample and alpha-to-coverage methods resolve the alpha edges: hundreds of pixels */
	for (int m = PER_PIXEL_METHODS; m < METHODS; m++)
		assert_true(off[m] > 300);
	for (int m = 0; m < METHODS; m++)
		free(c.images[m]);
	fixture_free(r);
	aa_scene_free(scene);
}

/* glTF MASK is a hard cut at alphaCutoff, with or without alpha to coverage (docs/methods.md): on a quad over
 * the whole image whose alpha rises linearly from 0 at one edge to 1 at the other, every method keeps
 * (1 - cutoff) of the rows at cutoffs 0.25, 0.5 and 0.75 (within 1.5 rows), and at most two partly kept
 * rows per column (the cut's own anti-aliased edge, which may straddle a row boundary). Keeping
 * round(alpha N) samples turned the panel into a ramp: about half the rows kept whatever the cutoff,
 * every row partly. The ramp is read magnified (64 texels, mip 0) and minified (512 texels, mip 2,
 * alpha-weighted mips). */
#define PANEL 128
#define PANEL_METHODS 7
static void test_mask_cuts_at_the_cutoff(void **state)
{
	(void)state;
	static const char *const list[PANEL_METHODS] = {
		"none", "ssaa:4", "msaa:4", "msaa:4,path=hardware,alpha_to_coverage=true",
		"msaa:4,path=virtual,alpha_to_coverage=true", "msaa:8,alpha_to_coverage=true",
		"rsaa:8,alpha_to_coverage=true"};
	static const int texel_rows[] = {64, 512};
	static const float cutoffs[] = {0.25f, 0.5f, 0.75f};
	const float bg[3] = {0.1f, 0.2f, 0.4f};
	int failures = 0;
	for (size_t t = 0; t < sizeof texel_rows / sizeof texel_rows[0]; t++)
		for (size_t k = 0; k < sizeof cutoffs / sizeof cutoffs[0]; k++) {
			struct aa_polygon2d quad = {4, {{0, 0}, {PANEL, 0}, {PANEL, PANEL}, {0, PANEL}}};
			struct aa_scene *scene;
			struct aa_error err = {0};
			float fg[3] = {1, 1, 1};
			assert_int_equal(aa_scene_from_polygons(&quad, 1, PANEL, PANEL, fg, bg, &scene, &err), 0);
			int rows = texel_rows[t];
			uint8_t *px = malloc((size_t)rows * 4 * 4);
			assert_non_null(px);
			for (int y = 0; y < rows; y++)
				for (int x = 0; x < 4; x++) {
					uint8_t *p = &px[(y * 4 + x) * 4];
					p[0] = 250, p[1] = 40, p[2] = 20;
					p[3] = (uint8_t)lrint(255.0 * (y + 0.5) / rows);
				}
			assert_non_null(scene->textures = calloc(1, sizeof *scene->textures));
			assert_int_equal(aa_texture_from_rgba8_as(&scene->textures[0], px, 4, rows, AA_TEXELS_COVERAGE, &err), 0);
			free(px);
			scene->texture_count = 1;
			struct aa_material *m = &scene->materials[0];
			m->pattern = AA_PATTERN_TEXTURE;
			m->texture_index = 0;
			m->alpha_cutout = true;
			m->alpha_cutoff = cutoffs[k];
			struct aa_job_spec spec;
			fixture_spec(&spec, NULL, list, PANEL_METHODS, PANEL, PANEL, 1, 2);
			struct capture c;
			for (int i = 0; i < PANEL_METHODS; i++)
				assert_non_null(c.images[i] = calloc(PANEL * PANEL * 3, sizeof(float)));
			struct aa_job_result *r = fixture_run(&spec, scene, capture_small, &c);
			float full = 0; /* the panel's colour where it is kept whole */
			for (int i = 0; i < PANEL * PANEL; i++)
				full = fmaxf(full, c.images[0][i * 3]);
			double want = PANEL * (1.0 - cutoffs[k]);
			for (int i = 0; i < PANEL_METHODS; i++) {
				double kept = 0;
				int worst_partial = 0;
				for (int x = 0; x < PANEL; x++) {
					int partial = 0;
					for (int y = 0; y < PANEL; y++) {
						double share = (c.images[i][(y * PANEL + x) * 3] - bg[0]) / (full - bg[0]);
						kept += share;
						partial += abs(x - y) > 1 && share > 0.02 && share < 0.98;
					}
					worst_partial = partial > worst_partial ? partial : worst_partial;
				}
				kept /= PANEL;
				bool ok = fabs(kept - want) <= 1.5 && worst_partial <= 2;
				printf("  %3d texel rows, cutoff %.2f: %-44s keeps %6.2f of %d rows (want %.0f), at most %d "
				       "partly%s\n", rows, cutoffs[k], list[i], kept, PANEL, want, worst_partial, ok ? "" : "  FAIL");
				failures += !ok;
			}
			for (int i = 0; i < PANEL_METHODS; i++)
				free(c.images[i]);
			fixture_free(r);
			aa_scene_free(scene);
		}
	if (failures)
		fail_msg("%d method runs do not cut at the cutoff", failures);
}

/* The scene: hardware and virtual samples test alpha the same way, with and without alpha to
 * coverage, so they score alike. */
static void test_paths_agree_on_cutout_fence(void **state)
{
	(void)state;
	const char *list[] = {"msaa:4,path=hardware", "msaa:4,path=virtual", "msaa:4,path=hardware,alpha_to_coverage=true",
			      "msaa:4,path=virtual,alpha_to_coverage=true"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "cutout-fence", list, 4, 320, 180, 1, 16);
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	double psnr[4];
	for (int i = 0; i < 4; i++)
		psnr[i] = r->methods[i].frames[0].metrics.psnr;
	printf("  cutout-fence 320x180: msaa:4 per pixel hardware %.2f dB, virtual %.2f dB; alpha to coverage "
	       "hardware %.2f dB, virtual %.2f dB\n", psnr[0], psnr[1], psnr[2], psnr[3]);
	assert_true(fabs(psnr[0] - psnr[1]) < 0.1);
	assert_true(fabs(psnr[2] - psnr[3]) < 0.1);
	fixture_free(r);
}

/* Every registered method states a rule; the families are as docs/methods.md says. */
static void test_every_method_reports_its_rule(void **state)
{
	(void)state;
	static const char *const expect[][2] = {
		{"none", "per-pixel"}, {"fxaa", "per-pixel"}, {"smaa", "per-pixel"}, {"gbaa", "per-pixel"},
		{"smaa:mode=t2x", "per-sample"}, {"smaa:mode=s2x", "per-pixel"}, {"smaa:mode=4x", "per-pixel"},
		{"cmaa2", "per-pixel"},
		{"msaa", "per-pixel"}, {"msaa:8,alpha_to_coverage=true", "alpha-to-coverage"}, {"rsaa", "per-pixel"},
		{"rsaa:8,alpha_to_coverage=true", "alpha-to-coverage"}, {"t2msaa", "per-pixel"},
		{"ssaa", "per-sample"}, {"taa", "per-sample"}, {"asaa", "per-sample"},
	};
	for (size_t i = 0; i < sizeof expect / sizeof expect[0]; i++) {
		const struct aa_method *m;
		struct aa_method_params p;
		struct aa_error err = {0};
		if (aa_method_parse(expect[i][0], "methods", &m, &p, &err) != 0)
			continue; /* not in this build */
		assert_string_equal(aa_alpha_rule_name(aa_method_alpha_rule(m, &p)), expect[i][1]);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_once_per_pixel_on_a_cutout_quad),
		cmocka_unit_test(test_mask_cuts_at_the_cutoff),
		cmocka_unit_test(test_paths_agree_on_cutout_fence),
		cmocka_unit_test(test_every_method_reports_its_rule),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}

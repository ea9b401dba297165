/* Mesh files drawn as their authors made them, on the GPU: one scene per material feature of
 * tests/assets/ whose reference frame (the ground truth every method is scored against) is checked where the
 * answer is known (an orthographic camera, ambient light only: a dielectric shows ambient x (base + 0.04),
 * an unlit or emissive surface its colour exactly) and compared with a golden image within a tolerance;
 * skinned vertices move and the velocity pass sees them; every method draws every feature without a NaN
 * or a validation error; a shadow-casting sun on `horizon` shows the fences' shadows.
 * AALAB_UPDATE_GOLDEN=1 writes the golden images (tests/assets/golden/) instead of checking them. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "run/engine_internal.h"
#include "fixture.h"
#include "render/frame_plan.h"
#include "render/renderer.h"
#include "methods/methods.h"

#define W 160
#define H 90
#define ORTHO_HEIGHT 2.25f /* 40 pixels per unit: x in [-2, 2], y in [-1.125, 1.125] */
#define BACKDROP 0.2f, 0.3f, 0.4f

static char assets[1024];

static int setup(void **state)
{
	const char *top = getenv("top_srcdir");
	snprintf(assets, sizeof assets, "%s/tests/assets", top && top[0] ? top : ".");
	return fixture_setup(state);
}

static struct aa_scene *load_scene(const char *json)
{
	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	if (aa_scene_load_string(json, "assets.json", assets, &sc, &err))
		fail_msg("%s", err.message);
	return sc;
}

/* A test asset before an unlit backdrop, seen by an orthographic camera; ambient light only, unless
 * `lights` says otherwise. */
static struct aa_scene *feature_scene(const char *file, float ambient, const char *lights, const char *object_extra)
{
	char json[2048];
	snprintf(json, sizeof json,
		 "{\"ambient\": [%g, %g, %g], \"background\": [0, 0, 0],"
		 " \"materials\": {\"backdrop\": {\"color\": [%s], \"unlit\": true}},"
		 " \"objects\": [{\"name\": \"backdrop\", \"mesh\": {\"type\": \"plane\", \"size\": [6, 4]},"
		 " \"material\": \"backdrop\", \"position\": [0, 0, -1], \"rotation\": [90, 0, 0]},"
		 " {\"name\": \"asset\", \"mesh\": {\"type\": \"file\", \"path\": \"%s\"}%s}],"
		 " \"lights\": [%s],"
		 " \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0], \"projection\": \"orthographic\","
		 " \"ortho_height\": %g}}",
		 ambient, ambient, ambient, "0.2, 0.3, 0.4", file, object_extra ? object_extra : "", lights ? lights : "",
		 ORTHO_HEIGHT);
	return load_scene(json);
}

struct capture {
	int frame;                      /* the reference frame kept */
	float *linear;                  /* W x H RGBA, linear */
	struct aa_image_rgba8 srgb;
};

static int capture_reference(const struct aa_event *ev, void *user)
{
	struct capture *c = user;
	if (ev->type != AA_EVENT_REFERENCE_FRAME || ev->frame_ordinal != c->frame)
		return 0;
	size_t n = (size_t)ev->linear->width * ev->linear->height * 4;
	c->linear = malloc(n * sizeof *c->linear);
	memcpy(c->linear, ev->linear->pixels, n * sizeof *c->linear);
	aa_image_rgba8_alloc(&c->srgb, ev->image->width, ev->image->height);
	memcpy(c->srgb.pixels, ev->image->pixels, n);
	return 0;
}

/* The reference of one frame at time `frame`/30 s (the default path, the scene camera). */
static void render_reference(const struct aa_scene *sc, int frame, int samples, struct capture *c)
{
	static const char *const none[] = {"none"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "assets", none, 1, W, H, 1, samples);
	spec.first_frame = frame;
	memset(c, 0, sizeof *c);
	struct aa_job_result *r = fixture_run(&spec, sc, capture_reference, c);
	assert_non_null(c->linear);
	assert_int_equal(r->reference.frames[0].nonfinite, 0);
	fixture_free(r);
}

static void capture_free(struct capture *c)
{
	free(c->linear);
	aa_image_rgba8_free(&c->srgb);
}

/* The linear colour of the pixel at world (x, y) (the orthographic camera above). */
static const float *at(const struct capture *c, float x, float y)
{
	float ppu = (float)H / ORTHO_HEIGHT;
	int px = (int)floorf((float)W / 2 + x * ppu), py = (int)floorf((float)H / 2 - y * ppu);
	assert_true(px >= 0 && px < W && py >= 0 && py < H);
	return &c->linear[((size_t)py * W + px) * 4];
}

static void expect_color(const struct capture *c, const char *what, float x, float y, float r, float g, float b,
			 float tolerance)
{
	const float *p = at(c, x, y);
	if (fabsf(p[0] - r) > tolerance || fabsf(p[1] - g) > tolerance || fabsf(p[2] - b) > tolerance)
		fail_msg("%s at (%g, %g): (%.4f, %.4f, %.4f), expected (%.4f, %.4f, %.4f) within %g", what, x, y, p[0], p[1],
			 p[2], r, g, b, tolerance);
}

/* Ambient light a on a dielectric of base colour c: a x (c + 0.04) (shading.glsl: diffuse plus F0). */
static float lit(float ambient, float base)
{
	return ambient * (base + 0.04f);
}

static float srgb(int byte)
{
	float v = (float)byte / 255.0f;
	return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

/* The golden image of a feature (the reference renderer's output when the test was written), within a
 * tolerance wide enough for differences of rounding between CPUs. */
static void check_golden(const char *name, const struct capture *c)
{
	char path[1200];
	snprintf(path, sizeof path, "%s/golden/%s.png", assets, name);
	struct aa_error err = {0};
	if (getenv("AALAB_UPDATE_GOLDEN")) {
		if (aa_image_write_png(path, &c->srgb, &err))
			fail_msg("%s", err.message);
		printf("  wrote %s\n", path);
		return;
	}
	struct aa_image_rgba8 golden = {0};
	struct aa_metrics m;
	if (aa_image_read_rgba8(path, &golden, &err))
		fail_msg("golden image: %s (AALAB_UPDATE_GOLDEN=1 writes it)", err.message);
	if (golden.width != c->srgb.width || golden.height != c->srgb.height)
		fail_msg("golden image %s is %dx%d", path, golden.width, golden.height);
	assert_int_equal(aa_metrics_compare(&golden, &c->srgb, &m, &err), 0);
	aa_image_rgba8_free(&golden);
	if (!m.identical && m.psnr < 40.0)
		fail_msg("%s: %.2f dB against its golden image (at least 40 expected)", name, m.psnr);
}

/* ---------------------------------------------------------------- one test per feature */

/* baseColorFactor; a base colour texture (sRGB) times a factor (1, 1, 0.5); KHR_materials_unlit. */
static void test_base_color(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("base-color.gltf", 0.5f, NULL, NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	const float t = 0.01f;
	expect_color(&c, "factor", -1.1f, 0, lit(0.5f, 0.8f), lit(0.5f, 0.1f), lit(0.5f, 0.1f), t);
	expect_color(&c, "texture red", -0.25f, 0.25f, lit(0.5f, 1), lit(0.5f, 0), lit(0.5f, 0), t);
	expect_color(&c, "texture green", 0.25f, 0.25f, lit(0.5f, 0), lit(0.5f, 1), lit(0.5f, 0), t);
	expect_color(&c, "texture blue x 0.5", -0.25f, -0.25f, lit(0.5f, 0), lit(0.5f, 0), lit(0.5f, 0.5f), t);
	expect_color(&c, "texture white x (1, 1, 0.5)", 0.25f, -0.25f, lit(0.5f, 1), lit(0.5f, 1), lit(0.5f, 0.5f), t);
	expect_color(&c, "unlit", 1.1f, 0, 0.2f, 0.6f, 0.9f, 1e-3f);
	expect_color(&c, "backdrop", 0, 1.0f, BACKDROP, 1e-3f);
	check_golden("base-color", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* COLOR_0 times the base colour: the quad's corners red, green, blue, white; its centre lies on the
 * diagonal from the red to the blue corner. */
static void test_vertex_colors(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("vertex-colors.gltf", 0.5f, NULL, NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	expect_color(&c, "centre", 0.01f, -0.01f, lit(0.5f, 0.5f), lit(0.5f, 0), lit(0.5f, 0.5f), 0.02f);
	const float *green = at(&c, 0.95f, 0.95f), *red = at(&c, -0.95f, 0.95f);
	assert_true(green[1] > 0.4f && green[0] < 0.1f && red[0] > 0.4f && red[1] < 0.1f);
	check_golden("vertex-colors", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* Emitted light on black surfaces, no ambient: the emissive factor times KHR_materials_emissive_strength,
 * and an emissive texture, exactly. */
static void test_emissive(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("emissive.gltf", 0.0f, NULL, NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	expect_color(&c, "factor x strength 2", -0.6f, 0, 0.8f, 0.4f, 0.0f, 1e-3f);
	expect_color(&c, "texture red", 0.35f, 0.25f, 1, 0, 0, 1e-3f);
	expect_color(&c, "texture blue", 0.35f, -0.25f, 0, 0, 1, 1e-3f);
	check_golden("emissive", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* The normal texture tilts every normal 45 degrees toward +u. Lit from the left at 45 degrees: with
 * generated tangents (+u = +x) the left quad turns away from the light (N.L = 0), the right one (tangent
 * -x) turns to it (N.L = 1); without the normal map both would be alike. */
static void test_normal_map(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("normal-map.gltf", 0.0f,
					    "{\"type\": \"directional\", \"direction\": [1, 0, -1]}", NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	const float *away = at(&c, -0.6f, 0), *toward = at(&c, 0.6f, 0);
	if (!(away[0] < 0.05f && toward[0] > 0.5f))
		fail_msg("normal map: turned away %.3f, turned toward %.3f", away[0], toward[0]);
	check_golden("normal-map", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* MASK: the texture's transparent left half shows the backdrop (the cut-out path); BLEND: half the red
 * quad over the backdrop; OPAQUE: alpha 0.2 ignored. */
static void test_alpha_modes(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("alpha-modes.gltf", 0.5f, NULL, NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	float g[3] = {srgb(40), srgb(200), srgb(40)};
	expect_color(&c, "mask, cut away", -1.35f, 0, BACKDROP, 1e-3f);
	expect_color(&c, "mask, kept", -0.85f, 0, lit(0.5f, g[0]), lit(0.5f, g[1]), lit(0.5f, g[2]), 0.01f);
	expect_color(&c, "blend", 0, 0, 0.5f * lit(0.5f, 1) + 0.5f * 0.2f, 0.5f * lit(0.5f, 0) + 0.5f * 0.3f,
		     0.5f * lit(0.5f, 0) + 0.5f * 0.4f, 0.01f);
	expect_color(&c, "opaque", 1.1f, 0, lit(0.5f, 0.1f), lit(0.5f, 0.1f), lit(0.5f, 0.9f), 0.01f);
	check_golden("alpha-modes", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* The frames of a job at one frame ordinal: the reference's (slot 0) and each method's (slot 1 + index). */
#define OPAQUE_ALPHA_METHODS 6
struct job_frames {
	int frame;
	struct capture slots[1 + OPAQUE_ALPHA_METHODS];
};

static int capture_job_frame(const struct aa_event *ev, void *user)
{
	struct job_frames *j = user;
	if ((ev->type != AA_EVENT_REFERENCE_FRAME && ev->type != AA_EVENT_METHOD_FRAME) || ev->frame_ordinal != j->frame)
		return 0;
	struct capture *c = &j->slots[ev->type == AA_EVENT_REFERENCE_FRAME ? 0 : 1 + ev->method_index];
	size_t n = (size_t)ev->linear->width * ev->linear->height * 4;
	c->linear = malloc(n * sizeof *c->linear);
	memcpy(c->linear, ev->linear->pixels, n * sizeof *c->linear);
	return 0;
}

/* glTF OPAQUE ignores alpha, also in the mip chain: a texture whose texels have alpha 0 (green on the left
 * half; red of alpha 0 between blue of alpha 1 on the right) keeps its colours at a distance (1024 texels
 * over 40 pixels: mip 4-5, 2-3 for the reference and ssaa:16) in the reference and in every method, where mips weighted by alpha turned
 * the left half black and the right half blue. The same texture on a BLEND quad is coverage: nothing on
 * the left, blue at half coverage on the right (its own copy with alpha-weighted mips). */
static void test_opaque_alpha(void **state)
{
	(void)state;
	static const char *const methods[OPAQUE_ALPHA_METHODS] = {"none", "fxaa", "smaa", "msaa:4", "ssaa:16", "taa"};
	struct aa_scene *sc = feature_scene("opaque-alpha.gltf", 0.5f, NULL, NULL);
	struct aa_job_spec spec;
	fixture_spec(&spec, "assets", methods, OPAQUE_ALPHA_METHODS, W, H, 4, 16);
	struct job_frames j = {.frame = 3};
	struct aa_job_result *r = fixture_run(&spec, sc, capture_job_frame, &j);
	float green[3] = {srgb(40), srgb(200), srgb(40)};
	float mix[3] = {(srgb(200) + srgb(40)) / 2, srgb(40), (srgb(40) + srgb(200)) / 2};
	float back[3] = {BACKDROP}, half_blue[3] = {0.5f * srgb(40) + 0.5f * back[0], 0.5f * srgb(40) + 0.5f * back[1],
						   0.5f * srgb(200) + 0.5f * back[2]};
	for (int k = 0; k <= OPAQUE_ALPHA_METHODS; k++) {
		const struct capture *c = &j.slots[k];
		const char *name = k ? methods[k - 1] : "reference";
		assert_non_null(c->linear);
		const float *p = at(c, -0.85f, 0), *q = at(c, -0.35f, 0), *b = at(c, 0.85f, 0);
		printf("  %-10s opaque: alpha-0 green (%.3f %.3f %.3f), red|blue (%.3f %.3f %.3f); blend blue (%.3f %.3f "
		       "%.3f)\n", name, p[0], p[1], p[2], q[0], q[1], q[2], b[0], b[1], b[2]);
	}
	for (int k = 0; k <= OPAQUE_ALPHA_METHODS; k++) {
		const struct capture *c = &j.slots[k];
		const char *name = k ? methods[k - 1] : "reference";
		char what[96];
		snprintf(what, sizeof what, "%s, opaque, green of alpha 0", name);
		expect_color(c, what, -0.85f, 0, green[0], green[1], green[2], 0.01f);
		snprintf(what, sizeof what, "%s, opaque, red of alpha 0 between blue", name);
		expect_color(c, what, -0.35f, 0, mix[0], mix[1], mix[2], 0.02f);
		snprintf(what, sizeof what, "%s, blend, alpha 0", name);
		expect_color(c, what, 0.35f, 0, back[0], back[1], back[2], 0.01f);
		snprintf(what, sizeof what, "%s, blend, blue at half coverage", name);
		expect_color(c, what, 0.85f, 0, half_blue[0], half_blue[1], half_blue[2], 0.02f);
	}
	for (int k = 0; k <= OPAQUE_ALPHA_METHODS; k++)
		free(j.slots[k].linear);
	fixture_free(r);
	aa_scene_free(sc);
}

/* Blended parts are drawn farthest first: where the green quad (in front, first in the file) overlaps
 * the red one (behind), green goes over red over the backdrop. */
static void test_blend_order(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("blend-order.gltf", 0.5f, NULL, NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	float red[3] = {lit(0.5f, 1), lit(0.5f, 0), lit(0.5f, 0)}, green[3] = {lit(0.5f, 0), lit(0.5f, 1), lit(0.5f, 0)};
	float back[3] = {BACKDROP}, want[3];
	for (int k = 0; k < 3; k++)
		want[k] = 0.5f * green[k] + 0.5f * (0.5f * red[k] + 0.5f * back[k]);
	expect_color(&c, "green over red", 0, 0, want[0], want[1], want[2], 0.01f);
	check_golden("blend-order", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* Both quads face away: the double-sided one is seen from behind, the single-sided one is culled. */
static void test_double_sided(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("double-sided.gltf", 0.5f, NULL, NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	expect_color(&c, "double-sided", -0.6f, 0, lit(0.5f, 0.9f), lit(0.5f, 0.6f), lit(0.5f, 0.1f), 0.01f);
	expect_color(&c, "single-sided, culled", 0.6f, 0, BACKDROP, 1e-3f);
	check_golden("double-sided", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* KHR_texture_transform, offset (0.5, 0.5) and 90 degrees: the quadrants red, green / blue, white come out
 * green, white / red, blue. */
static void test_texture_transform(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("texture-transform.gltf", 0.5f, NULL, NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	float on = lit(0.5f, 1), off = lit(0.5f, 0);
	expect_color(&c, "plain top left", -0.85f, 0.25f, on, off, off, 0.01f);
	expect_color(&c, "moved top left", 0.35f, 0.25f, off, on, off, 0.01f);
	expect_color(&c, "moved top right", 0.85f, 0.25f, on, on, on, 0.01f);
	expect_color(&c, "moved bottom left", 0.35f, -0.25f, on, off, off, 0.01f);
	expect_color(&c, "moved bottom right", 0.85f, -0.25f, off, off, on, 0.01f);
	check_golden("texture-transform", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* GGX metallic-roughness under a light: a metal reflects no diffuse light, and a metal-rough map's
 * quadrants follow its channels (blue metalness, green roughness); the occlusion map darkens ambient. */
static void test_metallic_roughness(void **state)
{
	(void)state;
	struct aa_scene *sc = feature_scene("metallic-roughness.gltf", 0.3f,
					    "{\"type\": \"directional\", \"direction\": [0.3, -0.2, -1]}", NULL);
	struct capture c;
	render_reference(sc, 0, 8, &c);
	const float *rough = at(&c, -1.1f, -0.3f), *metal = at(&c, 0.0f, -0.3f);
	const float *map_dielectric = at(&c, 1.35f, -0.25f), *map_metal = at(&c, 0.85f, 0.25f);
	/* the rough dielectric is lit like a Lambert surface; the metal, away from its highlight, is darker */
	assert_true(rough[0] > 0.4f && metal[2] < rough[2]);
	assert_true(map_metal[0] < map_dielectric[0]);
	check_golden("metallic-roughness", &c);
	capture_free(&c);
	aa_scene_free(sc);
}

/* The skinned bar: where its joints put it (not where the skinned mesh's own node would, 100 units off);
 * at clip time 1 its top half lies to the left. */
static void test_skin_pose(void **state)
{
	(void)state;
	static const char *const poses[] = {"", ", \"animation\": {\"clip\": \"bend\", \"time\": 1, \"speed\": 0}"};
	for (int p = 0; p < 2; p++) {
		char json[1024];
		snprintf(json, sizeof json,
			 "{\"ambient\": [0.5, 0.5, 0.5], \"background\": [0.2, 0.3, 0.4],"
			 " \"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"skin.gltf\"}%s}],"
			 " \"camera\": {\"position\": [0, 1, 5], \"target\": [0, 1, 0], \"projection\": \"orthographic\","
			 " \"ortho_height\": %g}}", poses[p], ORTHO_HEIGHT);
		struct aa_scene *sc = load_scene(json);
		struct capture c;
		render_reference(sc, 0, 4, &c);
		float bar[3] = {lit(0.5f, 0.8f), lit(0.5f, 0.5f), lit(0.5f, 0.2f)};
		/* world y is 1 at the image centre here */
		const float *top = at(&c, 0, 0.7f), *left = at(&c, -0.7f, 0), *bottom = at(&c, 0, -0.5f);
		bool top_covered = fabsf(top[0] - bar[0]) < 0.02f, left_covered = fabsf(left[0] - bar[0]) < 0.02f;
		assert_true(fabsf(bottom[0] - bar[0]) < 0.02f); /* the lower half never moves */
		if (p == 0 ? !(top_covered && !left_covered) : !(left_covered && !top_covered))
			fail_msg("%s pose: top %.3f, left %.3f (bar %.3f)", p ? "bent" : "rest", top[0], left[0], bar[0]);
		check_golden(p ? "skin-bent" : "skin-rest", &c);
		capture_free(&c);
		aa_scene_free(sc);
	}
}

static float half_to_float(uint16_t h)
{
	int e = (h >> 10) & 0x1f, m = h & 0x3ff;
	float v = e == 0 ? ldexpf((float)m, -24) : e == 31 ? INFINITY : ldexpf((float)(m | 0x400), e - 25);
	return h & 0x8000 ? -v : v;
}

/* The velocity pass follows the joints: between clip times 0.5 and 0.6 the bar's top swings left and
 * down, its lower half stays. Read from the G-buffer's velocity target (the renderer, no method). */
static void test_skin_velocity(void **state)
{
	(void)state;
	struct aa_scene *sc = load_scene(
		"{\"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"skin.gltf\"},"
		" \"animation\": {\"clip\": \"bend\", \"time\": 0.5, \"speed\": 1}}],"
		" \"camera\": {\"position\": [0, 1, 5], \"target\": [0, 1, 0], \"projection\": \"orthographic\","
		" \"ortho_height\": 2.25}}");
	static const char *const taa[] = {"taa"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "assets", taa, 1, W, H, 1, 2);
	struct aa_frame_plan plan;
	aa_frame_plan_build(sc, &spec, &plan);
	assert_true(plan.velocity);
	struct aa_error err = {0};
	struct aa_gpu *gpu = &fixture_engine->gpu;
	struct aa_scene_upload *up = aa_engine_scene_upload(fixture_engine, sc, &err);
	struct aa_renderer *r = NULL;
	if (!up || aa_renderer_create(gpu, sc, up, &plan, W, H, &r, &err))
		fail_msg("%s", err.message);
	struct aa_scene_target target;
	struct aa_scene_target_desc desc = {.samples = 1, .outputs = AA_OUT_VELOCITY};
	struct aa_gpu_image copy = {0};
	struct aa_fullscreen_pass pass;
	struct aa_fullscreen_desc fd = {.frag = "copy.frag", .source_count = 1, .target = &copy};
	if (aa_scene_target_create_desc(r, &target, W, H, &desc, "velocity test", NULL, &err) ||
	    aa_renderer_image_create(r, &copy, W, H, VK_FORMAT_R16G16B16A16_SFLOAT,
				     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
				     VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "copy", NULL, &err))
		fail_msg("%s", err.message);
	fd.sources[0] = &target.extra[0];
	if (aa_fullscreen_pass_create(r, &pass, &fd, &err))
		fail_msg("%s", err.message);
	struct aa_camera cam;
	bool cut;
	aa_camera_path_eval(&sc->paths[0], false, -1, 0.1, &cam, &cut);
	struct aa_frame_ctx ctx = {0};
	aa_renderer_set_frame(r, &cam, 0.1, &cam, 0.0, &ctx); /* clip times 0.6, and 0.5 the frame before */
	VkCommandBuffer cmd;
	struct aa_gpu_buffer readback = {0};
	if (aa_gpu_begin(gpu, &cmd, &err))
		fail_msg("%s", err.message);
	aa_renderer_draw_scene(r, cmd, &target, 0, 0);
	aa_fullscreen_pass_record(r, cmd, &pass, NULL, 0);
	if (aa_gpu_record_readback(gpu, cmd, &copy, &readback, &err) || aa_gpu_submit_wait(gpu, cmd, &err))
		fail_msg("%s", err.message);
	const uint16_t *v = readback.mapped;
	float ppu = (float)H / ORTHO_HEIGHT;
	/* the top end (y = 2 at rest): at clip time 0.6, 54 degrees around (0, 1); 0.1 s before at 45 */
	float a0 = 0.5f * 1.5707963f, a1 = 0.6f * 1.5707963f;
	float x1 = -sinf(a1) * 0.95f, y1 = 1.0f + cosf(a1) * 0.95f, x0 = -sinf(a0) * 0.95f, y0 = 1.0f + cosf(a0) * 0.95f;
	int px = (int)floorf(W / 2.0f + x1 * ppu), py = (int)floorf(H / 2.0f - (y1 - 1.0f) * ppu);
	const uint16_t *moving = &v[((size_t)py * W + px) * 4];
	float vx = half_to_float(moving[0]), vy = half_to_float(moving[1]);
	float want_x = (x1 - x0) * ppu, want_y = -(y1 - y0) * ppu; /* pixels, y down */
	if (fabsf(vx - want_x) > 0.5f || fabsf(vy - want_y) > 0.5f)
		fail_msg("velocity at the bar's top (%d, %d): (%.2f, %.2f) px, expected (%.2f, %.2f)", px, py, vx, vy,
			 want_x, want_y);
	/* y = 0.1, by the bottom ring: joint 0 holds it (the middle ring, half on joint 1, moves a little) */
	const uint16_t *still = &v[((size_t)(H / 2 + 36) * W + W / 2) * 4];
	if (!(fabsf(half_to_float(still[0])) < 0.1f && fabsf(half_to_float(still[1])) < 0.1f))
		fail_msg("velocity near the bar's foot: (%.3f, %.3f) px", half_to_float(still[0]), half_to_float(still[1]));
	aa_gpu_buffer_destroy(gpu, &readback);
	aa_fullscreen_pass_destroy(r, &pass);
	aa_gpu_image_destroy(gpu, &copy);
	aa_scene_target_destroy(r, &target);
	aa_renderer_destroy(r);
	aa_scene_free(sc);
}

/* Every feature with every method, two frames of the bending skin: finite, and no validation error
 * (MSAA, virtual samples, G-buffers, GBAA and the reference each compile their own variants). */
static void test_every_method(void **state)
{
	(void)state;
	static const char *const files[] = {"base-color.gltf", "vertex-colors.gltf", "emissive.gltf",
					    "normal-map.gltf", "alpha-modes.gltf", "blend-order.gltf", "double-sided.gltf",
					    "texture-transform.gltf", "metallic-roughness.gltf", "material.obj"};
	const char *methods[AA_MAX_METHODS];
	for (int i = 0; i < aa_method_count; i++)
		methods[i] = aa_methods[i]->name;
	char objects[2048] = "";
	for (size_t f = 0; f < sizeof files / sizeof files[0]; f++)
		snprintf(objects + strlen(objects), sizeof objects - strlen(objects),
			 "{\"mesh\": {\"type\": \"file\", \"path\": \"%s\"}, \"position\": [%g, %g, 0], \"scale\": 0.3},",
			 files[f], -1.8 + 0.9 * (double)(f % 5), 0.6 - 0.8 * (double)(f / 5));
	char json[4096];
	snprintf(json, sizeof json,
		 "{\"objects\": [%s {\"mesh\": {\"type\": \"file\", \"path\": \"skin.gltf\"}, \"position\": [1.6, -0.6, 0],"
		 " \"scale\": 0.3, \"animation\": {\"clip\": \"bend\", \"speed\": 2}}],"
		 " \"lights\": [{\"type\": \"directional\", \"direction\": [0.3, -1, -0.5], \"casts_shadow\": true}],"
		 " \"camera\": {\"position\": [0, 0, 4], \"target\": [0, 0, 0]}}", objects);
	struct aa_scene *sc = load_scene(json);
	struct aa_job_spec spec;
	fixture_spec(&spec, "assets", methods, aa_method_count, 64, 36, 2, 4);
	struct aa_job_result *r = fixture_run(&spec, sc, NULL, NULL);
	for (int f = 0; f < r->reference.frame_count; f++)
		assert_int_equal(r->reference.frames[f].nonfinite, 0);
	for (int m = 0; m < r->method_count; m++)
		for (int f = 0; f < r->methods[m].frame_count; f++)
			if (r->methods[m].frames[f].nonfinite)
				fail_msg("%s frame %d: %ld NaN/Inf", r->methods[m].label, f, r->methods[m].frames[f].nonfinite);
	bool blend = false;
	for (int i = 0; i < r->plan_count; i++)
		blend |= strcmp(r->plan[i].pass, "alpha-blend") == 0 && r->plan[i].ran;
	assert_true(blend);
	fixture_free(r);
	aa_scene_free(sc);
}

/* `horizon` with its sun casting shadows: the fences' shadows show in the reference. The map fitted to the
 * whole 400-unit scene darkened 92 pixels of 57,600 by 10/255 or more; fitted to the
 * view, the rails' and posts' shadows near the camera resolve. */
static int darker_pixels(const char *sun, bool shadows)
{
	char path[1200];
	snprintf(path, sizeof path, "%s/../../scenes/horizon.json", assets);
	json_error_t je;
	json_t *root = json_load_file(path, 0, &je);
	assert_non_null(root);
	json_t *light = json_array_get(json_object_get(root, "lights"), 0);
	json_object_set_new(light, "casts_shadow", json_boolean(shadows));
	if (sun)
		json_object_set_new(light, "direction", json_loads(sun, 0, &je));
	char *text = json_dumps(root, 0);
	json_decref(root);
	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	if (aa_scene_load_string(text, "horizon.json", NULL, &sc, &err))
		fail_msg("%s", err.message);
	free(text);
	static const char *const none[] = {"none"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "horizon", none, 1, 320, 180, 1, 16);
	struct capture c = {0};
	struct aa_job_result *r = fixture_run(&spec, sc, capture_reference, &c);
	fixture_free(r);
	aa_scene_free(sc);
	static uint8_t *lit_image;
	int count = 0;
	if (!shadows) {
		free(lit_image);
		lit_image = malloc((size_t)320 * 180 * 4);
		memcpy(lit_image, c.srgb.pixels, (size_t)320 * 180 * 4);
	} else {
		for (size_t i = 0; i < (size_t)320 * 180; i++) {
			int before = lit_image[i * 4] + lit_image[i * 4 + 1] + lit_image[i * 4 + 2];
			int after = c.srgb.pixels[i * 4] + c.srgb.pixels[i * 4 + 1] + c.srgb.pixels[i * 4 + 2];
			count += before - after >= 30; /* 10/255 on average over R, G, B */
		}
	}
	capture_free(&c);
	return count;
}

static void test_horizon_shadows(void **state)
{
	(void)state;
	darker_pixels(NULL, false);
	int own_sun = darker_pixels(NULL, true);
	darker_pixels("[-1.0, -0.5, 0.3]", false);
	int low_sun = darker_pixels("[-1.0, -0.5, 0.3]", true);
	printf("  horizon: %d pixels in shadow with its own sun, %d with a low sun\n", own_sun, low_sun);
	if (own_sun < 150 || low_sun < 350)
		fail_msg("horizon's shadows: %d and %d pixels darker by 10/255 (at least 150 and 350 expected)", own_sun,
			 low_sun);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_base_color),
		cmocka_unit_test(test_vertex_colors),
		cmocka_unit_test(test_emissive),
		cmocka_unit_test(test_normal_map),
		cmocka_unit_test(test_alpha_modes),
		cmocka_unit_test(test_blend_order),
		cmocka_unit_test(test_opaque_alpha),
		cmocka_unit_test(test_double_sided),
		cmocka_unit_test(test_texture_transform),
		cmocka_unit_test(test_metallic_roughness),
		cmocka_unit_test(test_skin_pose),
		cmocka_unit_test(test_skin_velocity),
		cmocka_unit_test(test_every_method),
		cmocka_unit_test(test_horizon_shadows),
	};
	return fixture_status(cmocka_run_group_tests(tests, setup, fixture_teardown));
}

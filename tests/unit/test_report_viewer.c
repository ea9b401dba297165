/* report.html's parts on hand-made results: the verdict and warnings panel (escaped, and absent warnings),
 * the viewer's JSON data (escaped so no label ends the script), viewer/NNNN.js (the frame's PNG bytes
 * as data: URLs), the worst regions read back from FLIP maps, and the EXR of a frame event. */
#include <ftw.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "image/image.h"
#include "metrics/flip.h"
#include "results/results.h"
#include "report/report.h"
#include "run/job_spec.h"

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
	(void)st;
	(void)flag;
	(void)ftw;
	return remove(path);
}

static char *make_tmpdir(void)
{
	char *dir = strdup("/tmp/aalab-viewer-test.XXXXXX");
	assert_non_null(mkdtemp(dir));
	return dir;
}

static void remove_tree(const char *dir)
{
	nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

static char *read_all(const char *path, size_t *size)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return NULL;
	fseek(f, 0, SEEK_END);
	const long n = ftell(f);
	fseek(f, 0, SEEK_SET);
	char *buf = calloc(1, (size_t)n + 1);
	assert_int_equal(fread(buf, 1, (size_t)n, f), (size_t)n);
	fclose(f);
	if (size)
		*size = (size_t)n;
	return buf;
}

/* Two methods ("plain", and one whose label is markup), frames 10.., at 40x20. */
static struct aa_job_result *make_result(int frames)
{
	struct aa_job_result *r = calloc(1, sizeof *r);
	aa_job_spec_defaults(&r->spec);
	r->spec.frames = frames;
	r->spec.width = 40;
	r->spec.height = 20;
	r->spec.keep_frames = true;
	r->timestamp_period_ns = 1.0;
	r->fps = 24;
	r->reference.samples = 16;
	r->reference.frame_count = frames;
	r->reference.frames = calloc((size_t)frames, sizeof *r->reference.frames);
	for (int f = 0; f < frames; f++) {
		r->reference.frames[f].frame = 10 + f;
		r->reference.frames[f].convergence_mse = 0.01; /* 68 dB: converged */
	}
	r->method_count = 2;
	snprintf(r->methods[0].label, sizeof r->methods[0].label, "plain");
	snprintf(r->methods[1].label, sizeof r->methods[1].label, "</script><!--<script>x");
	for (int i = 0; i < 2; i++) {
		r->methods[i].frame_count = frames;
		r->methods[i].frames = calloc((size_t)frames, sizeof *r->methods[i].frames);
		for (int f = 0; f < frames; f++) {
			r->methods[i].frames[f].frame = 10 + f;
			r->methods[i].frames[f].metrics.psnr = i ? NAN : 30 + f;
			r->methods[i].frames[f].metrics.identical = i == 1;
			r->methods[i].frames[f].metrics.flip_mean = 0.1 * i;
		}
	}
	return r;
}

static void free_result(struct aa_job_result *r)
{
	aa_job_result_free(r);
	free(r);
}

static char *panel_of(const json_t *verdict, const json_t *warnings)
{
	char *buf = NULL;
	size_t size = 0;
	FILE *o = open_memstream(&buf, &size);
	aa_report_write_verdict(o, verdict, warnings);
	fclose(o);
	return buf;
}

/* The top of the page says the verdict and the warnings as results.json has them, escaped; no warnings,
 * no warnings panel. */
static void test_verdict_panel(void **state)
{
	(void)state;
	json_t *verdict = json_pack("{s:s, s:[s], s:{s:i}}", "headline", "front: plain, </script><!--<script>x",
				    "lines", "a & b: 1.00 dB less PSNR than <c>", "rule", "min_timed_renders", 5);
	json_t *none = json_array();
	char *html = panel_of(verdict, none);
	json_decref(none);
	assert_non_null(strstr(html, "<section id=\"verdict\""));
	assert_non_null(strstr(html, "<p class=\"headline\">front: plain, &lt;/script&gt;&lt;!--&lt;script&gt;x</p>"));
	assert_non_null(strstr(html, "<li>a &amp; b: 1.00 dB less PSNR than &lt;c&gt;</li>"));
	assert_non_null(strstr(html, "fewer than 5 timed renders"));
	assert_null(strstr(html, "id=\"warnings\""));
	assert_null(strstr(html, "</script>"));
	free(html);
	json_t *warnings = json_pack("[{s:s, s:s, s:s}]", "code", "scene", "message", "material <glass> approximated",
				     "action", "fix <it>");
	html = panel_of(verdict, warnings);
	assert_non_null(strstr(html, "<section id=\"warnings\""));
	assert_non_null(strstr(html, "<li><b>scene</b>: material &lt;glass&gt; approximated<br><span class=\"todo\">"
				     "What to do: fix &lt;it&gt;</span></li>"));
	free(html);
	json_decref(verdict);
	json_decref(warnings);
}

/* The JSON inside <script type="application/json" id="aa-viewer-data">. */
static json_t *viewer_json(const char *page)
{
	const char *start = strstr(page, "id=\"aa-viewer-data\">");
	assert_non_null(start);
	start = strchr(start, '>') + 1;
	const char *end = strstr(start, "</script>");
	assert_non_null(end);
	json_error_t jerr;
	json_t *j = json_loadb(start, (size_t)(end - start), 0, &jerr);
	if (!j)
		fail_msg("viewer data is not JSON: %s", jerr.text);
	return j;
}

static void test_viewer_data(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(3);
	char *dir = make_tmpdir(), *page = NULL;
	size_t size = 0;
	struct aa_error err = { 0 };
	FILE *o = open_memstream(&page, &size);
	assert_int_equal(aa_report_write_viewer(o, r, dir, &err), 0);
	fclose(o);
	/* the label cannot end the data element nor open a comment in it */
	assert_null(strstr(page, "</script><!--"));
	assert_null(strstr(page, "<!--<script>"));
	json_t *d = viewer_json(page);
	assert_int_equal(json_integer_value(json_object_get(d, "width")), 40);
	assert_int_equal(json_integer_value(json_object_get(d, "height")), 20);
	assert_true(json_real_value(json_object_get(d, "fps")) == 24.0);
	assert_true(json_is_true(json_object_get(d, "images")));
	json_t *frames = json_object_get(d, "frames"), *methods = json_object_get(d, "methods");
	assert_int_equal(json_array_size(frames), 3);
	assert_int_equal(json_integer_value(json_array_get(frames, 2)), 12);
	assert_string_equal(json_string_value(json_object_get(json_array_get(methods, 1), "label")), "</script><!--<script>x");
	assert_string_equal(json_string_value(json_object_get(json_array_get(methods, 1), "dir")), "__script___--_script_x");
	json_t *psnr0 = json_object_get(json_array_get(methods, 0), "psnr"), *psnr1 = json_object_get(json_array_get(methods, 1), "psnr");
	assert_true(json_real_value(json_array_get(psnr0, 1)) == 31.0);
	assert_true(json_is_null(json_array_get(psnr1, 0))); /* identical: no finite PSNR */
	assert_true(json_is_true(json_array_get(json_object_get(json_array_get(methods, 1), "identical"), 0)));
	/* magma as FLIP colours it: index 0 is (0, 0, 4), index 255 (252, 253, 191) */
	const char *magma = json_string_value(json_object_get(d, "magma"));
	assert_int_equal(strlen(magma), 256 * 6);
	assert_memory_equal(magma, "000004", 6);
	assert_memory_equal(magma + 255 * 6, "fcfdbf", 6);
	assert_int_equal(json_array_size(json_object_get(d, "regions")), 0); /* no FLIP maps in dir */
	json_decref(d);
	free(page);
	remove_tree(dir);
	free(dir);
	free_result(r);
}

static void write_png(const char *dir, const char *kind, const char *label, int ordinal, uint8_t value)
{
	uint8_t px[40 * 20 * 4];
	memset(px, value, sizeof px);
	const struct aa_image_rgba8 img = { .width = 40, .height = 20, .pixels = px };
	char rel[300];
	struct aa_error err = { 0 };
	aa_results_frame_relpath(kind, label, ordinal, rel, sizeof rel);
	assert_int_equal(aa_results_write_image(dir, rel, &img, &err), 0);
}

static char *decode_base64(const char *s, size_t n, size_t *out_n)
{
	static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	char *out = malloc(n), *w = out;
	unsigned acc = 0;
	int bits = 0;
	for (size_t i = 0; i < n && s[i] != '='; i++) {
		const char *p = strchr(b64, s[i]);
		assert_non_null(p);
		acc = acc << 6 | (unsigned)(p - b64);
		bits += 6;
		if (bits >= 8) {
			bits -= 8;
			*w++ = (char)(acc >> bits & 255);
		}
	}
	*out_n = (size_t)(w - out);
	return out;
}

static void test_viewer_frames(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(2);
	char *dir = make_tmpdir(), path[600];
	struct aa_error err = { 0 };
	for (int f = 0; f < 2; f++) {
		write_png(dir, "frames", "reference", f, (uint8_t)(10 + f));
		if (f == 1) { /* frame 1's reference is noise, some 20 KB of PNG: its payload spans many chunks */
			uint8_t noise[80 * 60 * 4];
			uint32_t x = 12345;
			for (size_t i = 0; i < sizeof noise; i++) {
				x = x * 1664525u + 1013904223u;
				noise[i] = (uint8_t)(x >> 24);
			}
			const struct aa_image_rgba8 img = { .width = 80, .height = 60, .pixels = noise };
			assert_int_equal(aa_results_write_image(dir, "frames/reference/0001.png", &img, &err), 0);
		}
		write_png(dir, "frames", r->methods[0].label, f, (uint8_t)(20 + f));
		write_png(dir, "flip", r->methods[0].label, f, 0);
		write_png(dir, "frames", r->methods[1].label, f, (uint8_t)(30 + f));
	}
	/* method 1 has no FLIP map: null in its place */
	assert_int_equal(aa_report_write_viewer_frames(r, dir, &err), 0);
	snprintf(path, sizeof path, "%s/viewer/0001.js", dir);
	char *js = read_all(path, NULL);
	assert_non_null(js);
	const char *prefix = "aalabFrame(1,{\"ref\":\"data:image/png;base64,";
	assert_memory_equal(js, prefix, strlen(prefix));
	assert_non_null(strstr(js, "\"flip\":[\"data:image/png;base64,"));
	assert_non_null(strstr(js, ",null]});\n"));
	/* the reference's payload is the PNG file, byte for byte */
	const char *b = js + strlen(prefix), *end = strchr(b, '"');
	size_t n, file_n;
	char *png = decode_base64(b, (size_t)(end - b), &n);
	snprintf(path, sizeof path, "%s/frames/reference/0001.png", dir);
	char *file = read_all(path, &file_n);
	assert_true(file_n > 10000);
	assert_int_equal(n, file_n);
	assert_memory_equal(png, file, n);
	free(png);
	free(file);
	free(js);
	snprintf(path, sizeof path, "%s/viewer/0002.js", dir);
	assert_int_equal(access(path, F_OK), -1); /* one script a frame, no more */

	/* without kept frames: no scripts */
	remove_tree(dir);
	free(dir);
	dir = make_tmpdir();
	r->spec.keep_frames = false;
	assert_int_equal(aa_report_write_viewer_frames(r, dir, &err), 0);
	snprintf(path, sizeof path, "%s/viewer", dir);
	assert_int_equal(access(path, F_OK), -1);
	remove_tree(dir);
	free(dir);
	free_result(r);
}

/* A FLIP map of 40x20 with value v in the rectangle, 0 elsewhere, as the engine writes it (magma). */
static void write_flip(const char *dir, const char *label, int ordinal, int x0, int y0, int x1, int y1, float v)
{
	float map[40 * 20] = { 0 };
	uint8_t px[40 * 20 * 4];
	for (int y = y0; y < y1; y++)
		for (int x = x0; x < x1; x++)
			map[y * 40 + x] = v;
	struct aa_image_rgba8 img = { .width = 40, .height = 20, .pixels = px };
	aa_flip_colorize(map, true, &img);
	char rel[300];
	struct aa_error err = { 0 };
	aa_results_frame_relpath("flip", label, ordinal, rel, sizeof rel);
	assert_int_equal(aa_results_write_image(dir, rel, &img, &err), 0);
}

static void test_worst_regions(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(3);
	char *dir = make_tmpdir();
	/* tiles of 16 over 40x20: 3 x 2, the last column 8 wide and the last row 4 high.
	 * method 0: tile (16, 0) at 0.8 in frame 1 only; tile (0, 0) at 0.2 in frames 0 and 2 (a tie: the
	 * region shows the first of them); method 1: the partial tile (32, 16) at 0.6 in frame 2 only */
	for (int f = 0; f < 3; f++) {
		if (f == 1)
			write_flip(dir, r->methods[0].label, f, 16, 0, 32, 16, 0.8f);
		else
			write_flip(dir, r->methods[0].label, f, 0, 0, 16, 16, 0.2f);
		if (f == 2)
			write_flip(dir, r->methods[1].label, f, 32, 16, 40, 20, 0.6f);
		else
			write_flip(dir, r->methods[1].label, f, 0, 0, 0, 0, 0.0f);
	}
	json_t *g = aa_report_worst_regions(r, dir, 16, 6);
	/* totals: (16,0) 0.8*256 = 204.8; (0,0) 0.2*256*2 = 102.4; (32,16) 0.6*32 = 19.2 */
	assert_int_equal(json_array_size(g), 3);
	const int want[3][5] = { { 16, 0, 16, 16, 1 }, { 0, 0, 16, 16, 0 }, { 32, 16, 8, 4, 2 } };
	const double mean[3] = { 0.8 * 256 / (256 * 6.0), 0.2 * 256 * 2 / (256 * 6.0), 0.6 * 32 / (32 * 6.0) };
	const char *const keys[5] = { "x", "y", "w", "h", "ordinal" };
	for (int k = 0; k < 3; k++) {
		json_t *e = json_array_get(g, (size_t)k);
		for (int i = 0; i < 5; i++)
			if (json_integer_value(json_object_get(e, keys[i])) != want[k][i])
				fail_msg("region %d: %s is %lld, want %d", k, keys[i],
					 (long long)json_integer_value(json_object_get(e, keys[i])), want[k][i]);
		/* the map stores int(255 v + 0.5) / 255 */
		assert_true(fabs(json_real_value(json_object_get(e, "flip_mean")) - mean[k]) < 1.0 / 510);
	}
	json_decref(g);
	g = aa_report_worst_regions(r, dir, 16, 1);
	assert_int_equal(json_array_size(g), 1);
	json_decref(g);

	/* a map missing: no regions rather than wrong ones */
	char path[600], rel[300];
	aa_results_frame_relpath("flip", r->methods[1].label, 1, rel, sizeof rel);
	snprintf(path, sizeof path, "%s/%s", dir, rel);
	assert_int_equal(unlink(path), 0);
	g = aa_report_worst_regions(r, dir, 16, 6);
	assert_int_equal(json_array_size(g), 0);
	json_decref(g);
	remove_tree(dir);
	free(dir);
	free_result(r);
}

/* Every one of the 256 magma colours is read back as its own index: a tile holding index i at its pixel
 * i sums to 0 + 1/255 + ... + 255/255 = 128; a colour read wrongly or not at all moves the mean. */
static void test_worst_regions_every_colour(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(1);
	char *dir = make_tmpdir();
	float map[40 * 20] = { 0 };
	for (int i = 0; i < 256; i++)
		map[(i / 16) * 40 + i % 16] = (float)i / 255.0f;
	uint8_t px[40 * 20 * 4];
	struct aa_image_rgba8 img = { .width = 40, .height = 20, .pixels = px };
	aa_flip_colorize(map, true, &img);
	char rel[300];
	struct aa_error err = { 0 };
	aa_results_frame_relpath("flip", r->methods[0].label, 0, rel, sizeof rel);
	assert_int_equal(aa_results_write_image(dir, rel, &img, &err), 0);
	write_flip(dir, r->methods[1].label, 0, 0, 0, 0, 0, 0.0f);
	json_t *g = aa_report_worst_regions(r, dir, 16, 1);
	assert_int_equal(json_array_size(g), 1);
	json_t *e = json_array_get(g, 0);
	assert_int_equal(json_integer_value(json_object_get(e, "x")), 0);
	assert_int_equal(json_integer_value(json_object_get(e, "y")), 0);
	/* 128 over 256 pixels, 2 methods, 1 frame */
	const double mean = json_real_value(json_object_get(e, "flip_mean"));
	if (fabs(mean - 0.25) > 1e-9)
		fail_msg("flip_mean %.12f, want 0.25", mean);
	json_decref(g);
	remove_tree(dir);
	free(dir);
	free_result(r);
}

/* More frames than the report reads at once (32): ordinals past the first chunk, and a tie across
 * chunks shown at its first frame. */
static void test_worst_regions_many_frames(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(40);
	char *dir = make_tmpdir();
	for (int f = 0; f < 40; f++) {
		if (f == 33)
			write_flip(dir, r->methods[0].label, f, 16, 0, 32, 16, 0.8f);
		else if (f == 5 || f == 37)
			write_flip(dir, r->methods[0].label, f, 0, 0, 16, 16, 0.2f);
		else
			write_flip(dir, r->methods[0].label, f, 0, 0, 0, 0, 0.0f);
		write_flip(dir, r->methods[1].label, f, 0, 0, 0, 0, 0.0f);
	}
	json_t *g = aa_report_worst_regions(r, dir, 16, 6);
	assert_int_equal(json_array_size(g), 2);
	const int want[2][3] = { { 16, 0, 33 }, { 0, 0, 5 } };
	for (int k = 0; k < 2; k++) {
		json_t *e = json_array_get(g, (size_t)k);
		if (json_integer_value(json_object_get(e, "x")) != want[k][0] ||
		    json_integer_value(json_object_get(e, "y")) != want[k][1] ||
		    json_integer_value(json_object_get(e, "ordinal")) != want[k][2])
			fail_msg("region %d at (%lld, %lld) frame %lld, want (%d, %d) frame %d", k,
				 (long long)json_integer_value(json_object_get(e, "x")),
				 (long long)json_integer_value(json_object_get(e, "y")),
				 (long long)json_integer_value(json_object_get(e, "ordinal")), want[k][0], want[k][1],
				 want[k][2]);
	}
	json_decref(g);
	remove_tree(dir);
	free(dir);
	free_result(r);
}

static void test_exr_event(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(1);
	char *dir = make_tmpdir(), path[600];
	struct aa_image_rgbaf lin;
	assert_int_equal(aa_image_rgbaf_alloc(&lin, 4, 2), 0);
	for (int i = 0; i < 4 * 2 * 4; i++)
		lin.pixels[i] = 0.25f * (float)(i % 4) + 2.0f * (i == 0); /* 2.0: over 1, kept as float */
	struct aa_event ev = { .type = AA_EVENT_METHOD_FRAME, .result = r, .method_index = 1, .frame_ordinal = 3,
			       .linear = &lin };
	struct aa_error err = { 0 };
	assert_int_equal(aa_results_write_event_exr(dir, &ev, &err), 0);
	snprintf(path, sizeof path, "%s/exr/__script___--_script_x/0003.exr", dir);
	struct aa_image_rgbaf back;
	int channels = 0;
	if (aa_image_read_rgbaf(path, &back, &channels, &err))
		fail_msg("reading the EXR back: %s", err.message);
	assert_int_equal(back.width, 4);
	assert_int_equal(back.height, 2);
	for (int i = 0; i < 4 * 2 * 4; i++)
		assert_true(fabsf(back.pixels[i] - lin.pixels[i]) < 1e-3f);
	aa_image_rgbaf_free(&back);
	ev.type = AA_EVENT_PROGRESS; /* other events write nothing */
	assert_int_equal(aa_results_write_event_exr(dir, &ev, &err), 0);
	aa_image_rgbaf_free(&lin);
	remove_tree(dir);
	free(dir);
	free_result(r);
}

/* The cost-accuracy chart's labels: 14 methods crowded within a few pixels (two at one point) each get
 * a label over no other label and no point, inside the plot, nearer its own point than any other's or
 * joined to it by a leader line ending on its box; a label with room stays beside its point. */
static void test_place_labels(void **state)
{
	(void)state;
	enum { N = 15 };
	struct aa_point_label l[N];
	double px[N], py[N];
	const double box[4] = { 60, 20, 700, 330 };
	for (int i = 0; i < N - 1; i++) {
		px[i] = 200 + 3 * i;
		py[i] = 150 + 2 * (i % 5);
		l[i] = (struct aa_point_label){ .x0 = 0, .x1 = 6.6 * (4 + i % 6) };
	}
	px[1] = px[0], py[1] = py[0]; /* fxaa and fxaa-cs: the same point */
	px[N - 1] = 600, py[N - 1] = 60; /* alone */
	l[N - 1] = (struct aa_point_label){ .x0 = 0, .x1 = 40 };
	aa_report_place_labels(l, px, py, N, box);
	for (int i = 0; i < N; i++) {
		assert_true(l[i].x0 >= box[0] && l[i].x1 <= box[2] && l[i].y0 >= box[1] && l[i].y1 <= box[3]);
		assert_true(l[i].y1 - l[i].y0 == AA_LABEL_HEIGHT);
		for (int j = 0; j < N; j++) {
			if (j != i)
				assert_false(l[i].x0 < l[j].x1 && l[j].x0 < l[i].x1 && l[i].y0 < l[j].y1 && l[j].y0 < l[i].y1);
			assert_false(l[i].x0 < px[j] + AA_LABEL_DOT && px[j] - AA_LABEL_DOT < l[i].x1 &&
				     l[i].y0 < py[j] + AA_LABEL_DOT && py[j] - AA_LABEL_DOT < l[i].y1);
		}
		if (l[i].leader) { /* the line ends on the box */
			assert_true(l[i].lx >= l[i].x0 && l[i].lx <= l[i].x1 && l[i].ly >= l[i].y0 && l[i].ly <= l[i].y1);
		} else {
			const double own = hypot(fmax(fmax(l[i].x0 - px[i], 0), px[i] - l[i].x1),
						 fmax(fmax(l[i].y0 - py[i], 0), py[i] - l[i].y1));
			assert_true(own <= AA_LABEL_DOT + 4);
		}
	}
	assert_false(l[N - 1].leader); /* room beside it */
	assert_true(l[N - 1].x0 >= px[N - 1]);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_verdict_panel),
		cmocka_unit_test(test_viewer_data),
		cmocka_unit_test(test_viewer_frames),
		cmocka_unit_test(test_worst_regions),
		cmocka_unit_test(test_worst_regions_every_colour),
		cmocka_unit_test(test_worst_regions_many_frames),
		cmocka_unit_test(test_exr_event),
		cmocka_unit_test(test_place_labels),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}

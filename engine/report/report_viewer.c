/* The report's image viewer: the page part (a JSON description of the job, viewer.css and viewer.js,
 * embedded at build time from engine/results/) and, beside report.html, one script per frame,
 * viewer/NNNN.js, carrying that frame's PNGs as data: URLs.
 *
 * Why scripts and not the PNGs themselves: a page opened from file:// may draw images from other files
 * but never read their pixels back (the canvas is tainted, and fetch() is refused), so the inspector,
 * the gained and signed differences and method-against-method could not work. A <script> loads from
 * file:// everywhere, and a data: URL image leaves the canvas readable. The PNGs stay the job's images;
 * the scripts are loaded only when their frame is shown (or played). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "metrics/flip.h"
#include "results/results.h"
#include "viewer_assets.h" /* aa_viewer_js, aa_viewer_css: generated from viewer.js and viewer.css */
#include "report/report.h"

/* Worst regions: 16-pixel tiles, shown at 8x (128 CSS pixels) side by side for every method. */
#define REGION_TILE 16
#define REGION_COUNT 6

static const char *const viewer_palette[] = { "#2563eb", "#dc2626", "#16a34a", "#ea580c", "#7c3aed",
					      "#0891b2", "#db2777", "#65a30d", "#92400e", "#475569" };

static json_t *number_or_null(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

/* The 256 colours of the FLIP map as hex "rrggbb...": the page turns a map's pixel back into its value. */
static json_t *magma_hex(void)
{
	float ramp[256];
	uint8_t px[256 * 4];
	struct aa_image_rgba8 img = { .width = 256, .height = 1, .pixels = px };
	for (int i = 0; i < 256; i++)
		ramp[i] = (float)i / 255.0f;
	aa_flip_colorize(ramp, true, &img);
	char hex[256 * 6 + 1];
	for (int i = 0; i < 256; i++)
		snprintf(hex + 6 * i, 7, "%02x%02x%02x", px[4 * i], px[4 * i + 1], px[4 * i + 2]);
	return json_string(hex);
}

static json_t *viewer_data(const struct aa_job_result *r, const char *dir)
{
	json_t *methods = json_array();
	for (int i = 0; i < r->method_count; i++) {
		const struct aa_method_result *m = &r->methods[i];
		char dir[AA_LABEL_MAX * 2];
		aa_label_dirname(m->label, dir, sizeof dir);
		json_t *psnr = json_array(), *identical = json_array(), *flip = json_array();
		for (int f = 0; f < m->frame_count; f++) {
			json_array_append_new(psnr, number_or_null(m->frames[f].metrics.psnr));
			json_array_append_new(identical, json_boolean(m->frames[f].metrics.identical));
			json_array_append_new(flip, number_or_null(m->frames[f].metrics.flip_mean));
		}
		json_array_append_new(methods, json_pack("{ss ss ss so so so}", "label", m->label, "dir", dir,
							 "color", viewer_palette[i % 10], "psnr", psnr,
							 "identical", identical, "flip", flip));
	}
	json_t *frames = json_array();
	const int frame_count = r->method_count > 0 ? r->methods[0].frame_count : r->reference.frame_count;
	for (int f = 0; f < frame_count; f++)
		json_array_append_new(frames, json_integer(r->method_count > 0 ? r->methods[0].frames[f].frame
									       : r->reference.frames[f].frame));
	const char *why = !r->spec.keep_frames || frame_count == 0
				  ? "No images: the job did not keep frames."
				  : "No viewer: the job left it out (viewer: false); the frames are the PNGs in frames/, diff/ "
				    "and flip/ beside this page.";
	return json_pack("{so si si sf sb ss si so so so}", "regions",
			 aa_report_worst_regions(r, dir, REGION_TILE, REGION_COUNT), "width", r->spec.width, "height", r->spec.height, "fps",
			 r->fps > 0 ? r->fps : 30.0, "images", r->spec.keep_frames && r->spec.viewer && frame_count > 0, "no_images", why,
			 "reference_samples", r->reference.samples, "frames", frames, "methods", methods,
			 "magma", magma_hex());
}

int aa_report_write_viewer(FILE *o, const struct aa_job_result *r, const char *dir, struct aa_error *err)
{
	json_t *data = viewer_data(r, dir);
	char *text = data ? json_dumps(data, JSON_COMPACT) : NULL;
	json_decref(data);
	if (!text)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing the report's viewer");
	fprintf(o, "<style>%s</style>\n<section id=\"viewer\" class=\"viewer\"><noscript><p class=\"note\">The "
		   "image viewer needs JavaScript; the images are in frames/, diff/ and flip/ beside this page."
		   "</p></noscript></section>\n<script type=\"application/json\" id=\"aa-viewer-data\">", aa_viewer_css);
	/* Every '<' (only ever inside a JSON string) as \u003c: no label can end the element ("</script") or
	 * switch the HTML tokenizer into a script's escaped states ("<!--"). */
	for (const char *p = text; *p; p++)
		if (*p == '<')
			fputs("\\u003c", o);
		else
			fputc(*p, o);
	fprintf(o, "</script>\n<script>%s</script>\n", aa_viewer_js);
	free(text);
	return 0;
}

/* Reads a whole file; NULL (and *size 0) when it cannot. */
static unsigned char *read_file(const char *path, size_t *size)
{
	*size = 0;
	FILE *f = fopen(path, "rb");
	if (!f)
		return NULL;
	unsigned char *buf = NULL;
	size_t cap = 0, n = 0;
	for (;;) {
		if (n == cap) {
			cap = cap ? cap * 2 : 65536;
			unsigned char *grown = realloc(buf, cap);
			if (!grown) {
				free(buf);
				fclose(f);
				return NULL;
			}
			buf = grown;
		}
		const size_t got = fread(buf + n, 1, cap - n, f);
		n += got;
		if (got == 0)
			break;
	}
	const bool failed = ferror(f);
	fclose(f);
	if (failed) {
		free(buf);
		return NULL;
	}
	*size = n;
	return buf;
}

/* Encoded a chunk at a time into a buffer and written with one fwrite each: a frame's scripts carry
 * megabytes, which a putc per character makes a visible part of writing the report. */
static void put_base64(FILE *o, const unsigned char *s, size_t n)
{
	static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	char chunk[4096];
	size_t used = 0;
	for (size_t i = 0; i < n; i += 3) {
		const unsigned v = (unsigned)s[i] << 16 | (i + 1 < n ? (unsigned)s[i + 1] << 8 : 0) |
				   (i + 2 < n ? s[i + 2] : 0);
		chunk[used++] = b64[v >> 18 & 63];
		chunk[used++] = b64[v >> 12 & 63];
		chunk[used++] = i + 1 < n ? b64[v >> 6 & 63] : '=';
		chunk[used++] = i + 2 < n ? b64[v & 63] : '=';
		if (used == sizeof chunk) {
			fwrite(chunk, 1, used, o);
			used = 0;
		}
	}
	fwrite(chunk, 1, used, o);
}

/* One image of the frame as a quoted data: URL, or null when its file is missing. */
static void put_image(FILE *o, const char *dir, const char *rel)
{
	char path[4096];
	size_t n = 0;
	unsigned char *png = NULL;
	if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, rel) < sizeof path)
		png = read_file(path, &n);
	if (!png) {
		fputs("null", o);
		return;
	}
	fputs("\"data:image/png;base64,", o);
	put_base64(o, png, n);
	fputc('"', o);
	free(png);
}

int aa_report_write_viewer_frames(const struct aa_job_result *r, const char *dir, struct aa_error *err)
{
	const int frame_count = r->method_count > 0 ? r->methods[0].frame_count : 0;
	if (!r->spec.keep_frames || !r->spec.viewer || frame_count == 0)
		return 0;
	char sub[4096];
	if ((size_t)snprintf(sub, sizeof sub, "%s/viewer", dir) >= sizeof sub)
		return aa_error_set(err, AA_ERR_IO, "", "path %s/viewer is too long", dir);
	if (mkdir(sub, 0755) < 0 && errno != EEXIST)
		return aa_error_set(err, AA_ERR_IO, "", "cannot create directory %s: %s", sub, strerror(errno));
	for (int f = 0; f < frame_count; f++) {
		char *buf = NULL, rel[600], name[32];
		size_t size = 0;
		FILE *o = open_memstream(&buf, &size);
		if (!o)
			return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing viewer/%04d.js", f);
		/* aalabFrame(ordinal, {ref, method images, FLIP maps}) in job order; viewer.js defines it */
		fprintf(o, "aalabFrame(%d,{\"ref\":", f);
		aa_results_frame_relpath("frames", "reference", f, rel, sizeof rel);
		put_image(o, dir, rel);
		for (int k = 0; k < 2; k++) {
			fputs(k ? "],\"flip\":[" : ",\"m\":[", o);
			for (int i = 0; i < r->method_count; i++) {
				if (i)
					fputc(',', o);
				aa_results_frame_relpath(k ? "flip" : "frames", r->methods[i].label, f, rel, sizeof rel);
				put_image(o, dir, rel);
			}
		}
		fputs("]});\n", o);
		if (fclose(o) != 0 || !buf) {
			free(buf);
			return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing viewer/%04d.js", f);
		}
		snprintf(name, sizeof name, "%04d.js", f);
		const int rc = aa_results_write_file_atomic(sub, name, buf, size, err);
		free(buf);
		if (rc)
			return rc;
	}
	return 0;
}

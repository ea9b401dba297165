/* The layout of a job directory: where each method's frames and diff images go, and writing them. */
#include <errno.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "results/results.h"
#include "util/file_io.h"

void aa_results_frame_relpath(const char *kind, const char *label, int ordinal, char *out, size_t size)
{
	char dirname[AA_LABEL_MAX * 2];
	aa_label_dirname(label, dirname, sizeof dirname);
	snprintf(out, size, "%s/%s/%04d.png", kind, dirname, ordinal);
}

void aa_results_linear_relpath(const char *label, int ordinal, char *out, size_t size)
{
	char dirname[AA_LABEL_MAX * 2];
	aa_label_dirname(label, dirname, sizeof dirname);
	snprintf(out, size, "linear/%s/%04d.rgba16f", dirname, ordinal);
}

int aa_results_make_parents(char *path, struct aa_error *err)
{
	return aa_file_make_parents(path, err);
}

/* True when a component of path is "..". */
static bool has_dotdot(const char *path)
{
	for (const char *p = path; (p = strstr(p, "..")) != NULL; p += 2)
		if ((p == path || p[-1] == '/') && (p[2] == '\0' || p[2] == '/'))
			return true;
	return false;
}

int aa_results_write_image(const char *dir, const char *relpath, const struct aa_image_rgba8 *img,
			   struct aa_error *err)
{
	/* relpath comes from aa_results_frame_relpath; refuse anything that could leave dir. */
	if (!relpath || !*relpath || relpath[0] == '/' || has_dotdot(relpath) || !dir || !*dir)
		return aa_error_set(err, AA_ERR_INVALID, "", "image path \"%s\" is not a path inside the job directory",
				    relpath ? relpath : "");
	char path[4096];
	if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, relpath) >= sizeof path)
		return aa_error_set(err, AA_ERR_IO, "", "image path %s/%s is too long", dir, relpath);
	if (aa_results_make_parents(path, err) < 0)
		return -1;
	return aa_image_write_png(path, img, err);
}

/* Raw RGBA16F, rows top to bottom, little-endian IEEE halves: what a watcher asking for rgba16f gets. */
static int write_linear(const char *dir, const char *label, int ordinal, const struct aa_image_rgbaf *img,
			struct aa_error *err)
{
	char rel[AA_LABEL_MAX * 2 + 32], path[4096];
	aa_results_linear_relpath(label, ordinal, rel, sizeof rel);
	if (snprintf(path, sizeof path, "%s/%s", dir, rel) >= (int)sizeof path)
		return aa_error_set(err, AA_ERR_IO, "", "path %s/%s is too long", dir, rel);
	if (aa_results_make_parents(path, err) < 0)
		return -1;
	size_t n = (size_t)img->width * img->height * 4;
	uint16_t *half = malloc(n * sizeof *half);
	if (!half)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	for (size_t i = 0; i < n; i++)
		half[i] = aa_float_to_half(img->pixels[i]);
	FILE *f = fopen(path, "wb");
	bool ok = f && fwrite(half, sizeof *half, n, f) == n;
	if (f && fclose(f) != 0)
		ok = false;
	free(half);
	return ok ? 0 : aa_error_set(err, AA_ERR_IO, "", "cannot write %s: %s", path, strerror(errno));
}

struct image_write {
	const char *dir;
	const struct aa_image_rgba8 *img;
	char rel[AA_LABEL_MAX * 2 + 32];
	int rc;
	struct aa_error err;
};

static void *image_write_main(void *arg)
{
	struct image_write *w = arg;
	w->rc = aa_results_write_image(w->dir, w->rel, w->img, &w->err);
	return NULL;
}

int aa_results_write_event_images(const char *dir, const struct aa_event *ev, struct aa_error *err)
{
	char rel[AA_LABEL_MAX * 2 + 32];
	bool linear = ev->result && ev->result->spec.linear_frames && ev->linear;
	if (ev->result && ev->result->spec.exr_frames && aa_results_write_event_exr(dir, ev, err))
		return -1;
	if (ev->type == AA_EVENT_REFERENCE_FRAME) {
		aa_results_frame_relpath("frames", "reference", ev->frame_ordinal, rel, sizeof rel);
		if (linear && write_linear(dir, "reference", ev->frame_ordinal, ev->linear, err))
			return -1;
		return aa_results_write_image(dir, rel, ev->image, err);
	}
	if (ev->type != AA_EVENT_METHOD_FRAME)
		return 0;
	const char *label = ev->result->methods[ev->method_index].label;
	if (linear && write_linear(dir, label, ev->frame_ordinal, ev->linear, err))
		return -1;
	/* the frame, its difference and its FLIP map are encoded at once, each on a thread (PNG encoding is
	 * most of what writing them costs) */
	struct image_write w[3] = {{.dir = dir, .img = ev->image}, {.dir = dir, .img = ev->diff},
				   {.dir = dir, .img = ev->flip_map}};
	static const char *const kinds[3] = {"frames", "diff", "flip"};
	pthread_t threads[3];
	bool started[3] = {false, false, false};
	for (int k = 0; k < 3; k++) {
		if (!w[k].img)
			continue;
		aa_results_frame_relpath(kinds[k], label, ev->frame_ordinal, w[k].rel, sizeof w[k].rel);
		started[k] = k > 0 && pthread_create(&threads[k], NULL, image_write_main, &w[k]) == 0;
		if (!started[k])
			image_write_main(&w[k]);
	}
	int rc = 0;
	for (int k = 0; k < 3; k++) {
		if (started[k])
			pthread_join(threads[k], NULL);
		if (w[k].img && w[k].rc && rc == 0) {
			*err = w[k].err;
			rc = -1;
		}
	}
	return rc;
}

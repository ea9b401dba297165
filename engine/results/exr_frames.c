/* exr/<method dir>/NNNN.exr: a frame's linear colour as float EXR (job field exr_frames, aalab run --exr),
 * for oiiotool, idiff and tev, which read linear floats and not the 8-bit sRGB PNGs. */
#include <stdbool.h>
#include <stdio.h>

#include "image/image.h"
#include "results/results.h"

void aa_results_exr_relpath(const char *label, int ordinal, char *out, size_t size)
{
	char dirname[AA_LABEL_MAX * 2];
	aa_label_dirname(label, dirname, sizeof dirname);
	snprintf(out, size, "exr/%s/%04d.exr", dirname, ordinal);
}

int aa_results_write_event_exr(const char *dir, const struct aa_event *ev, struct aa_error *err)
{
	if (!ev->linear || !ev->result || (ev->type != AA_EVENT_REFERENCE_FRAME && ev->type != AA_EVENT_METHOD_FRAME))
		return 0;
	const char *label = ev->type == AA_EVENT_REFERENCE_FRAME ? "reference" : ev->result->methods[ev->method_index].label;
	char rel[AA_LABEL_MAX * 2 + 32], path[4096];
	aa_results_exr_relpath(label, ev->frame_ordinal, rel, sizeof rel);
	if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, rel) >= sizeof path)
		return aa_error_set(err, AA_ERR_IO, "", "path %s/%s is too long", dir, rel);
	if (aa_results_make_parents(path, err))
		return -1;
	return aa_image_write_rgbaf(path, ev->linear, err);
}

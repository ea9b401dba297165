/* reference.samples "auto": a reference that measures its own error and stops when it is small enough.
 * The sample points are nested, so doubling N adds N new renders to the running sum and the old N-sample
 * image becomes the new N/2 one: reaching N costs N renders, as a fixed N does. With a store, each level
 * reached is stored with its running sum, so that a later run with a higher target goes on from it. */
#include <stdlib.h>
#include <string.h>

#include "metrics/metrics.h"
#include "reference/reference.h"
#include "reference/reference_store.h"

static bool converged(const struct aa_metrics *m, double target_psnr)
{
	return m->identical || m->psnr >= target_psnr;
}

int aa_reference_render_auto(struct aa_reference *ref, struct aa_gpu_timer *timer, double target_psnr,
			     struct aa_image_rgbaf *full, struct aa_image_rgbaf *half, struct aa_image_rgba8 *full8,
			     struct aa_image_rgba8 *half8, int *samples, struct aa_metrics *conv, double *gpu_ms,
			     double *cpu_ms, struct aa_reference_store *store, struct aa_error *err)
{
	int n = ref->samples < AA_REFERENCE_AUTO_START ? ref->samples : AA_REFERENCE_AUTO_START;
	double gpu = 0, cpu = 0, g = 0, c = 0;
	/* A level from the store is its running sum; the GPU's sum holds on_gpu renders of this frame. When
	 * a level is not stored, the GPU goes on from the last one (put back on the GPU if it came from the
	 * store), so the additions happen in the order of an uninterrupted run and give its bits. */
	float *sum = NULL, *half_sum = NULL;
	int on_gpu = 0, rc = -1;
	if (store && aa_reference_store_load_level(store, ref, n, &sum, &half_sum, &g, &c)) {
		aa_reference_average(half_sum, n / 2, half);
		aa_reference_average(sum, n, full);
		free(half_sum);
	} else {
		if (aa_reference_render_count(ref, timer, n, full, half, &g, &c, err))
			return -1;
		on_gpu = n;
		if (store)
			aa_reference_store_save_level(store, ref, n, g, c);
	}
	gpu += g;
	cpu += c;
	for (;;) {
		aa_image_encode_srgb8(full, full8);
		aa_image_encode_srgb8(half, half8);
		if (aa_metrics_compare_pixels(full8, half8, conv, err))
			goto out;
		if (converged(conv, target_psnr) || n >= ref->samples)
			break;
		const int next = 2 * n <= ref->samples ? 2 * n : ref->samples;
		memcpy(half->pixels, full->pixels, (size_t)full->width * full->height * 4 * sizeof *full->pixels);
		float *next_sum = NULL, *unused = NULL;
		if (store && aa_reference_store_load_level(store, ref, next, &next_sum, &unused, &g, &c)) {
			aa_reference_average(next_sum, next, full);
			free(sum);
			sum = next_sum;
		} else {
			if (on_gpu != n && aa_reference_resume(ref, sum, n, err))
				goto out;
			if (aa_reference_extend(ref, timer, n, next, full, &g, &c, err))
				goto out;
			on_gpu = next;
			free(sum);
			sum = NULL;
			if (store)
				aa_reference_store_save_level(store, ref, next, g, c);
		}
		gpu += g;
		cpu += c;
		n = next;
	}
	*samples = n;
	*gpu_ms = gpu;
	*cpu_ms = cpu;
	rc = 0;
out:
	free(sum);
	return rc;
}

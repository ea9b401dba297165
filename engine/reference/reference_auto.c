/* reference.samples "auto": a reference that measures its own error and stops when it is small enough.
 * The Halton points are nested, so doubling N adds N new renders to the running sum and the old N-sample
 * image becomes the new N/2 one: reaching N costs N renders, as a fixed N does. */
#include <string.h>

#include "metrics/metrics.h"
#include "reference/reference.h"

static bool converged(const struct aa_metrics *m, double target_psnr)
{
	return m->identical || m->psnr >= target_psnr;
}

int aa_reference_render_auto(struct aa_reference *ref, struct aa_gpu_timer *timer, double target_psnr,
			     struct aa_image_rgbaf *full, struct aa_image_rgbaf *half, struct aa_image_rgba8 *full8,
			     struct aa_image_rgba8 *half8, int *samples, struct aa_metrics *conv, double *gpu_ms,
			     double *cpu_ms, struct aa_error *err)
{
	int n = ref->samples < AA_REFERENCE_AUTO_START ? ref->samples : AA_REFERENCE_AUTO_START;
	double gpu = 0, cpu = 0;
	if (aa_reference_render_count(ref, timer, n, full, half, &gpu, &cpu, err))
		return -1;
	for (;;) {
		aa_image_encode_srgb8(full, full8);
		aa_image_encode_srgb8(half, half8);
		if (aa_metrics_compare(full8, half8, conv, err))
			return -1;
		if (converged(conv, target_psnr) || n >= ref->samples)
			break;
		const int next = 2 * n <= ref->samples ? 2 * n : ref->samples;
		memcpy(half->pixels, full->pixels, (size_t)full->width * full->height * 4 * sizeof *full->pixels);
		double g = 0, c = 0;
		if (aa_reference_extend(ref, timer, n, next, full, &g, &c, err))
			return -1;
		gpu += g;
		cpu += c;
		n = next;
	}
	*samples = n;
	*gpu_ms = gpu;
	*cpu_ms = cpu;
	return 0;
}

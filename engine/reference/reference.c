/* Reference accumulation: jittered renders summed in RGBA32F, read back at N/2 and N samples. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "reference.h"

double aa_halton(unsigned index, unsigned base)
{
	double f = 1.0, r = 0.0;
	while (index > 0) {
		f /= base;
		r += f * (index % base);
		index /= base;
	}
	return r;
}

void aa_reference_offsets(int n, float (*out)[2])
{
	/* Starting at 1 skips the (0,0) point, so every sample is a distinct point of the pixel square. */
	for (int i = 0; i < n; i++) {
		out[i][0] = (float)(aa_halton((unsigned)i + 1, 2) - 0.5);
		out[i][1] = (float)(aa_halton((unsigned)i + 1, 3) - 0.5);
	}
}

int aa_reference_create(struct aa_renderer *r, int samples, struct aa_reference *ref, struct aa_error *err)
{
	memset(ref, 0, sizeof *ref);
	ref->r = r;
	ref->samples = samples;
	ref->offsets = calloc((size_t)samples, sizeof *ref->offsets);
	if (!ref->offsets)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	aa_reference_offsets(samples, ref->offsets);
	/* each of the N samples stands for 1/N of the pixel: textures are read log2(sqrt(N)) mip levels finer,
	 * so the accumulation converges to the box-filtered texture, not to trilinear blur */
	struct aa_scene_target_desc desc = {.samples = 1, .texture_lod_bias = -0.5f * log2f((float)samples)};
	/* summed with weight 1 and divided at readback, so N/2 and N share the sum */
	if (aa_sample_accumulator_create(r, &desc, samples, 1.0f, "reference", NULL, &ref->sum, err))
		return -1;
	ref->memory_bytes = ref->sum.memory_bytes;
	return 0;
}

void aa_reference_destroy(struct aa_reference *ref)
{
	if (!ref->r)
		return;
	aa_sample_accumulator_destroy(&ref->sum);
	aa_gpu_buffer_destroy(ref->r->gpu, &ref->readback);
	aa_gpu_buffer_destroy(ref->r->gpu, &ref->readback_half);
	free(ref->offsets);
	memset(ref, 0, sizeof *ref);
}

static void read_average(const struct aa_gpu_buffer *sum_buffer, int count, struct aa_image_rgbaf *out)
{
	const float *sum = sum_buffer->mapped;
	size_t n = (size_t)out->width * out->height * 4;
	float scale = 1.0f / (float)count;
	for (size_t i = 0; i < n; i++)
		out->pixels[i] = sum[i] * scale;
}

int aa_reference_render(struct aa_reference *ref, struct aa_gpu_timer *timer, struct aa_image_rgbaf *full,
			struct aa_image_rgbaf *half, double *gpu_ms, double *cpu_ms, struct aa_error *err)
{
	double t0 = aa_now_ms();
	*gpu_ms = 0;
	struct aa_renderer *r = ref->r;
	int mid = ref->samples / 2;
	VkCommandBuffer cmd;
	if (aa_gpu_begin(r->gpu, &cmd, err))
		return -1;
	/* one submission: the sum of the first N/2 renders is copied out on the way (outside the timed
	 * spans), then the rest are added to it */
	aa_gpu_timer_reset(cmd, timer);
	int span = aa_gpu_timer_begin(cmd, timer, "reference");
	aa_renderer_record_shadow(r, cmd);
	aa_sample_accumulator_clear(&ref->sum, cmd);
	for (int i = 0; i < mid; i++)
		aa_sample_accumulator_render(&ref->sum, cmd, ref->offsets[i][0], ref->offsets[i][1]);
	struct aa_gpu_image *sum = aa_sample_accumulator_sum(&ref->sum, cmd);
	aa_gpu_timer_end(cmd, timer, span);
	if (aa_gpu_record_readback(r->gpu, cmd, sum, &ref->readback_half, err)) {
		aa_gpu_submit_wait(r->gpu, cmd, NULL);
		return -1;
	}
	span = aa_gpu_timer_begin(cmd, timer, "reference");
	for (int i = mid; i < ref->samples; i++)
		aa_sample_accumulator_render(&ref->sum, cmd, ref->offsets[i][0], ref->offsets[i][1]);
	sum = aa_sample_accumulator_sum(&ref->sum, cmd);
	aa_gpu_timer_end(cmd, timer, span);
	if (aa_gpu_record_readback(r->gpu, cmd, sum, &ref->readback, err)) {
		aa_gpu_submit_wait(r->gpu, cmd, NULL);
		return -1;
	}
	if (aa_gpu_submit_wait(r->gpu, cmd, err))
		return -1;
	double ms[2] = {0, 0};
	if (aa_gpu_timer_read(r->gpu, timer, ms, err))
		return -1;
	*gpu_ms = ms[0] + ms[1];
	read_average(&ref->readback_half, mid, half);
	read_average(&ref->readback, ref->samples, full);
	*cpu_ms = aa_now_ms() - t0;
	return 0;
}

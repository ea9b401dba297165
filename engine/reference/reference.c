/* Reference accumulation: jittered renders summed in RGBA32F, read back at N/2 and N samples. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "reference/owen_sobol.h"
#include "reference/reference.h"

void aa_reference_offsets(int n, float (*out)[2])
{
	/* Owen-scrambled Sobol' points from index 0 (scrambling moves it off the pixel's corner): a sequence
	 * no method samples with (owen_sobol.h), nested, and stratified at every power of two. */
	for (int i = 0; i < n; i++) {
		float p[2];
		aa_owen_sobol_2d((uint32_t)i, p);
		out[i][0] = p[0] - 0.5f;
		out[i][1] = p[1] - 0.5f;
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
	ref->lod_bias = desc.texture_lod_bias;
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
	aa_reference_average(sum_buffer->mapped, count, out);
}

void aa_reference_average(const float *sum, int count, struct aa_image_rgbaf *out)
{
	size_t n = (size_t)out->width * out->height * 4;
	float scale = 1.0f / (float)count;
	for (size_t i = 0; i < n; i++)
		out->pixels[i] = sum[i] * scale;
}

/* Renders one submission holds at most: about this many pixel samples (at least one render), so that a
 * job asked to stop between submissions (aa_gpu_interrupted) waits for one bounded piece, never for a
 * whole reference. The running sum stays on the GPU between them and its batches of AA_ACCUMULATE_BATCH
 * renders are the same however the submissions split them, so the image is the same to the bit. */
#define REFERENCE_SUBMIT_PIXEL_SAMPLES (2 << 20)

/* Records renders [from, to) of the reference's pattern into the running sum (cleared first when from is 0),
 * copying the sum out into half_buf after render mid (when from < mid < to) and into full_buf at the end;
 * submits them in pieces and waits. gpu_ms: the renders and their accumulation. */
static int render_span(struct aa_reference *ref, struct aa_gpu_timer *timer, int from, int mid, int to,
		       double *gpu_ms, struct aa_error *err)
{
	struct aa_renderer *r = ref->r;
	const long pixels = (long)r->width * r->height;
	const int per_submit = pixels > 0 && REFERENCE_SUBMIT_PIXEL_SAMPLES / pixels > 1 ?
		(int)(REFERENCE_SUBMIT_PIXEL_SAMPLES / pixels) : 1;
	*gpu_ms = 0;
	for (int first = from; first < to; first += per_submit) {
		const int last = first + per_submit < to ? first + per_submit : to;
		VkCommandBuffer cmd;
		if (aa_gpu_interrupted(r->gpu, err) || aa_gpu_begin(r->gpu, &cmd, err))
			return -1;
		aa_gpu_timer_reset(cmd, timer);
		int span = aa_gpu_timer_begin(cmd, timer, "reference");
		if (first == 0) {
			aa_renderer_record_shadow(r, cmd);
			aa_sample_accumulator_clear(&ref->sum, cmd);
		}
		int spans = 1;
		for (int i = first; i < last; i++) {
			aa_sample_accumulator_render(&ref->sum, cmd, ref->offsets[i][0], ref->offsets[i][1]);
			if (i + 1 != mid || mid >= to)
				continue;
			/* the sum of the first mid renders is copied out on the way (outside the timed spans) */
			struct aa_gpu_image *sum = aa_sample_accumulator_sum(&ref->sum, cmd);
			aa_gpu_timer_end(cmd, timer, span);
			if (aa_gpu_record_readback(r->gpu, cmd, sum, &ref->readback_half, err)) {
				aa_gpu_submit_wait(r->gpu, cmd, NULL);
				return -1;
			}
			span = aa_gpu_timer_begin(cmd, timer, "reference");
			spans++;
		}
		if (last == to) {
			struct aa_gpu_image *sum = aa_sample_accumulator_sum(&ref->sum, cmd);
			aa_gpu_timer_end(cmd, timer, span);
			if (aa_gpu_record_readback(r->gpu, cmd, sum, &ref->readback, err)) {
				aa_gpu_submit_wait(r->gpu, cmd, NULL);
				return -1;
			}
		} else {
			aa_gpu_timer_end(cmd, timer, span);
		}
		if (aa_gpu_submit_wait(r->gpu, cmd, err))
			return -1;
		double ms[2] = {0, 0};
		if (aa_gpu_timer_read(r->gpu, timer, ms, err))
			return -1;
		*gpu_ms += ms[0] + (spans > 1 ? ms[1] : 0);
	}
	return 0;
}

int aa_reference_render(struct aa_reference *ref, struct aa_gpu_timer *timer, struct aa_image_rgbaf *full,
			struct aa_image_rgbaf *half, double *gpu_ms, double *cpu_ms, struct aa_error *err)
{
	return aa_reference_render_count(ref, timer, ref->samples, full, half, gpu_ms, cpu_ms, err);
}

int aa_reference_render_count(struct aa_reference *ref, struct aa_gpu_timer *timer, int count,
			      struct aa_image_rgbaf *full, struct aa_image_rgbaf *half, double *gpu_ms, double *cpu_ms,
			      struct aa_error *err)
{
	double t0 = aa_now_ms();
	*gpu_ms = 0;
	if (count < 2 || count > ref->samples || count % 2)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "reference: %d samples of %d", count, ref->samples);
	if (render_span(ref, timer, 0, count / 2, count, gpu_ms, err))
		return -1;
	read_average(&ref->readback_half, count / 2, half);
	read_average(&ref->readback, count, full);
	*cpu_ms = aa_now_ms() - t0;
	return 0;
}

int aa_reference_extend(struct aa_reference *ref, struct aa_gpu_timer *timer, int from, int to,
			struct aa_image_rgbaf *full, double *gpu_ms, double *cpu_ms, struct aa_error *err)
{
	double t0 = aa_now_ms();
	*gpu_ms = 0;
	if (from < 2 || to <= from || to > ref->samples)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "reference: samples %d to %d of %d", from, to,
				    ref->samples);
	if (render_span(ref, timer, from, -1, to, gpu_ms, err))
		return -1;
	read_average(&ref->readback, to, full);
	*cpu_ms = aa_now_ms() - t0;
	return 0;
}

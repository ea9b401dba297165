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
	if (aa_scene_target_create_desc(r, &ref->target, r->width, r->height, &desc, "reference", NULL, err) ||
	    aa_gpu_image_create(r->gpu, &ref->accum, r->width, r->height, VK_FORMAT_R32G32B32A32_SFLOAT,
				VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
				VK_IMAGE_USAGE_TRANSFER_DST_BIT, 1, 1, err) ||
	    aa_fullscreen_pass_create(r, &ref->accumulate, &(struct aa_fullscreen_desc){
			.frag = "accumulate.frag", .source_count = 1, .sources = {ref->target.output},
			.target = &ref->accum, .accumulate = true, .push_size = sizeof(float)}, err))
		return -1;
	ref->memory_bytes = ref->target.color.bytes + ref->target.depth.bytes + ref->accum.bytes;
	return 0;
}

void aa_reference_destroy(struct aa_reference *ref)
{
	if (!ref->r)
		return;
	aa_fullscreen_pass_destroy(ref->r, &ref->accumulate);
	aa_gpu_image_destroy(ref->r->gpu, &ref->accum);
	aa_scene_target_destroy(ref->r, &ref->target);
	aa_gpu_buffer_destroy(ref->r->gpu, &ref->readback);
	free(ref->offsets);
	memset(ref, 0, sizeof *ref);
}

/* Records samples [first, last) and reads the running sum back into out, divided by last. */
static int render_range(struct aa_reference *ref, struct aa_gpu_timer *timer, int first, int last,
			struct aa_image_rgbaf *out, double *gpu_ms, struct aa_error *err)
{
	struct aa_renderer *r = ref->r;
	VkCommandBuffer cmd;
	if (aa_gpu_begin(r->gpu, &cmd, err))
		return -1;
	aa_gpu_timer_reset(cmd, timer);
	int span = aa_gpu_timer_begin(cmd, timer, "reference");
	if (first == 0) {
		aa_renderer_record_shadow(r, cmd);
		aa_gpu_image_barrier(cmd, &ref->accum, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
		VkClearColorValue zero = {.float32 = {0, 0, 0, 0}};
		VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
		vkCmdClearColorImage(cmd, ref->accum.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
	}
	for (int i = first; i < last; i++) {
		aa_renderer_draw_scene(r, cmd, &ref->target, ref->offsets[i][0], ref->offsets[i][1]);
		float weight = 1.0f; /* summed; divided at readback so N/2 and N share the sum */
		aa_fullscreen_pass_record(r, cmd, &ref->accumulate, &weight, sizeof weight);
	}
	aa_gpu_timer_end(cmd, timer, span);
	if (aa_gpu_record_readback(r->gpu, cmd, &ref->accum, &ref->readback, err)) {
		aa_gpu_submit_wait(r->gpu, cmd, NULL);
		return -1;
	}
	if (aa_gpu_submit_wait(r->gpu, cmd, err))
		return -1;
	double ms = 0;
	if (aa_gpu_timer_read(r->gpu, timer, &ms, err))
		return -1;
	*gpu_ms += ms;
	const float *sum = ref->readback.mapped;
	size_t n = (size_t)out->width * out->height * 4;
	float scale = 1.0f / (float)last;
	for (size_t i = 0; i < n; i++)
		out->pixels[i] = sum[i] * scale;
	return 0;
}

int aa_reference_render(struct aa_reference *ref, struct aa_gpu_timer *timer, struct aa_image_rgbaf *full,
			struct aa_image_rgbaf *half, double *gpu_ms, double *cpu_ms, struct aa_error *err)
{
	double t0 = aa_now_ms();
	*gpu_ms = 0;
	int mid = ref->samples / 2;
	if (render_range(ref, timer, 0, mid, half, gpu_ms, err) ||
	    render_range(ref, timer, mid, ref->samples, full, gpu_ms, err))
		return -1;
	*cpu_ms = aa_now_ms() - t0;
	return 0;
}

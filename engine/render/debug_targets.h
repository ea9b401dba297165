/* Job option debug_targets (docs/job-format.md): every intermediate GPU image a method creates is entered
 * here, read back after each of the method's scored frames, and its non-finite texels counted. Nothing of
 * this exists when the option is off: no registry, no extra usage bits, no readback. */
#ifndef AA_DEBUG_TARGETS_H
#define AA_DEBUG_TARGETS_H

#include <stdbool.h>

#include "gpu/gpu.h"
#include "types/job.h"

struct aa_debug_target {
	struct aa_gpu_image *img;  /* the method's own struct: removed when the image is destroyed */
	VkImage image;             /* the handle at registration, to refuse an entry whose struct was reused */
	char name[48];
	int owner;                 /* the job's method index */
};

struct aa_debug_targets {
	struct aa_gpu *gpu;
	int owner;                 /* method index images created now belong to; -1: not entered (the
				    * reference, re-timing twins) */
	int count, capacity;
	struct aa_debug_target *targets;
	struct aa_gpu_buffer readback; /* host-visible, grown to the largest method's total */
};

/* Installs the registry on gpu (its images' destruction removes entries); owner starts at -1. */
int aa_debug_targets_create(struct aa_gpu *gpu, struct aa_debug_targets **out, struct aa_error *err);
void aa_debug_targets_destroy(struct aa_debug_targets *d);
/* Whether an image of this kind can be read back and checked: one sample, a float format, and depth only
 * when it is stored (sampled). Integer and UNORM formats cannot hold NaN/Inf and are not entered. */
bool aa_debug_targets_wants(VkFormat format, VkImageUsageFlags usage, uint32_t samples);
/* The usage the image needs for the readback: usage plus TRANSFER_SRC when d is on and wants it. */
VkImageUsageFlags aa_debug_targets_usage(const struct aa_debug_targets *d, VkFormat format, VkImageUsageFlags usage,
					 uint32_t samples);
/* Enters img under name for the current owner (d NULL, owner -1 or an unwanted kind: nothing). */
int aa_debug_targets_add(struct aa_debug_targets *d, struct aa_gpu_image *img, VkImageUsageFlags usage,
			 const char *name, struct aa_error *err);
/* Texels of tightly packed data of this format with a NaN/Inf channel (D32F: also outside [0, 1]); 0 for
 * a format that is not checked. */
long aa_debug_targets_count_invalid(const void *data, VkFormat format, int width, int height);
/* Reads back every written image of method `owner` in one submission and fills fr's intermediate counts. */
int aa_debug_targets_check(struct aa_debug_targets *d, int owner, struct aa_frame_result *fr, struct aa_error *err);

#endif

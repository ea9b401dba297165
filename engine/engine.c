/* The engine: one Vulkan device for the process, shared by every job. */
#include <malloc.h>
#include <stdlib.h>
#include <string.h>

#include "aa.h"
#include "engine_internal.h"

int aa_engine_create(const struct aa_engine_options *opts, struct aa_engine **out, struct aa_error *err)
{
	/* lavapipe returns its per-frame working memory to the kernel and faults it in again every frame
	 * unless trimming is raised (lavapipe-costs.md, trap 2): up to 2x slower, not repeatably. */
	mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
	struct aa_engine *e = calloc(1, sizeof *e);
	if (!e)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	const char *v = getenv("AALAB_VALIDATION");
	bool validation = (opts && opts->validation) || (v && strcmp(v, "0") != 0 && *v);
	if (aa_gpu_create(&e->gpu, opts ? opts->device : NULL, validation, err)) {
		free(e);
		return -1;
	}
	*out = e;
	return 0;
}

void aa_engine_destroy(struct aa_engine *e)
{
	if (!e)
		return;
	aa_gpu_destroy(&e->gpu);
	free(e);
}

int aa_engine_validation_errors(const struct aa_engine *e)
{
	return e->gpu.validation_errors;
}

const char *aa_engine_device_name(const struct aa_engine *e)
{
	return e->gpu.properties.deviceName;
}

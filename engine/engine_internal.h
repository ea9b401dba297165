/* The engine's private state, shared by engine.c and job_run.c. */
#ifndef AA_ENGINE_INTERNAL_H
#define AA_ENGINE_INTERNAL_H

#include "gpu/gpu.h"

struct aa_engine {
	struct aa_gpu gpu;
};

#endif

/* Jitter sequences: where each frame's samples fall inside the pixel. */
#include "methods/jitter.h"

#include "reference/reference.h"
#include "util/halton.h"

void aa_jitter_halton(int frame, int length, float out[2])
{
	unsigned i = (unsigned)(frame % length) + 1; /* skip index 0, the pixel corner */
	out[0] = (float)(aa_halton(i, 2) - 0.5);
	out[1] = (float)(aa_halton(i, 3) - 0.5);
}

void aa_jitter_quadrant(int frame, float out[2])
{
	/* order: top-left, bottom-right, top-right, bottom-left: consecutive frames are far apart */
	static const float q[4][2] = {{-0.25f, -0.25f}, {0.25f, 0.25f}, {0.25f, -0.25f}, {-0.25f, 0.25f}};
	int k = frame & 3;
	out[0] = q[k][0];
	out[1] = q[k][1];
}

void aa_jitter_alternate(int frame, float offset, float out[2])
{
	float s = (frame & 1) ? -offset : offset;
	out[0] = s;
	out[1] = s;
}

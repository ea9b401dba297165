/* Jitter sequences: where each frame's samples fall inside the pixel. */
#include <math.h>

#include "methods/jitter.h"
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

/* seed 000 draws g_t with the Marsaglia polar method (Listing 4.2) and supposes the original used a
 * precalculated table: a stratified, repeating set lets a still pixel settle on one well-spread estimate
 * instead of wandering with fresh random offsets; it is deterministic, so a run is reproducible and a run
 * started at a cut matches one that reached it. */
#define GAUSSIAN_TABLE 16
void aa_jitter_gaussian(int frame, float sigma, float out[2])
{
	unsigned i = (unsigned)((frame >> 2) & (GAUSSIAN_TABLE - 1)) + 1;
	double u = aa_halton(i, 2), v = aa_halton(i, 3);
	double radius = sigma * sqrt(-2.0 * log(u));
	out[0] = (float)(radius * cos(2.0 * M_PI * v));
	out[1] = (float)(radius * sin(2.0 * M_PI * v));
}

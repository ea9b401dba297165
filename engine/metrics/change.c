/* How much an image changed between two frames: the "stuck" verdict compares a method's change with the
 * reference's (docs/hard-cases.md). */
#include <stdlib.h>

#include "metrics/metrics.h"

double aa_metrics_mean_change(const struct aa_image_rgba8 *a, const struct aa_image_rgba8 *b)
{
	const size_t n = (size_t)a->width * a->height;
	unsigned long long sum = 0;
	for (size_t i = 0; i < n; i++)
		for (int c = 0; c < 3; c++)
			sum += (unsigned)abs((int)a->pixels[i * 4 + c] - (int)b->pixels[i * 4 + c]);
	return n ? (double)sum / (double)(3 * n) : 0.0;
}

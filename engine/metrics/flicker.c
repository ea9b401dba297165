/* Temporal stability of a method against the reference between two consecutive frames (metrics.h). */
#include <stdint.h>
#include <stdlib.h>

#include "metrics/metrics.h"

double aa_metrics_flicker(const struct aa_image_rgba8 *m, const struct aa_image_rgba8 *m_prev,
			  const struct aa_image_rgba8 *r, const struct aa_image_rgba8 *r_prev)
{
	size_t n = (size_t)m->width * m->height;
	uint64_t sum = 0;
	for (size_t i = 0; i < n * 4; i++) {
		if ((i & 3) == 3)
			continue;
		int d = ((int)m->pixels[i] - m_prev->pixels[i]) - ((int)r->pixels[i] - r_prev->pixels[i]);
		sum += (uint64_t)abs(d);
	}
	return (double)sum / (double)(n * 3);
}

/* The radical inverse: the Halton sequence of a base. */
#include "util/halton.h"

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

/* Standard sample locations, from the Vulkan specification's table of standard sample locations. */
#include <stddef.h>

#include "gpu/sample_positions.h"

static const float one[1][2] = {{0.5f, 0.5f}};
static const float two[2][2] = {{0.75f, 0.75f}, {0.25f, 0.25f}};
static const float four[4][2] = {{0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};
static const float eight[8][2] = {
	{0.5625f, 0.3125f}, {0.4375f, 0.6875f}, {0.8125f, 0.5625f}, {0.3125f, 0.1875f},
	{0.1875f, 0.8125f}, {0.0625f, 0.4375f}, {0.6875f, 0.9375f}, {0.9375f, 0.0625f},
};
static const float sixteen[16][2] = {
	{0.5625f, 0.5625f}, {0.4375f, 0.3125f}, {0.3125f, 0.625f}, {0.75f, 0.4375f},
	{0.1875f, 0.375f}, {0.625f, 0.8125f}, {0.8125f, 0.6875f}, {0.6875f, 0.1875f},
	{0.375f, 0.875f}, {0.5f, 0.0625f}, {0.25f, 0.125f}, {0.125f, 0.75f},
	{0.0f, 0.5f}, {0.9375f, 0.25f}, {0.875f, 0.9375f}, {0.0625f, 0.0f},
};

const float (*aa_standard_sample_positions(int n))[2]
{
	switch (n) {
	case 1: return one;
	case 2: return two;
	case 4: return four;
	case 8: return eight;
	case 16: return sixteen;
	}
	return NULL;
}

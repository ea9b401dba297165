/* Owen-scrambled Sobol' points (owen_sobol.h). */
#include "reference/owen_sobol.h"

/* Fixed seeds, one per dimension: the reference is deterministic, so stored frames stay valid. Any other
 * pair gives another, equally good scramble. */
#define SEED_X 0x9e3779b9u
#define SEED_Y 0x7f4a7c15u

static uint32_t reverse_bits(uint32_t x)
{
	x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
	x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
	x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
	x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
	return (x >> 16) | (x << 16);
}

void aa_sobol_2d(uint32_t index, uint32_t out[2])
{
	out[0] = reverse_bits(index);
	/* direction numbers of x + 1: v_0 = 1/2, v_i = v_(i-1) xor v_(i-1)/2 (the Pascal matrix mod 2) */
	uint32_t v = 1u << 31, y = 0;
	for (; index; index >>= 1, v ^= v >> 1)
		if (index & 1u)
			y ^= v;
	out[1] = y;
}

uint32_t aa_owen_scramble(uint32_t x, uint32_t seed)
{
	/* Burley's hash in bit-reversed order: each output bit flips by a function of the more significant
	 * input bits only, which is what a nested uniform scramble is (Laine and Karras's construction, with
	 * Burley's constants) */
	x = reverse_bits(x);
	x += seed;
	x ^= x * 0x6c50b47cu;
	x ^= x * 0xb82f1e52u;
	x ^= x * 0xc7afe638u;
	x ^= x * 0x8d22f6e6u;
	return reverse_bits(x);
}

void aa_owen_sobol_2d(uint32_t index, float out[2])
{
	uint32_t s[2];
	aa_sobol_2d(index, s);
	const uint32_t seeds[2] = {SEED_X, SEED_Y};
	for (int k = 0; k < 2; k++)
		out[k] = (float)(aa_owen_scramble(s[k], seeds[k]) >> 8) * (1.0f / 16777216.0f);
}

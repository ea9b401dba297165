/* The reference's sample sequence: the 2D Sobol' sequence (a (0,2)-sequence in base 2) with Owen's nested
 * uniform scrambling, computed by hashing (Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4),
 * 2020). No method jitters with it: every method's positions are dyadic or triadic fractions of small
 * denominator (standard MSAA positions, SSAA grids, Halton jitters, quadrant centres), which a scrambled
 * point almost never is, and tests/unit/test_sample_independence checks that none coincides. */
#ifndef AA_OWEN_SOBOL_H
#define AA_OWEN_SOBOL_H

#include <stdint.h>

/* The unscrambled Sobol' point `index` in 32-bit fixed point (dimension 0: van der Corput in base 2;
 * dimension 1: the direction numbers of the primitive polynomial x + 1). */
void aa_sobol_2d(uint32_t index, uint32_t out[2]);
/* Owen's nested uniform scramble of the 32-bit fraction x, the random tree chosen by seed. */
uint32_t aa_owen_scramble(uint32_t x, uint32_t seed);
/* Point `index` of the scrambled sequence in [0, 1)^2, each coordinate a multiple of 2^-24 (exact in
 * float). The first 2^k points form a (0,k,2)-net: every dyadic box of area 2^-k holds exactly one. */
void aa_owen_sobol_2d(uint32_t index, float out[2]);

#endif

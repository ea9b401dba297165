/* The radical inverse: the Halton sequence of a base. */
#ifndef AA_HALTON_H
#define AA_HALTON_H

/* Radical inverse of index in base (Halton sequence; index 0 gives 0). */
double aa_halton(unsigned index, unsigned base);

#endif

/* The Vulkan standard sample locations (standardSampleLocations), in [0,1)^2 of the pixel with y down:
 * what hardware MSAA uses, and where "virtual samples" rasterise when the device lacks a count. */
#ifndef AA_SAMPLE_POSITIONS_H
#define AA_SAMPLE_POSITIONS_H

/* Returns the n positions for n in {1, 2, 4, 8, 16}, NULL otherwise. */
const float (*aa_standard_sample_positions(int n))[2];

#endif

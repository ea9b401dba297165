/* Sub-pixel jitter sequences of the temporal methods, in pixels within [-0.5, 0.5)^2 (x right, y down).
 * A method passes the offset to aa_renderer_draw_scene, which applies it as a translation after the
 * projection, so points at every depth move by the same amount (seed 000's pre-projection jitter did
 * not). */
#ifndef AA_JITTER_H
#define AA_JITTER_H

/* Halton(2,3) points 1..length (length 8 or 16 in the seeds), repeating: seed 001's TAA. */
void aa_jitter_halton(int frame, int length, float out[2]);
/* The centres of the four pixel quadrants, one per frame: ASAA's four sub-pixel buffers (seed 000). */
void aa_jitter_quadrant(int frame, float out[2]);
/* T2MSAA's alternation: +offset and -offset on the diagonal on even and odd frames (seed 000; offset
 * 0.25, 0.1875 or 0.125 pixels). */
void aa_jitter_alternate(int frame, float offset, float out[2]);
/* ASAA's Gaussian offset g_t of frame (seed 000): a table of 16 offsets, Box-Muller applied to Halton(2,3)
 * points 1..16, each taken for four frames (one per quadrant buffer) in turn. */
void aa_jitter_gaussian(int frame, float sigma, float out[2]);

#endif

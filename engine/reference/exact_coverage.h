/* Exact box-filtered coverage of 2D polygon patterns: the zero-error reference for flat scenes. */
#ifndef AA_EXACT_COVERAGE_H
#define AA_EXACT_COVERAGE_H

#include "../scene/scene.h"

/* Each pixel's covered area (0..1) by the union of polygons, computed by clipping each polygon to the
 * pixel square (Sutherland-Hodgman) and summing areas. Polygons must not overlap each other.
 * coverage has width*height entries, rows top to bottom. */
void aa_exact_coverage(const struct aa_polygon2d *polys, int poly_count, int width, int height,
		       double *coverage);

enum aa_pattern2d_kind { AA_PATTERN2D_HALF_PLANE, AA_PATTERN2D_BAR, AA_PATTERN2D_STAR };

/* Builds a test pattern centred in a width x height image:
 * HALF_PLANE: everything on one side of a line through the centre at `angle_degrees` from the x axis
 *             (clipped to the image, as one convex polygon);
 * BAR:        a rectangle `thickness` px wide crossing the image at `angle_degrees`;
 * STAR:       `spokes` thin wedges from the centre (spokes <= 16 polygons), rotated by angle_degrees.
 * Returns the polygon count written to polys (capacity 16). */
int aa_pattern2d_make(enum aa_pattern2d_kind kind, double angle_degrees, double thickness, int spokes,
		      int width, int height, struct aa_polygon2d *polys);

#endif

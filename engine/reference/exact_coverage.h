/* Exact box-filtered coverage of 2D polygon patterns: the zero-error reference for flat scenes. */
#ifndef AA_EXACT_COVERAGE_H
#define AA_EXACT_COVERAGE_H

#include "scene/scene.h"

/* Each pixel's covered area (0..1) by the union of polygons, computed by clipping each polygon to the
 * pixel square (Sutherland-Hodgman) and summing areas. Polygons must not overlap each other.
 * coverage has width*height entries, rows top to bottom. Polygons with fewer than 3 or more than 16
 * vertices, or with a coordinate that is not finite or beyond +-1e15, are skipped. */
void aa_exact_coverage(const struct aa_polygon2d *polys, int poly_count, int width, int height,
		       double *coverage);

enum aa_pattern2d_kind { AA_PATTERN2D_HALF_PLANE, AA_PATTERN2D_BAR, AA_PATTERN2D_STAR };

/* Builds a test pattern centred in a width x height image. Angles turn counter-clockwise as seen on
 * screen (y points down, so 90 degrees points up). Every polygon is clipped to the image (<= 8 vertices).
 * HALF_PLANE: everything to the left of a line through the centre at `angle_degrees` from the x axis,
 *             looking along the line (0 degrees: the top half; 90: the left half), as one polygon;
 * BAR:        a rectangle `thickness` px wide crossing the image at `angle_degrees` (thickness > 0);
 * STAR:       `spokes` (1..16) wedges from the centre, each half of its 360/spokes sector wide, the
 *             first starting at angle_degrees, reaching past the image edges.
 * Returns the polygon count written to polys (capacity 16); 0 for invalid arguments. */
int aa_pattern2d_make(enum aa_pattern2d_kind kind, double angle_degrees, double thickness, int spokes,
		      int width, int height, struct aa_polygon2d *polys);

#endif

/* Exact box-filtered coverage of convex polygons, by clipping each polygon to every pixel it touches. */
#include "reference/exact_coverage.h"

#include <math.h>
#include <stdbool.h>
#include <string.h>

#define PI 3.14159265358979323846
/* Clipping a convex polygon adds at most one vertex per boundary, but a polygon that is not convex (the
 * header asks for convex ones; scene files may still hold others) can double its vertices at each of
 * the four boundaries of a pixel: 16 * 2^4. */
#define CLIP_CAPACITY 256

struct clip_polygon {
	int count;
	double x[CLIP_CAPACITY], y[CLIP_CAPACITY];
};

/* Sutherland-Hodgman against one axis-aligned boundary: keeps the part where sign * (coord - limit) <= 0
 * (sign +1 keeps coord <= limit, -1 keeps coord >= limit), on the x axis or the y axis. */
static void clip_axis(const struct clip_polygon *in, struct clip_polygon *out, bool on_x, double limit,
		      double sign)
{
	out->count = 0;
	for (int i = 0; i < in->count; i++) {
		int j = (i + 1) % in->count;
		double ci = on_x ? in->x[i] : in->y[i], cj = on_x ? in->x[j] : in->y[j];
		double di = sign * (ci - limit), dj = sign * (cj - limit);
		bool inside_i = di <= 0.0, inside_j = dj <= 0.0;
		if (inside_i) {
			out->x[out->count] = in->x[i];
			out->y[out->count] = in->y[i];
			out->count++;
		}
		if (inside_i != inside_j) {
			/* The crossing is put exactly on the boundary so neighbouring pixels share it. */
			double t = di / (di - dj);
			double other = on_x ? in->y[i] + t * (in->y[j] - in->y[i]) : in->x[i] + t * (in->x[j] - in->x[i]);
			out->x[out->count] = on_x ? limit : other;
			out->y[out->count] = on_x ? other : limit;
			out->count++;
		}
	}
}

/* Shoelace formula; the absolute value makes the winding direction irrelevant. */
static double polygon_area(const struct clip_polygon *p)
{
	double twice = 0.0;
	for (int i = 0; i < p->count; i++) {
		int j = (i + 1) % p->count;
		twice += p->x[i] * p->y[j] - p->x[j] * p->y[i];
	}
	return fabs(twice) * 0.5;
}

static void range_of(const struct clip_polygon *p, bool on_x, double *lo, double *hi)
{
	*lo = INFINITY;
	*hi = -INFINITY;
	for (int i = 0; i < p->count; i++) {
		double c = on_x ? p->x[i] : p->y[i];
		*lo = c < *lo ? c : *lo;
		*hi = c > *hi ? c : *hi;
	}
}

/* First and one-past-last pixel index overlapping [lo, hi], limited to [0, size). */
static void pixel_span(double lo, double hi, int size, int *first, int *end)
{
	double f = floor(lo), e = ceil(hi);
	*first = f < 0.0 ? 0 : f > size ? size : (int)f;
	*end = e < 0.0 ? 0 : e > size ? size : (int)e;
}

static bool polygon_usable(const struct aa_polygon2d *poly)
{
	if (poly->count < 3 || poly->count > 16)
		return false;
	/* The bound keeps clipping arithmetic far from overflow. */
	for (int i = 0; i < poly->count; i++)
		if (!(fabs(poly->xy[i][0]) <= 1e15) || !(fabs(poly->xy[i][1]) <= 1e15))
			return false;
	return true;
}

/* Adds one polygon's coverage: clip to each pixel row's strip, then each strip piece to each pixel. */
static void add_polygon(const struct aa_polygon2d *poly, int width, int height, double *coverage)
{
	struct clip_polygon whole = { .count = poly->count };
	for (int i = 0; i < poly->count; i++) {
		whole.x[i] = poly->xy[i][0];
		whole.y[i] = poly->xy[i][1];
	}
	double lo, hi;
	int row_first, row_end;
	range_of(&whole, false, &lo, &hi);
	pixel_span(lo, hi, height, &row_first, &row_end);
	for (int row = row_first; row < row_end; row++) {
		struct clip_polygon below, strip;
		clip_axis(&whole, &below, false, row, -1.0);
		clip_axis(&below, &strip, false, row + 1, 1.0);
		if (strip.count < 3)
			continue;
		int col_first, col_end;
		range_of(&strip, true, &lo, &hi);
		pixel_span(lo, hi, width, &col_first, &col_end);
		for (int col = col_first; col < col_end; col++) {
			struct clip_polygon right_of, cell;
			clip_axis(&strip, &right_of, true, col, -1.0);
			clip_axis(&right_of, &cell, true, col + 1, 1.0);
			if (cell.count >= 3)
				coverage[(size_t)row * width + col] += polygon_area(&cell);
		}
	}
}

void aa_exact_coverage(const struct aa_polygon2d *polys, int poly_count, int width, int height,
		       double *coverage)
{
	if (width <= 0 || height <= 0)
		return;
	memset(coverage, 0, (size_t)width * height * sizeof *coverage);
	for (int p = 0; p < poly_count; p++)
		if (polygon_usable(&polys[p]))
			add_polygon(&polys[p], width, height, coverage);
	/* Rounding can push a fully covered pixel a few ulps past 1. */
	for (size_t i = 0; i < (size_t)width * height; i++)
		if (coverage[i] > 1.0)
			coverage[i] = 1.0;
}

/* ---------------------------------------------------------------- test patterns */

static void image_rectangle(int width, int height, struct clip_polygon *out)
{
	*out = (struct clip_polygon){ .count = 4,
				      .x = { 0, width, width, 0 },
				      .y = { 0, 0, height, height } };
}

/* Sutherland-Hodgman against the half-plane n . (p - c) >= 0. */
static void clip_half_plane(const struct clip_polygon *in, struct clip_polygon *out, double cx, double cy,
			    double nx, double ny)
{
	out->count = 0;
	for (int i = 0; i < in->count; i++) {
		int j = (i + 1) % in->count;
		double di = nx * (in->x[i] - cx) + ny * (in->y[i] - cy);
		double dj = nx * (in->x[j] - cx) + ny * (in->y[j] - cy);
		if (di >= 0.0) {
			out->x[out->count] = in->x[i];
			out->y[out->count] = in->y[i];
			out->count++;
		}
		if ((di >= 0.0) != (dj >= 0.0)) {
			double t = di / (di - dj);
			out->x[out->count] = in->x[i] + t * (in->x[j] - in->x[i]);
			out->y[out->count] = in->y[i] + t * (in->y[j] - in->y[i]);
			out->count++;
		}
	}
}

/* Clips a convex polygon to the image and stores it; returns 1 if anything is left, else 0. */
static int store_clipped(const struct clip_polygon *shape, int width, int height, struct aa_polygon2d *out)
{
	struct clip_polygon a, b;
	clip_axis(shape, &a, true, 0.0, -1.0);
	clip_axis(&a, &b, true, width, 1.0);
	clip_axis(&b, &a, false, 0.0, -1.0);
	clip_axis(&a, &b, false, height, 1.0);
	if (b.count < 3 || b.count > 16 || polygon_area(&b) <= 0.0)
		return 0;
	out->count = b.count;
	for (int i = 0; i < b.count; i++) {
		out->xy[i][0] = b.x[i];
		out->xy[i][1] = b.y[i];
	}
	return 1;
}

int aa_pattern2d_make(enum aa_pattern2d_kind kind, double angle_degrees, double thickness, int spokes,
		      int width, int height, struct aa_polygon2d *polys)
{
	if (width <= 0 || height <= 0 || !isfinite(angle_degrees))
		return 0;
	double cx = width * 0.5, cy = height * 0.5;
	double angle = angle_degrees * (PI / 180.0);
	/* Angles turn counter-clockwise as seen on screen; with y pointing down that negates the y part. */
	double dx = cos(angle), dy = -sin(angle);
	double reach = hypot(width, height); /* longer than any line inside the image */
	struct clip_polygon shape;

	switch (kind) {
	case AA_PATTERN2D_HALF_PLANE: {
		/* Keep the side to the left of the direction on screen: above for 0 degrees, left for 90. */
		struct clip_polygon rect;
		image_rectangle(width, height, &rect);
		clip_half_plane(&rect, &shape, cx, cy, dy, -dx);
		return store_clipped(&shape, width, height, polys);
	}
	case AA_PATTERN2D_BAR: {
		if (!(thickness > 0.0) || !isfinite(thickness))
			return 0;
		double half = thickness * 0.5, nx = -dy, ny = dx;
		double sx[4] = { -reach, reach, reach, -reach }, sn[4] = { -half, -half, half, half };
		shape.count = 4;
		for (int i = 0; i < 4; i++) {
			shape.x[i] = cx + sx[i] * dx + sn[i] * nx;
			shape.y[i] = cy + sx[i] * dy + sn[i] * ny;
		}
		return store_clipped(&shape, width, height, polys);
	}
	case AA_PATTERN2D_STAR: {
		if (spokes < 1 || spokes > 16)
			return 0;
		/* Spoke k spans half of its 360/spokes sector, so wedges and gaps are equally wide. Each wedge
		 * is the centre plus three points on a circle beyond the image corners (the middle one keeps
		 * the far edge outside the image even for a single 180-degree wedge). */
		double sector = 2.0 * PI / spokes, far = 2.0 * reach;
		int count = 0;
		for (int k = 0; k < spokes; k++) {
			double a0 = angle + k * sector, a1 = a0 + 0.5 * sector;
			double along[3] = { a0, 0.5 * (a0 + a1), a1 };
			shape.count = 4;
			shape.x[0] = cx;
			shape.y[0] = cy;
			for (int i = 0; i < 3; i++) {
				shape.x[1 + i] = cx + far * cos(along[i]);
				shape.y[1 + i] = cy - far * sin(along[i]);
			}
			count += store_clipped(&shape, width, height, &polys[count]);
		}
		return count;
	}
	}
	return 0;
}

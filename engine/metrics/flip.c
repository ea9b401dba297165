/* FLIP error maps: the colour pipeline (contrast-sensitivity filters in YCxCz, then HyAB in Hunt-adjusted
 * CIELab) and the feature pipeline (edges and points of the luminance), combined per pixel.
 *
 * Every filter is separable and applied horizontally, then vertically, with clamp-to-edge borders, as
 * the reference implementation does. Each thread owns a band of output rows. It converts source rows to
 * YCxCz and filters them horizontally into a ring of 2M+1 rows (M, the larger of the two filter radii),
 * one strip of columns at a time so that the ring stays in L2; then it filters each output row
 * vertically in blocks of BLOCK pixels, which stay in L1, and computes the errors of the block. The SIMD
 * kernels (flip_simd.c) do per pixel what scalar code does, in the reference's order, so the map is the
 * same bit for bit with any number of threads and with or without AVX2.
 *
 * What depends on the reference alone (its filtered YCxCz and its edge and point strengths) can be made
 * once and kept per pixel (struct aa_flip_reference); a test image compared against it then goes through
 * the ring alone. Each value is computed by the same code either way, so the maps are the same. */
#include "metrics/flip.h"
#include "metrics/flip_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define FLIP_QC 0.7f  /* exponent of the colour distance */
#define FLIP_PC 0.4f  /* share of cmax where the colour error's slope changes */
#define FLIP_PT 0.95f /* colour error at that point */
#define FLIP_QF 0.5f  /* exponent of the feature difference */

#define MAX_THREADS 8
#define MIN_PIXELS_PER_THREAD 32768
#define MAX_EXPOSURES 100

static inline float luminance(const float rgb[3])
{
	return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
}

/* The reference's clamp: a NaN becomes 0. */
static inline float clamp01(float v)
{
	v = v > 0.0f ? v : 0.0f;
	return v > 1.0f ? 1.0f : v;
}

/* Filtered YCxCz -> linear RGB, clamped -> CIELab with the Hunt adjustment of a and b. */
static void hunt_lab(const float ycxcz[3], float lab[3])
{
	float xyz[3], rgb[3];
	flip_ycxcz_to_xyz(ycxcz, xyz);
	flip_xyz_to_linear(xyz, rgb);
	for (int i = 0; i < 3; i++)
		rgb[i] = clamp01(rgb[i]);
	flip_linear_to_xyz(rgb, xyz);
	flip_xyz_to_lab(xyz, lab);
	lab[1] = 0.01f * lab[0] * lab[1];
	lab[2] = 0.01f * lab[0] * lab[2];
}

static float hyab(const float r[3], const float t[3])
{
	float da = r[1] - t[1], db = r[2] - t[2];
	return fabsf(r[0] - t[0]) + sqrtf(da * da + db * db);
}

float aa_flip_max_color_distance(void)
{
	const float green[3] = { 0.0f, 1.0f, 0.0f }, blue[3] = { 0.0f, 0.0f, 1.0f };
	float xyz[3], g[3], b[3];
	flip_linear_to_xyz(green, xyz);
	flip_xyz_to_lab(xyz, g);
	flip_linear_to_xyz(blue, xyz);
	flip_xyz_to_lab(xyz, b);
	g[1] = 0.01f * g[0] * g[1];
	g[2] = 0.01f * g[0] * g[2];
	b[1] = 0.01f * b[0] * b[1];
	b[2] = 0.01f * b[0] * b[2];
	return powf(hyab(g, b), FLIP_QC);
}

/* The colour distance, compressed: linear up to pc*cmax (where it reaches pt), then slowly up to 1. */
static inline float color_error(const float ref_ycxcz[3], const float test_ycxcz[3], float cmax, float pccmax)
{
	float lr[3], lt[3];
	hunt_lab(ref_ycxcz, lr);
	hunt_lab(test_ycxcz, lt);
	float d = powf(hyab(lr, lt), FLIP_QC);
	if (d < pccmax)
		return d * (FLIP_PT / pccmax);
	return FLIP_PT + ((d - pccmax) / (cmax - pccmax)) * (1.0f - FLIP_PT);
}

float aa_flip_color_error(const float ref_ycxcz[3], const float test_ycxcz[3])
{
	float cmax = aa_flip_max_color_distance();
	return color_error(ref_ycxcz, test_ycxcz, cmax, FLIP_PC * cmax);
}

float aa_flip_feature_error(float edge_ref, float edge_test, float point_ref, float point_test)
{
	float de = fabsf(edge_ref - edge_test), dp = fabsf(point_ref - point_test);
	return powf((1.0f / sqrtf(2.0f)) * (de > dp ? de : dp), FLIP_QF);
}

/* ------------------------------------------------------------------------------------------------ the map */

/* Where one image's linear RGB rows come from: 8-bit sRGB through a table, or floats, optionally
 * exposed and tone mapped (HDR-FLIP). Values reach the pipeline clamped to [0,1]. */
struct flip_source {
	const uint8_t *rgba8;
	const float *rgbaf;
	bool tone_map;
	enum aa_flip_tone_mapper tm;
	float exposure_scale;
};

struct flip_run {
	struct flip_source src[2]; /* reference, test */
	int width, height, threads;
	const struct aa_flip_filters *f;
	int margin;                /* M: the larger filter radius */
	float cmax, pccmax;
	float srgb_table[256];
	float *map;
	bool merge_max;            /* HDR: keep the larger of map and this exposure's error */
	/* The images whose rows go through the ring: [0, 2) both; [1, 2) the test alone against ref_in,
	 * whose reference side was computed once; [0, 1) the reference alone, into ref_out. */
	int image_begin, image_end;
	const struct aa_flip_reference *ref_in;
	struct aa_flip_reference *ref_out;
};

/* The reference side of the map, per pixel: its vertically filtered Y, Cx and both Cz rows, and its edge
 * and point strengths. These depend on the reference alone, so every test image of one frame can share
 * them (aa_flip_ldr_rgba8_against). */
enum { R_Y, R_CX, R_CZ1, R_CZ2, R_EDGE, R_POINT, R_PLANES };

struct aa_flip_reference {
	int width, height;
	struct aa_flip_filters filters;
	float *plane[R_PLANES]; /* width x height, row-major, then BLOCK floats of slack the kernels read */
};

/* Horizontally filtered rows per image, in each ring slot. */
enum { H_Y, H_CX, H_CZ1, H_CZ2, H_DG, H_DDG, H_G, H_ROWS };
/* Unfiltered planes of one source row (padded by M on each side). */
enum { P_Y, P_CX, P_CZ, P_YN, P_PLANES };

struct flip_band {
	const struct flip_run *run;
	int y_begin, y_end;
	int x_begin, x_end;        /* the strip of columns being computed */
	int ring_size;             /* 2M + 1 */
	size_t row_len;            /* floats per ring row: the widest strip in whole blocks */
	float *ring;               /* ring_size x the run's images (1 or 2) x H_ROWS rows */
	int *ring_row;             /* the source row each slot holds, -1 when none */
	float *planes[P_PLANES];   /* M + row_len + M floats each, and a vector of slack */
	float *rgb[3];             /* linear R, G and B of one source row: M + row_len + M floats each */
};

/* Linear R, G and B planes of columns lo..hi-1 of row y, clamped to [0,1]. */
static void load_linear_row(const struct flip_run *run, const struct flip_source *s, int y, int lo, int hi,
			    float *const rgb[3])
{
	const int w = run->width;
	if (s->rgba8) {
		const uint8_t *p = s->rgba8 + (size_t)y * w * 4;
		for (int x = lo; x < hi; x++)
			for (int c = 0; c < 3; c++)
				rgb[c][x - lo] = run->srgb_table[p[4 * x + c]];
		return;
	}
	const float *p = s->rgbaf + (size_t)y * w * 4;
	for (int x = lo; x < hi; x++) {
		float v[3] = { p[4 * x], p[4 * x + 1], p[4 * x + 2] };
		if (s->tone_map) {
			for (int c = 0; c < 3; c++)
				v[c] = v[c] * s->exposure_scale;
			aa_flip_tone_map(s->tm, v, v);
		}
		for (int c = 0; c < 3; c++)
			rgb[c][x - lo] = clamp01(v[c]);
	}
}

static float *ring_rows(struct flip_band *band, int slot, int image)
{
	const struct flip_run *run = band->run;
	const int images = run->image_end - run->image_begin;
	return band->ring + ((size_t)slot * images + (size_t)(image - run->image_begin)) * H_ROWS * band->row_len;
}

/* Converts source row y of both images to YCxCz and filters it horizontally into its ring slot, for the
 * columns of the current strip. Plane index p holds column x_begin - M + p, clamped to the image. */
static void fill_ring_row(struct flip_band *band, int y)
{
	const struct flip_run *run = band->run;
	const struct aa_flip_filters *f = run->f;
	const int w = run->width, m = run->margin, rc = f->csf_radius, rf = f->feature_radius;
	const int slot = y % band->ring_size;
	/* Whole blocks covering the strip (the last strip may be narrower than the others). */
	const size_t len = ((size_t)(band->x_end - band->x_begin) + BLOCK - 1) / BLOCK * BLOCK;
	const size_t stride = band->row_len;
	const int first = band->x_begin - m, span = (int)len + 2 * m;
	const int lo = first < 0 ? 0 : first, hi = first + span < w ? first + span : w;
	for (int image = run->image_begin; image < run->image_end; image++) {
		load_linear_row(run, &run->src[image], y, lo, hi, band->rgb);
		float *py = band->planes[P_Y], *pcx = band->planes[P_CX];
		float *pcz = band->planes[P_CZ], *pyn = band->planes[P_YN];
		flip_ycxcz_row(band->rgb, hi - lo, py + (lo - first), pcx + (lo - first), pcz + (lo - first),
			       pyn + (lo - first));
		/* Clamp to edge: replicate the end pixels over what lies outside the image. */
		for (int q = 0; q < P_PLANES; q++) {
			float *row = band->planes[q];
			for (int p = 0; p < lo - first; p++)
				row[p] = row[lo - first];
			for (int p = hi - first; p < span; p++)
				row[p] = row[hi - 1 - first];
		}
		float *out = ring_rows(band, slot, image);
		const int tc = 2 * rc + 1, tf = 2 * rf + 1;
		flip_filter_row(py + m - rc, f->csf_y, tc, out + H_Y * stride, len);
		flip_filter_row(pcx + m - rc, f->csf_cx, tc, out + H_CX * stride, len);
		flip_filter_row(pcz + m - rc, f->csf_cz1, tc, out + H_CZ1 * stride, len);
		flip_filter_row(pcz + m - rc, f->csf_cz2, tc, out + H_CZ2 * stride, len);
		flip_filter_row3(pyn + m - rf, f->dg, f->ddg, f->g, tf, out + H_DG * stride, out + H_DDG * stride,
				 out + H_G * stride, len);
	}
	band->ring_row[slot] = y;
}

/* powf(+0, y) without the call: +0 for y > 0, 1 for y = 0, +inf below, NaN for NaN. */
static inline float pow_zero(float y)
{
	return y > 0.0f ? 0.0f : y == 0.0f ? 1.0f : y < 0.0f ? INFINITY : y;
}

static inline int clamp_row(int y, int h)
{
	return y < 0 ? 0 : y >= h ? h - 1 : y;
}

enum { V_Y, V_CX, V_CZ1, V_CZ2, V_DX, V_DDX, V_DY, V_DDY, V_ROWS };

/* Edge and point strength of n pixels of one image: its gradient and second-derivative magnitudes. */
static void features_block(float v[V_ROWS][BLOCK], int n, float edge[BLOCK], float point[BLOCK])
{
	for (int e = 0; e < n; e++) {
		edge[e] = sqrtf(v[V_DX][e] * v[V_DX][e] + v[V_DY][e] * v[V_DY][e]);
		point[e] = sqrtf(v[V_DDX][e] * v[V_DDX][e] + v[V_DDY][e] * v[V_DDY][e]);
	}
}

/* The errors of n pixels from their vertically filtered values: the colour pipeline's linear steps in
 * SIMD (flip_simd.c), the cube roots and powers here. Where the filtered colours agree exactly the colour
 * error is exactly 0 and its seven powf calls are skipped, likewise the feature power where the features
 * agree: the same results, much less time on the flat areas that fill most comparisons. r is the reference
 * side (R_* rows of BLOCK readable floats), v the test's filtered values. */
static void errors_block(const struct flip_run *run, const float *const r[R_PLANES], float v[V_ROWS][BLOCK],
			 int n, float *dst)
{
	const float delta = 6.0f / 29.0f, delta_sq = delta * delta, delta_cube = delta * delta_sq;
	const float factor = 1.0f / (3.0f * delta_sq), term = 4.0f / 29.0f;
	const float cmax = run->cmax, pccmax = run->pccmax;
	float t[2][3][BLOCK], dl[BLOCK], dab2[BLOCK];
	int32_t same[BLOCK];
	const float *const yc[2][4] = { { r[R_Y], r[R_CX], r[R_CZ1], r[R_CZ2] },
					{ v[V_Y], v[V_CX], v[V_CZ1], v[V_CZ2] } };
	float edge_t[BLOCK], point_t[BLOCK];
	features_block(v, n, edge_t, point_t);
	flip_colour_block(yc, t, same);
	for (int e = 0; e < n; e++)
		if (!same[e])
			for (int i = 0; i < 2; i++)
				for (int c = 0; c < 3; c++) {
					float x = t[i][c][e];
					t[i][c][e] = x > delta_cube ? powf(x, 1.0f / 3.0f) : factor * x + term;
				}
	flip_lab_block((const float(*)[3][BLOCK])t, dl, dab2);
	for (int e = 0; e < n; e++) {
		float cdiff = 0.0f;
		if (!same[e]) {
			float d = powf(dl[e] + sqrtf(dab2[e]), FLIP_QC);
			cdiff = d < pccmax ? d * (FLIP_PT / pccmax) : FLIP_PT + ((d - pccmax) / (cmax - pccmax)) * (1.0f - FLIP_PT);
		}
		const float edge_r = r[R_EDGE][e], point_r = r[R_POINT][e];
		bool no_feature = edge_r == edge_t[e] && point_r == point_t[e];
		float fdiff = no_feature ? 0.0f : aa_flip_feature_error(edge_r, edge_t[e], point_r, point_t[e]);
		float err = cdiff == 0.0f ? pow_zero(1.0f - fdiff) : powf(cdiff, 1.0f - fdiff);
		if (!run->merge_max || err > dst[e])
			dst[e] = err;
	}
}

/* Output row y: vertical filters block by block, then the error of every pixel of the block. */
static void compute_row(struct flip_band *band, int y)
{
	const struct flip_run *run = band->run;
	const struct aa_flip_filters *f = run->f;
	const int h = run->height, m = run->margin, rc = f->csf_radius, rf = f->feature_radius;
	const size_t len = band->row_len;
	/* Rows y-M..y+M (clamped) form a contiguous range of at most 2M+1 rows, so slot y % (2M+1) never
	 * evicts a row that this output row still needs. */
	for (int k = -m; k <= m; k++) {
		int yy = clamp_row(y + k, h);
		if (band->ring_row[yy % band->ring_size] != yy)
			fill_ring_row(band, yy);
	}
	/* rows[image][s][k]: horizontally filtered row s of source row y + k - radius. */
	const float *rows[2][H_ROWS][AA_FLIP_MAX_TAPS];
	for (int image = run->image_begin; image < run->image_end; image++)
		for (int s = 0; s < H_ROWS; s++) {
			int radius = s < H_DG ? rc : rf;
			for (int k = 0; k <= 2 * radius; k++) {
				int yy = clamp_row(y + k - radius, h);
				rows[image][s][k] = ring_rows(band, yy % band->ring_size, image) + s * len;
			}
		}
	float v[2][V_ROWS][BLOCK], ref_edge[BLOCK], ref_point[BLOCK];
	const size_t pixel0 = (size_t)y * run->width + band->x_begin;
	const int tc = 2 * rc + 1, tf = 2 * rf + 1, strip = band->x_end - band->x_begin;
	for (size_t e0 = 0; e0 < (size_t)strip; e0 += BLOCK) {
		for (int i = run->image_begin; i < run->image_end; i++) {
			flip_filter_column(rows[i][H_Y], e0, f->csf_y, tc, v[i][V_Y]);
			flip_filter_column(rows[i][H_CX], e0, f->csf_cx, tc, v[i][V_CX]);
			flip_filter_column(rows[i][H_CZ1], e0, f->csf_cz1, tc, v[i][V_CZ1]);
			flip_filter_column(rows[i][H_CZ2], e0, f->csf_cz2, tc, v[i][V_CZ2]);
			flip_filter_column(rows[i][H_DG], e0, f->g, tf, v[i][V_DX]);
			flip_filter_column(rows[i][H_DDG], e0, f->g, tf, v[i][V_DDX]);
			flip_filter_column2(rows[i][H_G], e0, f->dg, f->ddg, tf, v[i][V_DY], v[i][V_DDY]);
		}
		int n = strip - (int)e0 < BLOCK ? strip - (int)e0 : BLOCK;
		if (run->ref_in) {
			const float *r[R_PLANES];
			for (int q = 0; q < R_PLANES; q++)
				r[q] = run->ref_in->plane[q] + pixel0 + e0;
			errors_block(run, r, v[1], n, run->map + pixel0 + e0);
			continue;
		}
		features_block(v[0], n, ref_edge, ref_point);
		if (run->ref_out) {
			/* n values only: the rest of the block belongs to the next strip or row, maybe another band's. */
			const float *from[R_PLANES] = { v[0][V_Y], v[0][V_CX], v[0][V_CZ1], v[0][V_CZ2], ref_edge, ref_point };
			for (int q = 0; q < R_PLANES; q++)
				memcpy(run->ref_out->plane[q] + pixel0 + e0, from[q], (size_t)n * sizeof(float));
			continue;
		}
		const float *const r[R_PLANES] = { v[0][V_Y], v[0][V_CX], v[0][V_CZ1], v[0][V_CZ2], ref_edge, ref_point };
		errors_block(run, r, v[1], n, run->map + pixel0 + e0);
	}
}

/* Columns per strip: the ring of one strip (2M+1 rows of 2 x H_ROWS filtered rows) should stay in a
 * core's L2 cache, which the vertical filters read 2M+1 times per value. */
#define RING_BYTES (1u << 20)

static int strip_width(const struct flip_run *run)
{
	size_t per_column = (size_t)(2 * run->margin + 1) * 2 * H_ROWS * sizeof(float);
	size_t max_blocks = RING_BYTES / per_column / BLOCK;
	size_t blocks = ((size_t)run->width + BLOCK - 1) / BLOCK;
	max_blocks = max_blocks < 1 ? 1 : max_blocks;
	/* As few strips as fit, of about equal width, so the last one is not a sliver. */
	size_t strips = (blocks + max_blocks - 1) / max_blocks;
	return (int)((blocks + strips - 1) / strips * BLOCK);
}

static void *band_run(void *arg)
{
	struct flip_band *band = arg;
	const int strip = (int)band->row_len;
	for (int x = 0; x < band->run->width; x += strip) {
		band->x_begin = x;
		band->x_end = x + strip < band->run->width ? x + strip : band->run->width;
		for (int s = 0; s < band->ring_size; s++)
			band->ring_row[s] = -1;
		for (int y = band->y_begin; y < band->y_end; y++)
			compute_row(band, y);
	}
	return NULL;
}

static void band_free(struct flip_band *band)
{
	free(band->ring);
	free(band->ring_row);
	for (int p = 0; p < P_PLANES; p++)
		free(band->planes[p]);
	for (int c = 0; c < 3; c++)
		free(band->rgb[c]);
}

static int band_init(struct flip_band *band, const struct flip_run *run, int y_begin, int y_end)
{
	memset(band, 0, sizeof *band);
	band->run = run;
	band->y_begin = y_begin;
	band->y_end = y_end;
	band->ring_size = 2 * run->margin + 1;
	band->row_len = (size_t)strip_width(run);
	const size_t images = (size_t)(run->image_end - run->image_begin);
	band->ring = malloc((size_t)band->ring_size * images * H_ROWS * band->row_len * sizeof(float));
	band->ring_row = malloc((size_t)band->ring_size * sizeof(int));
	bool ok = band->ring && band->ring_row;
	for (int c = 0; c < 3; c++) {
		band->rgb[c] = calloc(band->row_len + 2 * (size_t)run->margin + VECTOR_SLACK, sizeof(float));
		ok = ok && band->rgb[c];
	}
	for (int p = 0; p < P_PLANES; p++) {
		band->planes[p] = malloc((band->row_len + 2 * (size_t)run->margin + VECTOR_SLACK) * sizeof(float));
		ok = ok && band->planes[p];
	}
	if (!ok) {
		band_free(band);
		return -1;
	}
	for (int s = 0; s < band->ring_size; s++)
		band->ring_row[s] = -1;
	return 0;
}

static int thread_count(const struct flip_run *run)
{
	long n = run->threads;
	if (n <= 0) {
		long cpus = sysconf(_SC_NPROCESSORS_ONLN);
		long by_size = (long)run->width * run->height / MIN_PIXELS_PER_THREAD;
		n = cpus < by_size ? cpus : by_size;
	}
	if (n > MAX_THREADS)
		n = MAX_THREADS;
	if (n > run->height)
		n = run->height;
	return n < 1 ? 1 : (int)n;
}

static int run_bands(struct flip_run *run, struct aa_error *err)
{
	const int threads = thread_count(run);
	struct flip_band bands[MAX_THREADS];
	pthread_t tids[MAX_THREADS];
	bool started[MAX_THREADS] = { false };
	int ready = 0;
	for (int t = 0; t < threads; t++) {
		int y0 = (int)((long)run->height * t / threads), y1 = (int)((long)run->height * (t + 1) / threads);
		if (band_init(&bands[t], run, y0, y1) != 0)
			break;
		ready++;
	}
	if (ready < threads) {
		for (int t = 0; t < ready; t++)
			band_free(&bands[t]);
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for FLIP on %dx%d images", run->width,
				    run->height);
	}
	/* Band 0 runs on this thread; a band whose thread cannot start runs here too. */
	for (int t = 1; t < threads; t++)
		started[t] = pthread_create(&tids[t], NULL, band_run, &bands[t]) == 0;
	band_run(&bands[0]);
	for (int t = 1; t < threads; t++) {
		if (started[t])
			pthread_join(tids[t], NULL);
		else
			band_run(&bands[t]);
	}
	for (int t = 0; t < threads; t++)
		band_free(&bands[t]);
	return 0;
}

static int run_setup(struct flip_run *run, struct aa_flip_filters *f, const struct aa_flip_options *opt,
		     int rw, int rh, int tw, int th, const void *rp, const void *tp, float *map,
		     struct aa_error *err)
{
	memset(run, 0, sizeof *run);
	if (rw != tw || rh != th)
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot compare a %dx%d image against a %dx%d reference",
				    tw, th, rw, rh);
	if (rw <= 0 || rh <= 0 || !rp || !tp || !map)
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot compare empty images");
	float ppd = opt && opt->ppd != 0.0f ? opt->ppd : AA_FLIP_DEFAULT_PPD;
	if (aa_flip_filters_init(ppd, f) != 0)
		return aa_error_set(err, AA_ERR_INVALID, "ppd", "pixels per degree must be in (0, %g], got %g",
				    (double)AA_FLIP_MAX_PPD, (double)ppd);
	run->width = rw;
	run->height = rh;
	run->threads = opt ? opt->threads : 0;
	run->f = f;
	run->margin = f->csf_radius > f->feature_radius ? f->csf_radius : f->feature_radius;
	run->cmax = aa_flip_max_color_distance();
	run->pccmax = FLIP_PC * run->cmax;
	run->map = map;
	run->image_begin = 0;
	run->image_end = 2;
	return 0;
}

/* Image `slot` of a run reads `pixels`, 8-bit sRGB or linear float. The reference tool reads v / 255 and
 * decodes sRGB in float; a table holds the 256 results. */
static void run_source(struct flip_run *run, int slot, const void *pixels, bool rgba8)
{
	if (rgba8) {
		for (int v = 0; v < 256; v++)
			run->srgb_table[v] = aa_flip_srgb_to_linear((float)v / 255.0f);
		run->src[slot].rgba8 = pixels;
	} else {
		run->src[slot].rgbaf = pixels;
	}
}

int aa_flip_ldr_rgba8(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
		      const struct aa_flip_options *opt, float *map, struct aa_error *err)
{
	struct flip_run run;
	struct aa_flip_filters f;
	if (run_setup(&run, &f, opt, ref->width, ref->height, test->width, test->height, ref->pixels,
		      test->pixels, map, err) != 0)
		return -1;
	run_source(&run, 0, ref->pixels, true);
	run_source(&run, 1, test->pixels, true);
	return run_bands(&run, err);
}

int aa_flip_ldr_linear(const struct aa_image_rgbaf *ref, const struct aa_image_rgbaf *test,
		       const struct aa_flip_options *opt, float *map, struct aa_error *err)
{
	struct flip_run run;
	struct aa_flip_filters f;
	if (run_setup(&run, &f, opt, ref->width, ref->height, test->width, test->height, ref->pixels,
		      test->pixels, map, err) != 0)
		return -1;
	run.src[0].rgbaf = ref->pixels;
	run.src[1].rgbaf = test->pixels;
	return run_bands(&run, err);
}

/* ------------------------------------------------------------------------------- the shared reference */

void aa_flip_reference_free(struct aa_flip_reference *ref)
{
	if (!ref)
		return;
	for (int q = 0; q < R_PLANES; q++)
		free(ref->plane[q]);
	free(ref);
}

/* Runs the ring over the reference alone (src[0]) and keeps its side of every pixel. A reference made
 * before at the same size keeps its planes: fresh pages of a few MB cost about as much as the filtering. */
static int reference_build(const struct aa_flip_options *opt, int w, int h, const void *pixels, bool rgba8,
			   struct aa_flip_reference **out, struct aa_error *err)
{
	struct aa_flip_reference *ref = *out;
	*out = NULL;
	if (ref && (ref->width != w || ref->height != h)) {
		aa_flip_reference_free(ref);
		ref = NULL;
	}
	if (!ref && !(ref = calloc(1, sizeof *ref)))
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for a FLIP reference");
	struct flip_run run;
	float unused_map;
	if (run_setup(&run, &ref->filters, opt, w, h, w, h, pixels, pixels, &unused_map, err) != 0) {
		aa_flip_reference_free(ref);
		return -1;
	}
	ref->width = w;
	ref->height = h;
	const size_t n = (size_t)w * h;
	bool ok = true;
	for (int q = 0; q < R_PLANES; q++) {
		/* calloc: the slack past the last pixel, which the colour kernel reads, is defined */
		if (!ref->plane[q])
			ref->plane[q] = calloc(n + BLOCK, sizeof(float));
		ok = ok && ref->plane[q];
	}
	if (!ok) {
		aa_flip_reference_free(ref);
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for the FLIP reference of a %dx%d image", w, h);
	}
	run_source(&run, 0, pixels, rgba8);
	run.map = NULL;
	run.image_begin = 0;
	run.image_end = 1;
	run.ref_out = ref;
	if (run_bands(&run, err) != 0) {
		aa_flip_reference_free(ref);
		return -1;
	}
	*out = ref;
	return 0;
}

int aa_flip_reference_rgba8(const struct aa_image_rgba8 *ref, const struct aa_flip_options *opt,
			    struct aa_flip_reference **out, struct aa_error *err)
{
	return reference_build(opt, ref->width, ref->height, ref->pixels, true, out, err);
}

int aa_flip_reference_linear(const struct aa_image_rgbaf *ref, const struct aa_flip_options *opt,
			     struct aa_flip_reference **out, struct aa_error *err)
{
	return reference_build(opt, ref->width, ref->height, ref->pixels, false, out, err);
}

/* The test side through the ring, the reference side read from ref. */
static int against(const struct aa_flip_reference *ref, int w, int h, const void *pixels, bool rgba8,
		   const struct aa_flip_options *opt, float *map, struct aa_error *err)
{
	if (!ref)
		return aa_error_set(err, AA_ERR_INVALID, "", "no FLIP reference");
	if (opt && opt->ppd != 0.0f && opt->ppd != ref->filters.ppd)
		return aa_error_set(err, AA_ERR_INVALID, "ppd",
				    "the FLIP reference was made at %g pixels per degree, not %g",
				    (double)ref->filters.ppd, (double)opt->ppd);
	struct flip_run run;
	struct aa_flip_filters unused;
	const struct aa_flip_options o = { .ppd = ref->filters.ppd, .threads = opt ? opt->threads : 0 };
	if (run_setup(&run, &unused, &o, ref->width, ref->height, w, h, pixels, pixels, map, err) != 0)
		return -1;
	run.f = &ref->filters;
	run_source(&run, 1, pixels, rgba8);
	run.image_begin = 1;
	run.ref_in = ref;
	return run_bands(&run, err);
}

int aa_flip_ldr_rgba8_against(const struct aa_flip_reference *ref, const struct aa_image_rgba8 *test,
			      const struct aa_flip_options *opt, float *map, struct aa_error *err)
{
	return against(ref, test->width, test->height, test->pixels, true, opt, map, err);
}

int aa_flip_ldr_linear_against(const struct aa_flip_reference *ref, const struct aa_image_rgbaf *test,
			       const struct aa_flip_options *opt, float *map, struct aa_error *err)
{
	return against(ref, test->width, test->height, test->pixels, false, opt, map, err);
}

int aa_flip_exposure_range(const struct aa_image_rgbaf *ref, enum aa_flip_tone_mapper tm, float *start,
			   float *stop, struct aa_error *err)
{
	size_t n = (size_t)ref->width * ref->height;
	float *lum = malloc(n * sizeof *lum), *sorted = malloc(n * sizeof *sorted);
	if (!lum || !sorted || n == 0) {
		free(lum);
		free(sorted);
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for the exposure range");
	}
	float y_max = -1e30f, y_min_positive = 1e30f;
	for (size_t i = 0; i < n; i++) {
		lum[i] = luminance(ref->pixels + 4 * i);
		y_max = lum[i] > y_max ? lum[i] : y_max;
		if (lum[i] > 0.0f && lum[i] < y_min_positive)
			y_min_positive = lum[i];
	}
	int rc = aa_flip_sort_floats(lum, n, sorted);
	/* The reference takes element N/2 of the sorted luminances, without averaging. */
	float y_median = rc == 0 ? sorted[n / 2] : 0.0f;
	free(lum);
	free(sorted);
	if (rc != 0)
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for the exposure range");
	if (!(y_max > 0.0f) || !isfinite(y_max))
		return aa_error_set(err, AA_ERR_INVALID, "",
				    "the reference has no positive finite luminance; give the start and stop exposures");
	/* More than half the pixels black would put the stop exposure at infinity: use the darkest lit pixel. */
	if (!(y_median > 0.0f))
		y_median = y_min_positive;
	float x_max = aa_flip_tone_xmax(tm);
	*start = log2f(x_max / y_max);
	*stop = log2f(x_max / y_median);
	return 0;
}

int aa_flip_hdr(const struct aa_image_rgbaf *ref, const struct aa_image_rgbaf *test,
		const struct aa_flip_options *opt, float *map, struct aa_flip_hdr_info *info, struct aa_error *err)
{
	struct flip_run run;
	struct aa_flip_filters f;
	if (run_setup(&run, &f, opt, ref->width, ref->height, test->width, test->height, ref->pixels,
		      test->pixels, map, err) != 0)
		return -1;
	enum aa_flip_tone_mapper tm = opt ? opt->tone_mapper : AA_FLIP_ACES;
	if ((int)tm < 0 || tm > AA_FLIP_REINHARD)
		return aa_error_set(err, AA_ERR_INVALID, "tone_mapper", "unknown tone mapper %d", (int)tm);
	float start = 0.0f, stop = 0.0f;
	if (!opt || !opt->have_start || !opt->have_stop) {
		if (aa_flip_exposure_range(ref, tm, &start, &stop, err) != 0)
			return -1;
	}
	if (opt && opt->have_start)
		start = opt->start_exposure;
	if (opt && opt->have_stop)
		stop = opt->stop_exposure;
	if (!isfinite(start) || !isfinite(stop) || start > stop)
		return aa_error_set(err, AA_ERR_INVALID, "exposure",
				    "the start exposure (%g) must not be above the stop exposure (%g)", (double)start,
				    (double)stop);
	int count = opt && opt->exposures > 0 ? opt->exposures : (int)ceilf(stop - start);
	if (count < 2)
		count = 2;
	if (count > MAX_EXPOSURES)
		return aa_error_set(err, AA_ERR_LIMIT, "exposure",
				    "%d exposures from %g to %g is more than %d; narrow the range", count, (double)start,
				    (double)stop, MAX_EXPOSURES);
	const float step = (stop - start) / (float)(count - 1);
	memset(map, 0, (size_t)ref->width * ref->height * sizeof *map);
	run.merge_max = true;
	for (int i = 0; i < 2; i++) {
		run.src[i].rgbaf = i == 0 ? ref->pixels : test->pixels;
		run.src[i].tone_map = true;
		run.src[i].tm = tm;
	}
	for (int i = 0; i < count; i++) {
		const float exposure = start + (float)i * step;
		const float scale = powf(2.0f, exposure);
		run.src[0].exposure_scale = run.src[1].exposure_scale = scale;
		if (run_bands(&run, err) != 0)
			return -1;
	}
	if (info) {
		info->start_exposure = start;
		info->stop_exposure = stop;
		info->exposures = count;
	}
	return 0;
}

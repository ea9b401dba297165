/* Trains RSAA's offset table (Reshetov 2012, section 2.3) from random one- and two-line pixel cases. */
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gpu/sample_positions.h"
#include "methods/rsaa_table.h"

/* ---------------------------------------------------------------- deterministic random numbers */

/* xoshiro256** seeded through splitmix64: fixed integer arithmetic, the same stream everywhere. */
struct rng {
	uint64_t s[4];
};

static uint64_t splitmix64(uint64_t *x)
{
	uint64_t z = (*x += UINT64_C(0x9e3779b97f4a7c15));
	z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
	z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
	return z ^ (z >> 31);
}

static void rng_seed(struct rng *r, uint64_t seed)
{
	for (int i = 0; i < 4; i++)
		r->s[i] = splitmix64(&seed);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

static uint64_t rng_next(struct rng *r)
{
	uint64_t *s = r->s;
	uint64_t result = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
	s[2] ^= s[0];
	s[3] ^= s[1];
	s[1] ^= s[2];
	s[0] ^= s[3];
	s[2] ^= t;
	s[3] = rotl(s[3], 45);
	return result;
}

/* uniform in [0, 1), exact multiples of 2^-53 */
static double rng_unit(struct rng *r) { return (double)(rng_next(r) >> 11) * 0x1.0p-53; }

/* ---------------------------------------------------------------- one training case */

/* A line n.x = c with |n| = 1. */
struct line {
	double nx, ny, c;
};

/* A random line crossing the pixel [-0.5, 0.5]^2: through a point uniform in the pixel, in a direction
 * uniform on the circle (rejection from the disc, so no trigonometry). Lines through the centre itself
 * are redrawn (the centre must be on one side). */
static struct line random_line(struct rng *r)
{
	for (;;) {
		double px = rng_unit(r) - 0.5, py = rng_unit(r) - 0.5;
		double x = 2.0 * rng_unit(r) - 1.0, y = 2.0 * rng_unit(r) - 1.0, l2 = x * x + y * y;
		if (l2 > 1.0 || l2 < 1e-12)
			continue;
		double l = sqrt(l2);
		struct line ln = {x / l, y / l, 0.0};
		ln.c = ln.nx * px + ln.ny * py;
		if (fabs(ln.c) > 1e-9)
			return ln;
	}
}

/* Side of the line the pixel centre is on: inside(p) is true on the centre's side. */
static bool on_centre_side(const struct line *l, double x, double y)
{
	return (l->nx * x + l->ny * y - l->c) * -l->c > 0.0;
}

/* Area of the pixel [-0.5, 0.5]^2 on the centre's side of every line (exact polygon clipping). */
static double covered_area(const struct line *lines, int count)
{
	double poly[2][12][2] = {{{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}};
	int n = 4, cur = 0;
	for (int k = 0; k < count; k++) {
		const struct line *l = &lines[k];
		double side = l->c > 0 ? -1.0 : 1.0; /* centre's side: side * (n.x - c) > 0 */
		int m = 0;
		for (int i = 0; i < n; i++) {
			const double *a = poly[cur][i], *b = poly[cur][(i + 1) % n];
			double da = side * (l->nx * a[0] + l->ny * a[1] - l->c);
			double db = side * (l->nx * b[0] + l->ny * b[1] - l->c);
			if (da >= 0) {
				poly[!cur][m][0] = a[0];
				poly[!cur][m++][1] = a[1];
			}
			if ((da >= 0) != (db >= 0)) {
				double t = da / (da - db);
				poly[!cur][m][0] = a[0] + t * (b[0] - a[0]);
				poly[!cur][m++][1] = a[1] + t * (b[1] - a[1]);
			}
		}
		n = m;
		cur = !cur;
	}
	double area = 0;
	for (int i = 0; i < n; i++) {
		const double *a = poly[cur][i], *b = poly[cur][(i + 1) % n];
		area += a[0] * b[1] - b[0] * a[1];
	}
	return fabs(area) * 0.5;
}

/* ---------------------------------------------------------------- the fit */

/* One training case: key = kind (0 one line, 1 two lines) << 17 | mask << 9 | pattern, where pattern holds
 * which of the 3x3 neighbouring pixel centres lie in the centre's region (the 1-spp image is white there,
 * black elsewhere), and t is the exact covered area (the supersampled value). Sorted by key, then t. */
struct sample_case {
	uint32_t key;
	double t;
};

static int case_order(const void *a, const void *b)
{
	const struct sample_case *x = a, *y = b;
	if (x->key != y->key)
		return x->key < y->key ? -1 : 1;
	return (x->t > y->t) - (x->t < y->t);
}

static int pattern_bit(int dx, int dy) { return (dy + 1) * 3 + (dx + 1); }

/* The cases of one mask grouped by pattern: [lo, hi) in the sorted array, with prefix sums of t. */
struct pattern_group {
	unsigned pattern;
	long lo, hi;
};

struct fit_data {
	const struct sample_case *cases;
	const double *prefix; /* prefix[i] = sum of t over cases[0..i) */
	const struct pattern_group *groups;
	int group_count;
};

/* Sum over the mask's cases of |bilinear(offset) - t|: the bilinear value is one number per pattern, and
 * the cases of a pattern are sorted by t, so each pattern costs one binary search. */
static double abs_error(const struct fit_data *f, double ox, double oy)
{
	int qx = ox >= 1.0 ? 0 : (int)floor(ox), qy = oy >= 1.0 ? 0 : (int)floor(oy);
	double u = ox - qx, v = oy - qy, e = 0;
	for (int k = 0; k < f->group_count; k++) {
		unsigned p = f->groups[k].pattern;
		double c00 = (p >> pattern_bit(qx, qy)) & 1, c10 = (p >> pattern_bit(qx + 1, qy)) & 1;
		double c01 = (p >> pattern_bit(qx, qy + 1)) & 1, c11 = (p >> pattern_bit(qx + 1, qy + 1)) & 1;
		double pred = (c00 * (1 - u) + c10 * u) * (1 - v) + (c01 * (1 - u) + c11 * u) * v;
		long lo = f->groups[k].lo, hi = f->groups[k].hi, a = lo, b = hi;
		while (a < b) { /* first case with t > pred */
			long mid = a + (b - a) / 2;
			if (f->cases[mid].t <= pred)
				a = mid + 1;
			else
				b = mid;
		}
		e += pred * (double)(a - lo) - (f->prefix[a] - f->prefix[lo]) + (f->prefix[hi] - f->prefix[a]) -
		     pred * (double)(hi - a);
	}
	return e;
}

/* The offset in [-1, 1]^2 with the least summed absolute error: a grid in steps of 1/32 (among equal
 * errors the shortest offset wins, so flat directions stay at 0), then a shrinking pattern search that
 * moves only on strict improvement. Returns the error sum there. */
static double fit_offset(const struct fit_data *f, double count, float out[2])
{
	enum { G = 64 };
	double tol = 1e-9 * (count > 1 ? count : 1), be = INFINITY, bx = 0, by = 0;
	for (int j = -G; j <= G; j++)
		for (int i = -G; i <= G; i++) {
			double x = (double)i / G, y = (double)j / G, e = abs_error(f, x, y);
			if (e < be - tol || (e <= be + tol && x * x + y * y < bx * bx + by * by))
				be = e, bx = x, by = y;
		}
	static const int dir[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
	for (double step = 0.5 / G; step > 1e-5; step *= 0.5)
		for (bool moved = true; moved;) {
			moved = false;
			for (int k = 0; k < 8; k++) {
				double x = bx + dir[k][0] * step, y = by + dir[k][1] * step;
				if (fabs(x) > 1 || fabs(y) > 1)
					continue;
				double e = abs_error(f, x, y);
				if (e < be - tol) {
					be = e, bx = x, by = y;
					moved = true;
				}
			}
		}
	out[0] = (float)bx;
	out[1] = (float)by;
	return be;
}

/* ---------------------------------------------------------------- the table */

void rsaa_fallback_offset(const float (*pos)[2], int n, unsigned mask, float out[2])
{
	int far = -1, dissimilar = 0;
	double far_d = -1;
	for (int i = 0; i < n; i++) {
		if (mask & (1u << i))
			continue;
		dissimilar++;
		double x = pos[i][0] - 0.5, y = pos[i][1] - 0.5, d = x * x + y * y;
		if (d >= far_d)
			far_d = d, far = i;
	}
	out[0] = out[1] = 0;
	if (far < 0)
		return;
	double x = pos[far][0] - 0.5, y = pos[far][1] - 0.5;
	double m = fmax(fabs(x), fabs(y)), len = (double)dissimilar / (n + 1);
	if (m > 0) {
		out[0] = (float)(x / m * len);
		out[1] = (float)(y / m * len);
	}
}

int rsaa_table_train(const float (*pos)[2], int n, long cases, uint64_t seed, struct rsaa_table *out)
{
	if (!pos || n < 1 || n > RSAA_MAX_SAMPLES || cases < 2 || cases > 100000000L || !out)
		return -1;
	struct timespec t0, t1;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	int masks = 1 << n;
	struct sample_case *all = malloc((size_t)cases * sizeof *all);
	double *prefix = malloc(((size_t)cases + 1) * sizeof *prefix);
	struct pattern_group *groups = malloc(512 * sizeof *groups);
	if (!all || !prefix || !groups) {
		free(all);
		free(prefix);
		free(groups);
		return -1;
	}
	memset(out, 0, sizeof *out);
	out->samples = n;
	out->masks = masks;
	out->training_cases = cases;
	out->seed = seed;

	/* half the cases with one line, half with two */
	struct rng rng;
	rng_seed(&rng, seed);
	for (long k = 0; k < cases; k++) {
		int kind = (int)(k & 1), count = kind + 1;
		struct line lines[2];
		for (int i = 0; i < count; i++)
			lines[i] = random_line(&rng);
		unsigned mask = 0, pattern = 0;
		for (int i = 0; i < n; i++) {
			bool in = true;
			for (int j = 0; j < count; j++)
				in = in && on_centre_side(&lines[j], pos[i][0] - 0.5, pos[i][1] - 0.5);
			mask |= (unsigned)in << i;
		}
		for (int dy = -1; dy <= 1; dy++)
			for (int dx = -1; dx <= 1; dx++) {
				bool in = true;
				for (int j = 0; j < count && (dx || dy); j++)
					in = in && on_centre_side(&lines[j], dx, dy);
				pattern |= (unsigned)in << pattern_bit(dx, dy);
			}
		all[k].key = (uint32_t)kind << 17 | mask << 9 | pattern;
		all[k].t = covered_area(lines, count);
	}
	qsort(all, (size_t)cases, sizeof *all, case_order);
	prefix[0] = 0;
	for (long i = 0; i < cases; i++)
		prefix[i + 1] = prefix[i] + all[i].t;

	/* first[kind * masks + mask]: where that bucket's cases start in the sorted array (sorting by key
	 * orders by kind, then mask) */
	long *first = calloc((size_t)2 * masks + 1, sizeof *first);
	if (!first) {
		free(all);
		free(prefix);
		free(groups);
		return -1;
	}
	for (long i = 0; i < cases; i++)
		first[(all[i].key >> 17) * (unsigned)masks + ((all[i].key >> 9) & 255u) + 1]++;
	for (int b = 0; b < 2 * masks; b++)
		first[b + 1] += first[b];
	for (int m = 0; m < masks; m++) {
		long count[2] = {first[m + 1] - first[m], first[masks + m + 1] - first[masks + m]};
		/* mask 0 (no subsample agrees with the centre) is sub-pixel detail, not a thin wedge around the
		 * centre; the paper's table gives it the fallback value too */
		int cls = m == masks - 1 ? RSAA_CLASS_FULL
			  : m == 0	  ? RSAA_CLASS_FALLBACK
			  : count[0] > 0  ? RSAA_CLASS_ONE_LINE
			  : count[1] > 0  ? RSAA_CLASS_TWO_LINE
					  : RSAA_CLASS_FALLBACK;
		out->mask_class[m] = (unsigned char)cls;
		out->class_count[cls]++;
		if (cls == RSAA_CLASS_FALLBACK) {
			rsaa_fallback_offset(pos, n, (unsigned)m, out->offset[m]);
			continue;
		}
		if (cls == RSAA_CLASS_FULL)
			continue;
		int kind = cls == RSAA_CLASS_TWO_LINE;
		long lo = first[kind * masks + m], hi = first[kind * masks + m + 1];
		struct fit_data f = {all, prefix, groups, 0};
		for (long i = lo; i < hi;) {
			long j = i;
			while (j < hi && all[j].key == all[i].key)
				j++;
			groups[f.group_count++] = (struct pattern_group){all[i].key & 511u, i, j};
			i = j;
		}
		double e = fit_offset(&f, (double)(hi - lo), out->offset[m]);
		out->cases[m] = (uint32_t)(hi - lo);
		out->mean_abs_error[m] = e / (double)(hi - lo);
	}
	free(first);
	free(all);
	free(prefix);
	free(groups);
	clock_gettime(CLOCK_MONOTONIC, &t1);
	out->train_ms = (double)(t1.tv_sec - t0.tv_sec) * 1e3 + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-6;
	return 0;
}

/* ---------------------------------------------------------------- the process-wide cache */

static pthread_mutex_t cache_lock = PTHREAD_MUTEX_INITIALIZER;
static struct rsaa_table *cache[2]; /* [0]: 4 samples, [1]: 8 samples; freed at exit by the OS */

const struct rsaa_table *rsaa_table_get(int n)
{
	if (n != 4 && n != 8)
		return NULL;
	pthread_mutex_lock(&cache_lock);
	struct rsaa_table **slot = &cache[n == 8];
	if (!*slot) {
		struct rsaa_table *t = malloc(sizeof *t);
		if (t && rsaa_table_train(aa_standard_sample_positions(n), n, RSAA_TRAINING_CASES,
					  RSAA_TRAINING_SEED, t) == 0)
			*slot = t;
		else
			free(t);
	}
	const struct rsaa_table *t = *slot;
	pthread_mutex_unlock(&cache_lock);
	return t;
}

double rsaa_sadp(const double p1[3], const double n1[3], const double p2[3], const double n2[3])
{
	double r[3] = {p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]};
	double len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
	double scale = fmax(fmax(fabs(p1[0]), fabs(p1[1])), fmax(fabs(p1[2]), 1.0));
	if (!(len > 1e-6 * scale)) /* coincident: no direction to measure along */
		return 0.0;
	double a = fabs(n1[0] * r[0] + n1[1] * r[1] + n1[2] * r[2]);
	double b = fabs(n2[0] * r[0] + n2[1] * r[1] + n2[2] * r[2]);
	return (a + b) / len;
}

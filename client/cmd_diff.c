/* aalab diff: compares two images of any format OpenImageIO reads with PSNR, SSIM, FLIP and the Fourier
 * bands, like idiff or the FLIP tool, and exits 1 when a --fail-above or --fail-below threshold trips. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "client.h"
#include "metrics/metrics.h"

const char aa_diff_help[] =
	"usage: aalab diff REF TEST [options]\n"
	"\n"
	"Compares TEST against the reference REF (PNG, EXR, JPEG, TIFF, ... anything OpenImageIO reads; grey\n"
	"is used as RGB, alpha is ignored). 8-bit and 16-bit images are compared as 8-bit sRGB with LDR-FLIP;\n"
	"a reference ending in .exr or .hdr makes it a comparison of linear floats with HDR-FLIP.\n"
	"\n"
	"  --metrics LIST          psnr, ssim, flip, fourier or all (default psnr,ssim,flip); psnr also\n"
	"                          gives mse, rmsd and max_abs\n"
	"  --json                  print the results as one JSON object\n"
	"  --error-map OUT.png     write the FLIP error map (magma colour map; computes FLIP; default: none)\n"
	"  --no-magma              write the error map in grey levels instead\n"
	"  --fail-above NAME=X     exit 1 when NAME is above X (repeatable; default: none)\n"
	"  --fail-below NAME=X     exit 1 when NAME is below X (repeatable; default: none). NAME, for both:\n"
	"                          psnr mse rmsd max_abs ssim flip (the mean) flip.median flip.q1\n"
	"                          flip.q3 flip.min flip.max fourier.low fourier.mid fourier.high\n"
	"  --ppd X, --pixels-per-degree X\n"
	"                          pixels per degree for FLIP (default 67.02: a 0.7 m wide 4K monitor at 0.7 m)\n"
	"  --viewing-conditions D,W,R  pixels per degree from distance D and monitor width W in metres and\n"
	"                          R pixels across (default: --ppd's)\n"
	"  --hdr, --ldr            force HDR-FLIP (linear floats) or LDR-FLIP (8-bit sRGB) (default: HDR for a\n"
	"                          reference ending in .exr or .hdr, else LDR)\n"
	"  --tone-mapper NAME      HDR: aces (default), hable or reinhard\n"
	"  --start-exposure X, --stop-exposure X, --exposures N\n"
	"                          HDR: the exposure range (log2) and steps; default from the reference\n"
	"  --timings               also print how long reading and each metric took\n"
	"\n"
	"PSNR, MSE, RMSD and max_abs are in 8-bit units over R, G and B (peak 255); for HDR, in linear units\n"
	"(peak 1). PSNR of identical images is infinite (null in JSON, with \"identical\": true). FLIP is 0\n"
	"for identical images and at most about 1. The Fourier bands split the MSE by spatial frequency:\n"
	"low < 1/16, mid 1/16 to 1/4, high >= 1/4 cycles per pixel; they add up to the MSE.\n"
	"\n"
	"Exit status: 0 compared (and every threshold held), 1 a threshold tripped, 2 bad arguments, an\n"
	"unreadable or unwritable file, images of different sizes or an unsupported channel layout.\n";

enum { WANT_PSNR = 1, WANT_SSIM = 2, WANT_FLIP = 4, WANT_FOURIER = 8 };

#define MAX_THRESHOLDS 32

struct threshold {
	char name[32];
	double limit;
	bool above;  /* fail when the value is above the limit (else below) */
	double value;
	bool failed;
};

struct diff_opts {
	const char *ref_path, *test_path, *error_map;
	int want, threshold_want; /* metrics asked for, and those the thresholds need */
	bool json, magma, timings;
	int hdr; /* -1 auto, 0 LDR, 1 HDR */
	struct aa_flip_options flip;
	int threshold_count;
	struct threshold thresholds[MAX_THRESHOLDS];
};

struct diff_result {
	int width, height;
	bool hdr;
	double mse, rmsd, psnr, max_abs, ssim;
	bool identical;
	struct aa_flip_stats flip;
	struct aa_flip_hdr_info hdr_info;
	double fourier[AA_FOURIER_BANDS];
	double ms_read, ms_psnr, ms_ssim, ms_flip, ms_fourier;
};

static double now_ms(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* ------------------------------------------------------------------------------------------ arguments */

static const char *const threshold_names[] = {
	"psnr", "mse", "rmsd", "max_abs", "ssim", "flip", "flip.mean", "flip.median", "flip.q1", "flip.q3",
	"flip.min", "flip.max", "fourier.low", "fourier.mid", "fourier.high",
};

/* The metric group a threshold name needs, or 0 when the name is unknown. */
static int threshold_needs(const char *name)
{
	for (size_t i = 0; i < sizeof threshold_names / sizeof threshold_names[0]; i++)
		if (strcmp(name, threshold_names[i]) == 0)
			return i < 4 ? WANT_PSNR : i == 4 ? WANT_SSIM : i < 12 ? WANT_FLIP : WANT_FOURIER;
	return 0;
}

static int parse_metrics(const char *text, int *want)
{
	char buf[256];
	snprintf(buf, sizeof buf, "%s", text);
	*want = 0;
	for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
		if (strcmp(tok, "psnr") == 0 || strcmp(tok, "mse") == 0 || strcmp(tok, "rmsd") == 0 ||
		    strcmp(tok, "max_abs") == 0)
			*want |= WANT_PSNR;
		else if (strcmp(tok, "ssim") == 0)
			*want |= WANT_SSIM;
		else if (strcmp(tok, "flip") == 0)
			*want |= WANT_FLIP;
		else if (strcmp(tok, "fourier") == 0)
			*want |= WANT_FOURIER;
		else if (strcmp(tok, "all") == 0)
			*want |= WANT_PSNR | WANT_SSIM | WANT_FLIP | WANT_FOURIER;
		else {
			fprintf(stderr, "aalab diff: metrics: unknown metric '%s' (psnr, ssim, flip, fourier, all)\n", tok);
			return -1;
		}
	}
	if (!*want) {
		fprintf(stderr, "aalab diff: metrics: name at least one of psnr, ssim, flip, fourier\n");
		return -1;
	}
	return 0;
}

static int parse_double(const char *flag, const char *text, double *out)
{
	char *end;
	errno = 0;
	*out = strtod(text, &end);
	if (errno || end == text || *end || !isfinite(*out)) {
		fprintf(stderr, "aalab diff: %s: expected a number, got '%s'\n", flag, text);
		return -1;
	}
	return 0;
}

static int parse_threshold(struct diff_opts *o, const char *text, bool above)
{
	const char *flag = above ? "fail-above" : "fail-below";
	const char *eq = strchr(text, '=');
	if (o->threshold_count >= MAX_THRESHOLDS) {
		fprintf(stderr, "aalab diff: %s: at most %d thresholds\n", flag, MAX_THRESHOLDS);
		return -1;
	}
	struct threshold *t = &o->thresholds[o->threshold_count];
	if (!eq || eq == text || (size_t)(eq - text) >= sizeof t->name) {
		fprintf(stderr, "aalab diff: %s: expected NAME=VALUE (e.g. flip=0.05), got '%s'\n", flag, text);
		return -1;
	}
	memcpy(t->name, text, (size_t)(eq - text));
	t->name[eq - text] = '\0';
	int needs = threshold_needs(t->name);
	if (!needs) {
		fprintf(stderr, "aalab diff: %s: unknown metric '%s' (see aalab diff --help)\n", flag, t->name);
		return -1;
	}
	if (parse_double(flag, eq + 1, &t->limit))
		return -1;
	t->above = above;
	o->threshold_want |= needs;
	o->threshold_count++;
	return 0;
}

static int parse_viewing(const char *text, float *ppd)
{
	double d, w, r;
	char extra;
	if (sscanf(text, "%lf,%lf,%lf%c", &d, &w, &r, &extra) != 3 || !(d > 0) || !(w > 0) || !(r > 0)) {
		fprintf(stderr, "aalab diff: viewing-conditions: expected DISTANCE,WIDTH,PIXELS (metres, metres, "
			"pixels), e.g. 0.7,0.7,3840; got '%s'\n", text);
		return -1;
	}
	*ppd = aa_flip_ppd((float)d, (float)w, (float)r);
	return 0;
}

/* Returns 0 to go on, or the exit status (help printed: 0; bad arguments: 2) plus 1000. */
static int parse_args(int argc, char **argv, struct diff_opts *o)
{
	enum { OPT_METRICS = 256, OPT_JSON, OPT_MAP, OPT_NO_MAGMA, OPT_ABOVE, OPT_BELOW, OPT_PPD, OPT_VIEW, OPT_HDR,
	       OPT_LDR, OPT_TM, OPT_START, OPT_STOP, OPT_EXPOSURES, OPT_TIMINGS, OPT_HELP };
	static const struct option opts[] = {
		{"metrics", required_argument, 0, OPT_METRICS}, {"json", no_argument, 0, OPT_JSON},
		{"error-map", required_argument, 0, OPT_MAP}, {"no-magma", no_argument, 0, OPT_NO_MAGMA},
		{"fail-above", required_argument, 0, OPT_ABOVE}, {"fail-below", required_argument, 0, OPT_BELOW},
		{"ppd", required_argument, 0, OPT_PPD}, {"pixels-per-degree", required_argument, 0, OPT_PPD},
		{"viewing-conditions", required_argument, 0, OPT_VIEW}, {"hdr", no_argument, 0, OPT_HDR},
		{"ldr", no_argument, 0, OPT_LDR}, {"tone-mapper", required_argument, 0, OPT_TM},
		{"start-exposure", required_argument, 0, OPT_START}, {"stop-exposure", required_argument, 0, OPT_STOP},
		{"exposures", required_argument, 0, OPT_EXPOSURES}, {"timings", no_argument, 0, OPT_TIMINGS},
		{"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0},
	};
	memset(o, 0, sizeof *o);
	o->want = WANT_PSNR | WANT_SSIM | WANT_FLIP;
	o->magma = true;
	o->hdr = -1;
	bool ppd_given = false;
	int c, tm;
	double v;
	optind = 1;
	opterr = 0;
	while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
		switch (c) {
		case OPT_METRICS:
			if (parse_metrics(optarg, &o->want))
				return 1002;
			break;
		case OPT_JSON: o->json = true; break;
		case OPT_MAP: o->error_map = optarg; break;
		case OPT_NO_MAGMA: o->magma = false; break;
		case OPT_ABOVE:
		case OPT_BELOW:
			if (parse_threshold(o, optarg, c == OPT_ABOVE))
				return 1002;
			break;
		case OPT_PPD:
			if (parse_double("ppd", optarg, &v))
				return 1002;
			if (!(v > 0) || v > AA_FLIP_MAX_PPD) {
				fprintf(stderr, "aalab diff: ppd: must be in (0, %g], got %s\n", (double)AA_FLIP_MAX_PPD, optarg);
				return 1002;
			}
			o->flip.ppd = (float)v;
			ppd_given = true;
			break;
		case OPT_VIEW:
			/* --ppd wins when both are given, as in the FLIP tool */
			if (parse_viewing(optarg, ppd_given ? &(float){ 0 } : &o->flip.ppd))
				return 1002;
			break;
		case OPT_HDR: o->hdr = 1; break;
		case OPT_LDR: o->hdr = 0; break;
		case OPT_TM:
			if ((tm = aa_flip_tone_mapper_parse(optarg)) < 0) {
				fprintf(stderr, "aalab diff: tone-mapper: unknown '%s' (aces, hable, reinhard)\n", optarg);
				return 1002;
			}
			o->flip.tone_mapper = (enum aa_flip_tone_mapper)tm;
			break;
		case OPT_START:
		case OPT_STOP:
			if (parse_double(c == OPT_START ? "start-exposure" : "stop-exposure", optarg, &v))
				return 1002;
			if (c == OPT_START) {
				o->flip.have_start = true;
				o->flip.start_exposure = (float)v;
			} else {
				o->flip.have_stop = true;
				o->flip.stop_exposure = (float)v;
			}
			break;
		case OPT_EXPOSURES:
			if (parse_double("exposures", optarg, &v))
				return 1002;
			if (v < 2 || v > 100 || v != floor(v)) {
				fprintf(stderr, "aalab diff: exposures: a whole number from 2 to 100, got %s\n", optarg);
				return 1002;
			}
			o->flip.exposures = (int)v;
			break;
		case OPT_TIMINGS: o->timings = true; break;
		case OPT_HELP: fputs(aa_diff_help, stdout); return 1000;
		default:
			fprintf(stderr, "aalab diff: unknown or incomplete option '%s'\n", argv[optind - 1]);
			fputs("usage: aalab diff REF TEST [options]; see aalab diff --help\n", stderr);
			return 1002;
		}
	}
	if (argc - optind != 2) {
		fprintf(stderr, "aalab diff: expected two images, REF and TEST, got %d\n", argc - optind);
		fputs("usage: aalab diff REF TEST [options]; see aalab diff --help\n", stderr);
		return 1002;
	}
	o->ref_path = argv[optind];
	o->test_path = argv[optind + 1];
	o->want |= o->threshold_want;
	if (o->error_map)
		o->want |= WANT_FLIP;
	if (o->hdr < 0) {
		const char *dot = strrchr(o->ref_path, '.');
		o->hdr = dot && (strcasecmp(dot, ".exr") == 0 || strcasecmp(dot, ".hdr") == 0);
	}
	return 0;
}

/* ------------------------------------------------------------------------------------------ reading */

struct read_job {
	const char *path;
	bool hdr;
	struct aa_image_rgba8 img8;
	struct aa_image_rgbaf imgf;
	int rc;
	struct aa_error err;
};

static void *read_one(void *arg)
{
	struct read_job *j = arg;
	j->rc = j->hdr ? aa_image_read_rgbaf(j->path, &j->imgf, NULL, &j->err)
		       : aa_image_read_rgba8(j->path, &j->img8, &j->err);
	return NULL;
}

/* Reads both files, each on its own thread (decoding dominates a PNG comparison). */
static int read_images(const struct diff_opts *o, struct read_job jobs[2])
{
	memset(jobs, 0, 2 * sizeof *jobs);
	jobs[0].path = o->ref_path;
	jobs[1].path = o->test_path;
	jobs[0].hdr = jobs[1].hdr = o->hdr;
	pthread_t tid;
	bool threaded = pthread_create(&tid, NULL, read_one, &jobs[1]) == 0;
	read_one(&jobs[0]);
	if (threaded)
		pthread_join(tid, NULL);
	else
		read_one(&jobs[1]);
	for (int i = 0; i < 2; i++)
		if (jobs[i].rc) {
			fprintf(stderr, "aalab diff: %s\n", jobs[i].err.message);
			return -1;
		}
	return 0;
}

static int find_nonfinite(const struct aa_image_rgbaf *img, const char *path)
{
	size_t n = (size_t)img->width * img->height;
	for (size_t p = 0; p < n; p++)
		for (int c = 0; c < 3; c++)
			if (!isfinite(img->pixels[4 * p + c])) {
				fprintf(stderr, "aalab diff: '%s' has a non-finite value (NaN or Inf) at pixel (%zu, %zu)\n",
					path, p % (size_t)img->width, p / (size_t)img->width);
				return -1;
			}
	return 0;
}

/* ------------------------------------------------------------------------------------------ metrics */

/* MSE, PSNR and max |diff| over R, G and B of 8-bit images, exact in integers (as aa_metrics_compare). */
static void psnr_rgba8(const struct aa_image_rgba8 *a, const struct aa_image_rgba8 *b, struct diff_result *r)
{
	size_t n = (size_t)a->width * a->height;
	uint64_t sum = 0;
	int max_abs = 0;
	for (size_t i = 0; i < 4 * n; i += 4)
		for (int c = 0; c < 3; c++) {
			int d = (int)a->pixels[i + c] - (int)b->pixels[i + c];
			sum += (uint64_t)(d * d);
			max_abs = abs(d) > max_abs ? abs(d) : max_abs;
		}
	r->mse = (double)sum / (3.0 * (double)n);
	r->identical = sum == 0;
	r->psnr = aa_psnr_from_mse(r->mse, 255.0);
	r->max_abs = max_abs;
}

static double max_abs_rgbaf(const struct aa_image_rgbaf *a, const struct aa_image_rgbaf *b)
{
	size_t n = (size_t)a->width * a->height;
	double m = 0;
	for (size_t i = 0; i < 4 * n; i += 4)
		for (int c = 0; c < 3; c++)
			m = fmax(m, fabs((double)a->pixels[i + c] - (double)b->pixels[i + c]));
	return m;
}

/* R, G, B planes of doubles: the two images' values, or their difference. */
static double *planes_rgbaf(const struct aa_image_rgbaf *a, const struct aa_image_rgbaf *b)
{
	size_t n = (size_t)a->width * a->height;
	double *p = malloc(3 * n * sizeof *p);
	if (p)
		for (size_t i = 0; i < n; i++)
			for (int c = 0; c < 3; c++)
				p[c * n + i] = (double)a->pixels[4 * i + c] - (b ? (double)b->pixels[4 * i + c] : 0.0);
	return p;
}

/* SSIM of linear float images: per channel, over the reference's range of values, averaged. */
static double ssim_rgbaf(const struct aa_image_rgbaf *ref, const struct aa_image_rgbaf *test)
{
	size_t n = (size_t)ref->width * ref->height;
	double *r = planes_rgbaf(ref, NULL), *t = planes_rgbaf(test, NULL), sum = 0;
	double lo = INFINITY, hi = -INFINITY;
	for (size_t i = 0; r && i < 3 * n; i++) {
		lo = fmin(lo, r[i]);
		hi = fmax(hi, r[i]);
	}
	double range = hi > lo ? hi - lo : 1.0;
	for (int c = 0; r && t && c < 3; c++)
		sum += aa_ssim_channel(r + c * n, t + c * n, ref->width, ref->height, range);
	free(r);
	free(t);
	return r && t ? sum / 3.0 : NAN;
}

static int fourier_rgbaf(const struct aa_image_rgbaf *ref, const struct aa_image_rgbaf *test, double bands[],
			 struct aa_error *err)
{
	size_t n = (size_t)ref->width * ref->height;
	double *e = planes_rgbaf(test, ref);
	if (!e)
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for the error image");
	const double *fields[3] = { e, e + n, e + 2 * n };
	int rc = aa_fourier_band_energy(fields, 3, ref->width, ref->height, 0, bands, err);
	for (int b = 0; b < AA_FOURIER_BANDS; b++)
		bands[b] /= 3.0 * (double)n;
	free(e);
	return rc;
}

/* Computes what o->want asks for; writes the error map. Returns 0 or an exit status. */
static int compute(const struct diff_opts *o, struct read_job img[2], struct diff_result *r)
{
	struct aa_error err = { 0 };
	const bool hdr = o->hdr;
	const size_t n = (size_t)r->width * r->height;
	double t = now_ms();
	if (o->want & WANT_PSNR) {
		if (hdr) {
			if (aa_metrics_psnr_linear(&img[0].imgf, &img[1].imgf, &r->mse, &r->psnr, &r->identical, &err))
				goto fail;
			r->max_abs = max_abs_rgbaf(&img[0].imgf, &img[1].imgf);
		} else {
			psnr_rgba8(&img[0].img8, &img[1].img8, r);
		}
		r->rmsd = sqrt(r->mse);
		r->ms_psnr = now_ms() - t;
	}
	t = now_ms();
	if (o->want & WANT_SSIM) {
		r->ssim = hdr ? ssim_rgbaf(&img[0].imgf, &img[1].imgf) : aa_ssim_rgba8(&img[0].img8, &img[1].img8);
		r->ms_ssim = now_ms() - t;
	}
	t = now_ms();
	if (o->want & WANT_FLIP) {
		float *map = malloc(n * sizeof *map);
		int rc = !map ? aa_error_set(&err, AA_ERR_LIMIT, "", "out of memory for the FLIP map")
			 : hdr ? aa_flip_hdr(&img[0].imgf, &img[1].imgf, &o->flip, map, &r->hdr_info, &err)
			       : aa_flip_ldr_rgba8(&img[0].img8, &img[1].img8, &o->flip, map, &err);
		if (rc == 0 && aa_flip_pool(map, n, &r->flip) != 0)
			rc = aa_error_set(&err, AA_ERR_LIMIT, "", "out of memory pooling the FLIP map");
		r->ms_flip = now_ms() - t;
		struct aa_image_rgba8 picture = { 0 };
		if (rc == 0 && o->error_map) {
			if (aa_image_rgba8_alloc(&picture, r->width, r->height) != 0) {
				rc = aa_error_set(&err, AA_ERR_LIMIT, "", "out of memory for the error map image");
			} else {
				aa_flip_colorize(map, o->magma, &picture);
				if (aa_image_write_png(o->error_map, &picture, &err) != 0)
					err.code = AA_ERR_INVALID; /* a path the user gave: bad input, exit 2 */
				rc = err.code ? -1 : 0;
			}
		}
		aa_image_rgba8_free(&picture);
		free(map);
		if (rc)
			goto fail;
	}
	t = now_ms();
	if (o->want & WANT_FOURIER) {
		if (hdr ? fourier_rgbaf(&img[0].imgf, &img[1].imgf, r->fourier, &err)
			: aa_fourier_bands_rgba8(&img[0].img8, &img[1].img8, r->fourier, &err))
			goto fail;
		r->ms_fourier = now_ms() - t;
	}
	return 0;
fail:
	fprintf(stderr, "aalab diff: %s%s%s\n", err.path, err.path[0] ? ": " : "", err.message);
	return err.code == AA_ERR_LIMIT || err.code == AA_ERR_INTERNAL ? AA_EXIT_FAILED : AA_EXIT_USAGE;
}

/* ------------------------------------------------------------------------------------------ output */

static double threshold_value(const struct diff_result *r, const char *name)
{
	const struct aa_flip_stats *f = &r->flip;
	const char *const *names = threshold_names;
	/* identical images have an infinite PSNR: above any limit */
	const double psnr = r->identical ? INFINITY : r->psnr;
	const double values[] = { psnr, r->mse, r->rmsd, r->max_abs, r->ssim, f->mean, f->mean, f->weighted_median,
				  f->weighted_q1, f->weighted_q3, f->min, f->max, r->fourier[0], r->fourier[1],
				  r->fourier[2] };
	for (size_t i = 0; i < sizeof values / sizeof values[0]; i++)
		if (strcmp(name, names[i]) == 0)
			return values[i];
	return NAN;
}

static json_t *num(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

static void print_json(const struct diff_opts *o, const struct diff_result *r, bool failed)
{
	json_t *root = json_pack("{s:s, s:s, s:i, s:i, s:s}", "reference", o->ref_path, "test", o->test_path,
				 "width", r->width, "height", r->height, "mode", r->hdr ? "hdr" : "ldr");
	json_t *ms = json_pack("{s:o}", "read", num(r->ms_read));
	if (o->want & WANT_PSNR) {
		json_object_set_new(root, "psnr", r->identical ? json_null() : num(r->psnr));
		json_object_set_new(root, "identical", json_boolean(r->identical));
		json_object_set_new(root, "mse", num(r->mse));
		json_object_set_new(root, "rmsd", num(r->rmsd));
		json_object_set_new(root, "max_abs", num(r->max_abs));
		json_object_set_new(ms, "psnr", num(r->ms_psnr));
	}
	if (o->want & WANT_SSIM) {
		json_object_set_new(root, "ssim", num(r->ssim));
		json_object_set_new(ms, "ssim", num(r->ms_ssim));
	}
	if (o->want & WANT_FLIP) {
		const struct aa_flip_stats *f = &r->flip;
		json_t *flip = json_pack("{s:o, s:o, s:o, s:o, s:o, s:o, s:o}", "mean", num(f->mean), "weighted_median",
					 num(f->weighted_median), "weighted_q1", num(f->weighted_q1), "weighted_q3",
					 num(f->weighted_q3), "min", num(f->min), "max", num(f->max), "ppd",
					 num(o->flip.ppd ? o->flip.ppd : AA_FLIP_DEFAULT_PPD));
		if (r->hdr) {
			json_object_set_new(flip, "tone_mapper", json_string(aa_flip_tone_mapper_name(o->flip.tone_mapper)));
			json_object_set_new(flip, "start_exposure", num(r->hdr_info.start_exposure));
			json_object_set_new(flip, "stop_exposure", num(r->hdr_info.stop_exposure));
			json_object_set_new(flip, "exposures", json_integer(r->hdr_info.exposures));
		}
		if (o->error_map)
			json_object_set_new(flip, "error_map", json_string(o->error_map));
		json_object_set_new(root, "flip", flip);
		json_object_set_new(ms, "flip", num(r->ms_flip));
	}
	if (o->want & WANT_FOURIER) {
		json_t *fo = json_object();
		for (int b = 0; b < AA_FOURIER_BANDS; b++)
			json_object_set_new(fo, aa_fourier_band_names[b], num(r->fourier[b]));
		json_object_set_new(fo, "edges", json_pack("[f, f]", AA_FOURIER_LOW_MID, AA_FOURIER_MID_HIGH));
		json_object_set_new(root, "fourier", fo);
		json_object_set_new(ms, "fourier", num(r->ms_fourier));
	}
	json_t *th = json_array();
	for (int i = 0; i < o->threshold_count; i++) {
		const struct threshold *t = &o->thresholds[i];
		json_array_append_new(th, json_pack("{s:s, s:o, s:o, s:b}", "metric", t->name, t->above ? "above" : "below",
						    json_real(t->limit), "value", num(t->value), "failed", t->failed));
	}
	json_object_set_new(root, "thresholds", th);
	json_object_set_new(root, "failed", json_boolean(failed));
	json_object_set_new(root, "timings_ms", ms);
	json_dumpf(root, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
	fputc('\n', stdout);
	json_decref(root);
}

static void print_text(const struct diff_opts *o, const struct diff_result *r)
{
	printf("reference  %s\ntest       %s\nsize       %dx%d, %s\n", o->ref_path, o->test_path, r->width,
	       r->height, r->hdr ? "linear float (HDR)" : "8-bit sRGB (LDR)");
	const char *unit = r->hdr ? "linear units" : "8-bit units";
	if (o->want & WANT_PSNR) {
		if (r->identical)
			printf("PSNR       inf (identical)\n");
		else
			printf("PSNR       %.4f dB  (MSE %.6g, RMSD %.6g, max |diff| %.6g, in %s)\n", r->psnr, r->mse,
			       r->rmsd, r->max_abs, unit);
	}
	if (o->want & WANT_SSIM)
		printf("SSIM       %.6f\n", r->ssim);
	if (o->want & WANT_FLIP) {
		const struct aa_flip_stats *f = &r->flip;
		printf("FLIP       %.6f  mean, %s-FLIP at %.2f pixels per degree\n", f->mean, r->hdr ? "HDR" : "LDR",
		       (double)(o->flip.ppd ? o->flip.ppd : AA_FLIP_DEFAULT_PPD));
		printf("           weighted median %.6f, weighted quartiles %.6f / %.6f, min %.6f, max %.6f\n",
		       f->weighted_median, f->weighted_q1, f->weighted_q3, f->min, f->max);
		if (r->hdr)
			printf("           %s tone mapper, exposures %.4f to %.4f in %d steps\n",
			       aa_flip_tone_mapper_name(o->flip.tone_mapper), (double)r->hdr_info.start_exposure,
			       (double)r->hdr_info.stop_exposure, r->hdr_info.exposures);
		if (o->error_map)
			printf("           error map: %s\n", o->error_map);
	}
	if (o->want & WANT_FOURIER)
		printf("Fourier    MSE by frequency: low %.6g, mid %.6g, high %.6g (%s; edges 1/16 and 1/4 cycles "
		       "per pixel)\n", r->fourier[0], r->fourier[1], r->fourier[2], unit);
	if (o->timings) {
		printf("time       read %.1f ms", r->ms_read);
		const char *names[] = { "psnr", "ssim", "flip", "fourier" };
		const double ms[] = { r->ms_psnr, r->ms_ssim, r->ms_flip, r->ms_fourier };
		for (int i = 0; i < 4; i++)
			if (o->want & (1 << i))
				printf(", %s %.1f ms", names[i], ms[i]);
		putchar('\n');
	}
}

int cmd_diff(int argc, char **argv)
{
	struct diff_opts *o = calloc(1, sizeof *o);
	if (!o)
		return AA_EXIT_FAILED;
	int status = parse_args(argc, argv, o);
	if (status) {
		free(o);
		return status - 1000;
	}
	struct diff_result r = { .mse = NAN, .psnr = NAN, .rmsd = NAN, .max_abs = NAN, .ssim = NAN, .hdr = o->hdr };
	struct read_job img[2];
	double t = now_ms();
	status = AA_EXIT_USAGE;
	if (read_images(o, img))
		goto out;
	r.ms_read = now_ms() - t;
	int rw = o->hdr ? img[0].imgf.width : img[0].img8.width, rh = o->hdr ? img[0].imgf.height : img[0].img8.height;
	int tw = o->hdr ? img[1].imgf.width : img[1].img8.width, th = o->hdr ? img[1].imgf.height : img[1].img8.height;
	if (rw != tw || rh != th) {
		fprintf(stderr, "aalab diff: the images differ in size: reference '%s' is %dx%d, test '%s' is %dx%d\n",
			o->ref_path, rw, rh, o->test_path, tw, th);
		goto out;
	}
	if (o->hdr && (find_nonfinite(&img[0].imgf, o->ref_path) || find_nonfinite(&img[1].imgf, o->test_path)))
		goto out;
	r.width = rw;
	r.height = rh;
	status = compute(o, img, &r);
	if (status)
		goto out;
	bool failed = false;
	for (int i = 0; i < o->threshold_count; i++) {
		struct threshold *th = &o->thresholds[i];
		th->value = threshold_value(&r, th->name);
		/* a value that could not be computed (NaN) fails the gate rather than passing it silently */
		th->failed = isnan(th->value) || (th->above ? th->value > th->limit : th->value < th->limit);
		failed |= th->failed;
	}
	if (o->json)
		print_json(o, &r, failed);
	else
		print_text(o, &r);
	for (int i = 0; i < o->threshold_count; i++) {
		const struct threshold *th = &o->thresholds[i];
		if (th->failed && isnan(th->value))
			fprintf(stderr, "aalab diff: %s could not be computed, so its threshold fails\n", th->name);
		else if (th->failed)
			fprintf(stderr, "aalab diff: %s = %.6g is %s %.6g\n", th->name, th->value,
				th->above ? "above" : "below", th->limit);
	}
	status = failed ? AA_EXIT_FAILED : AA_EXIT_OK;
out:
	for (int i = 0; i < 2; i++) {
		aa_image_rgba8_free(&img[i].img8);
		aa_image_rgbaf_free(&img[i].imgf);
	}
	free(o);
	return status;
}

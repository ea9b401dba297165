/* Prints the metrics of TEST.png against REF.png as one JSON object, for the oracle tests and benchmarks.
 * Usage: metrics_tool [--time N] REF TEST
 *   --time N  also runs SSIM N more times and reports the mean wall time as "ssim_seconds". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "image/image.h"
#include "metrics/metrics.h"

/* JSON has no NaN: non-finite numbers become null, as in the service's results. */
static void print_number(const char *name, double v, const char *sep)
{
	if (isfinite(v))
		printf("\"%s\":%.17g%s", name, v, sep);
	else
		printf("\"%s\":null%s", name, sep);
}

static double now_seconds(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
	int repeat = 0, arg = 1;
	if (argc == 5 && strcmp(argv[1], "--time") == 0) {
		repeat = atoi(argv[2]);
		arg = 3;
	}
	if (argc - arg != 2 || repeat < 0) {
		fprintf(stderr, "usage: metrics_tool [--time N] REF TEST\n");
		return 2;
	}
	struct aa_error err = { 0 };
	struct aa_image_rgba8 ref = { 0 }, test = { 0 };
	struct aa_metrics m;
	int status = 1;
	if (aa_image_read_rgba8(argv[arg], &ref, &err) != 0 || aa_image_read_rgba8(argv[arg + 1], &test, &err) != 0 ||
	    aa_metrics_compare(&ref, &test, &m, &err) != 0) {
		fprintf(stderr, "metrics_tool: %s\n", err.message);
		goto out;
	}
	double seconds = NAN;
	if (repeat > 0) {
		double start = now_seconds();
		for (int i = 0; i < repeat; i++)
			aa_ssim_rgba8(&ref, &test);
		seconds = (now_seconds() - start) / repeat;
	}
	printf("{\"width\":%d,\"height\":%d,", ref.width, ref.height);
	print_number("mse", m.mse, ",");
	print_number("rmsd", m.rmsd, ",");
	print_number("psnr", m.psnr, ",");
	printf("\"identical\":%s,", m.identical ? "true" : "false");
	print_number("snr", m.snr, ",");
	print_number("ssim", m.ssim, ",");
	print_number("max_abs", m.max_abs, ",");
	if (repeat > 0)
		print_number("ssim_seconds", seconds, ",");
	printf("\"exceed\":[");
	for (int i = 0; i < AA_THRESHOLD_COUNT; i++)
		printf("%.17g%s", m.exceed[i], i + 1 < AA_THRESHOLD_COUNT ? "," : "");
	printf("]}\n");
	status = 0;
out:
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
	return status;
}

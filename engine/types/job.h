/* A job: what to render and compare (the spec, parsed from the job JSON of docs/job-format.md), and what
 * came out (the result, serialised to results.json by engine/results/). */
#ifndef AA_JOB_H
#define AA_JOB_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <jansson.h>

#include "util/error.h"
#include "types/method.h"
#include "metrics/metrics.h"

#define AA_MAX_METHODS 24
#define AA_MAX_PASSES 16
#define AA_MAX_INVALID_TARGETS 8 /* per frame, the intermediates with invalid texels that are named */
#define AA_MAX_MEMORY_ITEMS 24
#define AA_MAX_WARNINGS 32         /* as AA_SCENE_MAX_WARNINGS */
#define AA_LABEL_MAX 128

struct aa_method_spec {
	const struct aa_method *method;
	struct aa_method_params params;
	char label[AA_LABEL_MAX];  /* canonical text (aa_method_label), e.g. "ssaa", "ssaa:samples=4" */
};

/* One case of a suite (a job that is a matrix of cases, docs/job-format.md "Suites"): a scene on a
 * camera path at a size, over a run of frames; the job's methods, reference and timing apply to each. */
#define AA_MAX_CASES 64
#define AA_CASE_SCENE_MAX 256
struct aa_case_spec {
	char scene[AA_CASE_SCENE_MAX]; /* name or path, as given */
	char path[64];
	int width, height;
	int frames;
	int first_frame;
};

/* Labels name a run for a build farm (commit, branch, build URL, machine): key=value, stored with the
 * results and the daemon's job, never part of what is rendered. */
#define AA_MAX_LABELS 16
struct aa_label {
	char key[32];              /* letters, digits, '.', '_', '-' */
	char value[256];
};

struct aa_job_spec {
	char scene[1024];          /* name or path, as given */
	char path[64];             /* camera path name: "default", "static" or a path of the scene */
	int width, height;
	int frames;
	int first_frame;           /* frame index of the first rendered frame on the path (time = index/fps) */
	int reference_samples;     /* N of the accumulated reference; N/2 is the convergence check */
	int timing_repeat;         /* timing.repeat: each method's frame is rendered and timed this many times
				    * (the first is scored); the reference is rendered once */
	bool timing_auto;          /* timing.repeat "auto" (the default): timing_repeat is the fewest repeats
				    * that give each method AA_MIN_TIMED_RENDERS timed renders over the frames
				    * (aa_timing_auto_repeat), set for each case */
	int method_count;
	struct aa_method_spec methods[AA_MAX_METHODS];
	bool keep_frames;          /* keep every frame's image in events (the CLI writes PNGs) */
	bool linear_frames;        /* also store each frame's linear colour as raw RGBA16F (streamable) */
	bool exr_frames;           /* also write each frame's linear colour as float EXR (aalab run --exr) */
	bool viewer;               /* report.html's image viewer and its viewer/NNNN.js frame scripts (the
				    * frames again as data: URLs, ~1.3x their disk); false: the PNGs only */
	double over_threshold;     /* idiff-style count: a pixel is over when any of R,G,B differs from the
				    * reference by more than this share of full scale (8-bit sRGB) */
	int inject_nonfinite_frame; /* tests only, not in job JSON: this frame's shading emits NaN/Inf in a
				     * sparse pixel pattern (-1: never) */
	char name[128];            /* optional user label of the job */
	/* suites: with is_suite the cases below are the job (the single-case fields above are unused);
	 * without it the job is its one case, the fields above (aa_job_case) */
	bool is_suite;
	int case_count;
	struct aa_case_spec cases[AA_MAX_CASES];
	char suite[64];            /* the suite's name: jobs of one suite are compared and plotted together */
	int label_count;
	struct aa_label labels[AA_MAX_LABELS];
	char baseline[160];        /* aalabd: the job to compare with, "000042" or "latest:KEY=VALUE,..." */
	/* shards (docs/farm.md): job field shard.warmup, -1 for each method's default (aa_shard_warmup) */
	int shard_warmup;
	/* not in job JSON, set for a shard's run: frames rendered before first_frame by the methods with
	 * history only (no reference, not scored), and the whole job's ordinal of first_frame, by which the
	 * method order rotates as in the unsharded run */
	int warmup_frames;
	int order_ordinal;
	/* reference.samples "auto": per frame, N doubles from AA_REFERENCE_AUTO_START until the N/2-vs-N
	 * convergence PSNR reaches reference_target_psnr or N reaches reference_samples (reference.max_samples) */
	bool reference_auto;
	double reference_target_psnr;
	bool verdicts;             /* job key "verdicts": judge every case and method (docs/hard-cases.md) */
	bool debug_targets;        /* job key "debug_targets": read back every intermediate image of every
				    * method after each frame and count its non-finite texels (engine/render/debug_targets.c) */
	/* not in job JSON: the reference store. explain_key: an AA_EVENT_REFERENCE_KEY before each frame's
	 * reference; reference_verify (aalab cache verify): every reference is rendered and compared bit for
	 * bit with its stored entry, nothing is read from or written to the store */
	bool explain_key;
	bool reference_verify;
};

/* Shared limits (the daemon adds its own budget on top). */
#define AA_MAX_SIZE 8192
#define AA_MAX_FRAMES 100000
#define AA_MAX_REFERENCE_SAMPLES 4096
#define AA_REFERENCE_AUTO_TARGET_PSNR 45.0  /* reference.target_psnr's default */
#define AA_REFERENCE_AUTO_MAX_SAMPLES 256   /* reference.max_samples' default */
#define AA_MAX_REPEAT 100
#define AA_MIN_TIMED_RENDERS 5 /* fewer timed renders per method and its cost is not ranked */
#define AA_MAX_SHARD_WARMUP 1000
#define AA_OVER_THRESHOLD_DEFAULT 0.01 /* the report viewer's default: more than 2 of 255 levels */

/* ---- results ---- */

struct aa_pass_timing {
	char name[32];
	double gpu_ms;
};

struct aa_memory_item {
	char name[48];
	uint64_t bytes;
};

struct aa_frame_result {
	int frame;                 /* frame index on the path */
	int pass_count;
	struct aa_pass_timing passes[AA_MAX_PASSES]; /* the method's own passes, in order */
	double gpu_ms;             /* sum of passes */
	double cpu_ms;             /* wall time of record + submit + wait for this method's frame */
	struct aa_metrics metrics; /* against this frame's reference */
	long nonfinite;            /* NaN/Inf values found in the method's float output (must be 0) */
	long over_threshold;       /* pixels where any of R,G,B differs from the reference by more than the
				    * job's over_threshold (idiff's count; 8-bit sRGB) */
	double flicker;            /* mean |(m[t] - m[t-1]) - (r[t] - r[t-1])| over pixels and R,G,B, 8-bit
				    * units: change between frames the reference does not have; NAN at frame 0 */
	long out_of_range;         /* finite values of the float output outside the colour range (negative
				    * R, G or B, below -1/1024): a verdict of docs/hard-cases.md */
	double change, ref_change; /* mean |m[t] - m[t-1]| and |r[t] - r[t-1]| (8-bit sRGB, R,G,B); NAN at
				    * frame 0: the "stuck" verdict */
	/* job option debug_targets only (0 otherwise): the method's intermediate images read back after this
	 * frame, the texels among them with a NaN/Inf channel (depth: also outside [0, 1]), and which images */
	int targets_read;
	long intermediate_invalid;
	int invalid_target_count;
	struct aa_target_count { char name[48]; long texels; } invalid_targets[AA_MAX_INVALID_TARGETS];
};

/* One timed render of a method's frame: the scored one (repeat 0) or a re-timing (timing.repeat). */
struct aa_timed_render {
	int ordinal;               /* frame ordinal: frames[ordinal].passes name pass_ms */
	int repeat;                /* 0 = the scored render */
	int position;              /* place in its round's method order, 0 = first after the reference */
	double gpu_ms, cpu_ms;
	int pass_count;            /* 0 when this render's passes were not the scored render's */
	double pass_ms[AA_MAX_PASSES];
};

struct aa_method_result {
	char label[AA_LABEL_MAX];
	const struct aa_method *method;
	struct aa_method_params params;
	char path_taken[160];      /* e.g. "4x4 ordered grid, box filter", "hardware 4x", "virtual samples" */
	int memory_count;
	struct aa_memory_item memory[AA_MAX_MEMORY_ITEMS]; /* every image/buffer the method allocated */
	uint64_t memory_bytes;     /* sum of memory[] */
	int frame_count;
	struct aa_frame_result *frames;
	int timed_count;           /* frames x timing.repeat when complete */
	struct aa_timed_render *timed; /* [ordinal * repeat + r] */
};

struct aa_reference_frame {
	int frame;
	char cache[12];            /* the reference store: "hit", "miss", "continued" (an auto reference went on
				    * from a stored sum), "" without a store or when the frame cannot be keyed */
	double gpu_ms;             /* all N jittered renders + accumulation */
	double cpu_ms;
	bool convergence_identical;
	double convergence_psnr;   /* PSNR (8-bit sRGB) of the N/2-sample vs the N-sample image; NAN if identical */
	double convergence_mse;
	long nonfinite;            /* NaN/Inf values in the accumulated float image (must be 0) */
	bool reused;               /* static camera, nothing moves: frame 0's reference, not re-rendered */
	int samples;               /* N this frame's reference used (reference.samples "auto": the N reached) */
};

/* What the reference store did for a job's frames (engine/reference/reference_cache.h). */
#define AA_REFERENCE_CACHE_WARNINGS 4
struct aa_reference_cache_result {
	bool used;                 /* the job had a store (off: false, and nothing else is set) */
	int hits;                  /* frames served whole from the store */
	int misses;                /* frames rendered, whole or (continued) in part */
	int continued;             /* of the misses: auto references that went on from a stored sum */
	int unkeyed;               /* frames that cannot be keyed (a scene built in code, or a file that changed
				    * while the scene loaded): rendered, not stored */
	uint64_t bytes_read, bytes_written;
	int discarded;             /* entries that failed their check: removed and rendered again */
	int verified, mismatched;  /* verify mode (aalab cache verify): entries compared bit for bit, and those
				    * that differed from the render */
	char verified_key[65];     /* verify mode: the key of the last entry compared (hex) */
	int warning_count;         /* the first few messages, e.g. of a discarded entry */
	char warnings[AA_REFERENCE_CACHE_WARNINGS][256];
};

struct aa_reference_result {
	int samples;               /* N, or with auto_samples the cap (reference.max_samples) */
	bool auto_samples;         /* reference.samples "auto": each frame's N is in frames[].samples */
	double target_psnr;        /* with auto_samples */
	char pattern[32];          /* "owen-sobol" (AA_REFERENCE_PATTERN) */
	uint64_t memory_bytes;
	int frame_count;
	struct aa_reference_frame *frames;
	struct aa_reference_cache_result cache;
};

struct aa_plan_entry {
	char pass[32];
	char reason[160];
	bool ran;
};

struct aa_job_result {
	struct aa_job_spec spec;
	char scene_name[64];
	char scene_file[1024];
	uint64_t scene_triangles;
	char device_name[256];
	char driver_info[256];
	double timestamp_period_ns;
	int plan_count;
	struct aa_plan_entry plan[AA_MAX_PASSES];
	int warning_count;         /* what loading the scene dropped or approximated, once each */
	int warnings_dropped;      /* more than AA_MAX_WARNINGS: counted, not kept */
	char warnings[AA_MAX_WARNINGS][256];
	struct aa_reference_result reference;
	int method_count;
	struct aa_method_result methods[AA_MAX_METHODS];
	double wall_seconds;
	char started_at[32];       /* ISO 8601 UTC */
	double fps;                /* the scene's frames per second (report.html plays frames at it) */
};

/* ---- events out ---- */

enum aa_event_type {
	AA_EVENT_JOB_STARTED,      /* result->plan, device and scene are filled */
	AA_EVENT_REFERENCE_FRAME,  /* frame's reference done; image = reference image */
	AA_EVENT_METHOD_FRAME,     /* method_index's frame done; image = its output; diff = |diff| x 4;
	                            * flip_map = FLIP error map */
	AA_EVENT_PROGRESS,         /* done/total units of work */
	AA_EVENT_JOB_FINISHED,
	AA_EVENT_REFERENCE_KEY,    /* spec.explain_key: text = the frame's reference key, part by part, and
				    * whether the store has it */
};

struct aa_event {
	enum aa_event_type type;
	const struct aa_job_result *result; /* the result so far */
	int frame;                 /* frame index on the path (REFERENCE_FRAME, METHOD_FRAME) */
	int frame_ordinal;         /* 0..frames-1 */
	int method_index;          /* METHOD_FRAME */
	const struct aa_image_rgba8 *image;  /* 8-bit sRGB, as written to PNG and scored */
	const struct aa_image_rgbaf *linear; /* the same frame in linear float, before encoding */
	const struct aa_image_rgba8 *diff;
	const struct aa_image_rgba8 *flip_map; /* METHOD_FRAME: the FLIP error map in the magma colour map */
	int done, total;           /* PROGRESS */
	const char *text;          /* REFERENCE_KEY */
	int case_index;            /* the case of a suite (aa_suite_run); 0 otherwise */
};

/* Return non-zero to cancel the job. */
typedef int (*aa_event_fn)(const struct aa_event *ev, void *user);

#endif

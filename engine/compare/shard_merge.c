/* Shards' results: written with the whole job they belong to, read back, and merged into the results of
 * the whole job (docs/farm.md, "Merging"). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "run/farm.h"
#include "run/shard.h"
#include "results/results.h"
#include "compare/shard_merge.h"
#include "report/report.h"
#include "run/job_spec.h"

/* Each frame's error-threshold curve, per method: what results.json stores only as a mean. */
static json_t *curves_json(const struct aa_job_result *r)
{
	json_t *curves = json_array();
	for (int i = 0; curves && i < r->method_count; i++) {
		json_t *frames = json_array();
		for (int k = 0; frames && k < r->methods[i].frame_count; k++) {
			json_t *curve = json_array();
			for (int t = 0; curve && t < AA_THRESHOLD_COUNT; t++) {
				const double v = r->methods[i].frames[k].metrics.exceed[t];
				json_array_append_new(curve, isfinite(v) ? json_real(v) : json_null());
			}
			json_array_append_new(frames, curve);
		}
		json_array_append_new(curves, frames);
	}
	return curves;
}

int aa_shard_results_write(const struct aa_suite_result *r, const struct aa_job_spec *whole, int index, int count,
			   const char *dir, struct aa_error *err)
{
	if (r->case_count < 1)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "no results to write");
	/* the reports (and, rewritten below with the shard's key, results.json) as for any run */
	if (aa_suite_results_write(r, dir, err))
		return -1;
	json_t *root = aa_suite_results_to_json(r), *shard = aa_shard_json(whole, index, count);
	json_t *curves = json_array();
	/* so that the merged curve is the mean over every frame of the job, as the unsharded run computes it:
	 * per method for a job, per case and method for a suite */
	for (int c = 0; curves && c < r->case_count; c++)
		json_array_append_new(curves, curves_json(r->cases[c]));
	if (curves && !r->spec.is_suite) {
		json_t *one = json_incref(json_array_get(curves, 0));
		json_decref(curves);
		curves = one;
	}
	if (!root || !shard || !curves || json_object_set_new(shard, "error_threshold_curves", curves) < 0 ||
	    json_object_set_new(root, "shard", shard) < 0) {
		json_decref(root);
		if (!root)
			json_decref(shard);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory building results.json");
	}
	/* 17 significant digits, unlike the 15 of an unsharded run's results.json: every double reads back
	 * exactly, so that the merged summaries are those of the unsharded run to the last bit */
	char *text = json_dumps(root, JSON_INDENT(2) | JSON_REAL_PRECISION(17));
	json_decref(root);
	size_t len = text ? strlen(text) : 0;
	char *with_newline = text ? realloc(text, len + 2) : NULL;
	if (!with_newline) {
		free(text);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing results.json");
	}
	with_newline[len] = '\n';
	with_newline[len + 1] = '\0';
	int rc = aa_results_write_file_atomic(dir, "results.json", with_newline, len + 1, err);
	free(with_newline);
	return rc;
}

/* ---- merging ---- */

struct shard_doc {
	const char *dir;
	json_t *doc;
	const json_t *shard;
	int index, count, warmup;
	const char *hash;
};

static json_t *load_results(const char *dir, bool *absent, struct aa_error *err)
{
	char path[4200];
	snprintf(path, sizeof path, "%s/results.json", dir);
	*absent = false;
	if (access(path, F_OK) != 0 && (errno == ENOENT || errno == ENOTDIR)) {
		*absent = true;
		return NULL;
	}
	json_error_t je;
	json_t *doc = json_load_file(path, 0, &je);
	if (!doc)
		aa_error_set(err, AA_ERR_INVALID, "", "%s: line %d: %s", path, je.line, je.text);
	return doc;
}

static int read_image(const char *dir, const char *kind, const char *label, int ordinal, struct aa_image_rgba8 *img)
{
	char rel[512], path[4800];
	aa_results_frame_relpath(kind, label, ordinal, rel, sizeof rel);
	snprintf(path, sizeof path, "%s/%s", dir, rel);
	struct aa_error ignored;
	return access(path, R_OK) == 0 ? aa_image_read_rgba8(path, img, &ignored) : -1;
}

/* Flicker of the first frame of shard s (its shard could not see the frame before): from the images of
 * the last frame of shard s-1 and the first of shard s, the 8-bit images each scored. */
static void border_flicker(const struct aa_shard_merge *m, int s, int begin, FILE *notes)
{
	const struct aa_job_result *r = m->result->cases[0];
	struct aa_image_rgba8 ref_prev = {0}, ref = {0}, out_prev = {0}, out = {0};
	int prev_begin, prev_end;
	aa_shard_range(r->spec.frames, s - 1, m->shard_count, &prev_begin, &prev_end);
	bool ok = read_image(m->dirs[s - 1], "frames", "reference", prev_end - prev_begin - 1, &ref_prev) == 0 &&
		  read_image(m->dirs[s], "frames", "reference", 0, &ref) == 0;
	for (int i = 0; i < r->method_count; i++) {
		struct aa_frame_result *f = &r->methods[i].frames[begin];
		bool have = ok && read_image(m->dirs[s - 1], "frames", r->methods[i].label, prev_end - prev_begin - 1,
					     &out_prev) == 0 &&
			    read_image(m->dirs[s], "frames", r->methods[i].label, 0, &out) == 0 &&
			    out.width == ref.width && out.height == ref.height && out_prev.width == ref.width &&
			    out_prev.height == ref.height && ref_prev.width == ref.width && ref_prev.height == ref.height;
		if (have)
			f->flicker = aa_metrics_flicker(&out, &out_prev, &ref, &ref_prev);
		else if (notes)
			fprintf(notes, "%s: flicker of frame %d not computed: the images of frames %d and %d are not in "
				"the shards (keep_frames)\n", r->methods[i].label, f->frame, f->frame - 1, f->frame);
		aa_image_rgba8_free(&out_prev);
		aa_image_rgba8_free(&out);
	}
	aa_image_rgba8_free(&ref_prev);
	aa_image_rgba8_free(&ref);
}

/* Copies shard s's result into the whole job's at ordinal begin. */
static void place_shard(struct aa_job_result *w, const struct aa_job_result *s, int begin)
{
	const int repeat = w->spec.timing_repeat;
	for (int k = 0; k < s->reference.frame_count; k++)
		w->reference.frames[begin + k] = s->reference.frames[k];
	/* the store's counts add up over the shards (a shard without a store leaves them as they are) */
	struct aa_reference_cache_result *wc = &w->reference.cache;
	const struct aa_reference_cache_result *sc = &s->reference.cache;
	if (sc->used) {
		wc->used = true;
		wc->hits += sc->hits;
		wc->misses += sc->misses;
		wc->continued += sc->continued;
		wc->unkeyed += sc->unkeyed;
		wc->bytes_read += sc->bytes_read;
		wc->bytes_written += sc->bytes_written;
		wc->discarded += sc->discarded;
		for (int i = 0; i < sc->warning_count && wc->warning_count < AA_REFERENCE_CACHE_WARNINGS; i++)
			memcpy(wc->warnings[wc->warning_count++], sc->warnings[i], sizeof wc->warnings[0]);
	}
	for (int i = 0; i < w->method_count; i++) {
		const struct aa_method_result *sm = &s->methods[i];
		struct aa_method_result *wm = &w->methods[i];
		for (int k = 0; k < sm->frame_count; k++)
			wm->frames[begin + k] = sm->frames[k];
		for (int k = 0; k < sm->timed_count; k++) {
			struct aa_timed_render *t = &wm->timed[begin * repeat + k];
			*t = sm->timed[k];
			t->ordinal += begin;
		}
	}
}

/* The shards none of docs is, named by their frames (or a suite's cases); AA_ERR_INVALID when any. */
static int check_shards(struct shard_doc *docs, int n, int count, const struct aa_job_spec *whole,
			struct aa_error *err)
{
	char missing[600] = "";
	int absent = 0;
	for (int s = 0; s < count; s++) {
		int have = 0;
		for (int k = 0; k < n; k++)
			have += docs[k].doc && docs[k].index == s;
		if (have)
			continue;
		int b, e;
		size_t len = strlen(missing);
		if (whole->is_suite) {
			aa_shard_cases(whole, s, count, &b, &e);
			for (int c = b; c < e; c++) {
				char id[512];
				aa_case_id(whole, c, id, sizeof id);
				len = strlen(missing);
				if (len < sizeof missing)
					snprintf(missing + len, sizeof missing - len, "%s%s", absent || c > b ? ", " : "", id);
			}
			len = strlen(missing);
			if (len < sizeof missing)
				snprintf(missing + len, sizeof missing - len, " (shard %d of %d)", s, count);
		} else {
			aa_shard_range(whole->frames, s, count, &b, &e);
			if (len < sizeof missing)
				snprintf(missing + len, sizeof missing - len, "%s%d-%d (shard %d of %d)", absent ? ", " : "",
					 whole->first_frame + b, whole->first_frame + e - 1, s, count);
		}
		absent++;
	}
	if (absent)
		return aa_error_set(err, AA_ERR_INVALID, "", "missing %s %s; run %s again and merge",
				    whole->is_suite ? "cases" : "frames", missing, absent > 1 ? "those shards" : "that shard");
	return 0;
}

static const struct shard_doc *doc_of(const struct shard_doc *docs, int s)
{
	while (!docs->doc || docs->index != s)
		docs++;
	return docs;
}

/* Earliest start, the sum of wall times (the machine time of the whole job), and a note when a shard ran on
 * another device than shard 0. */
static void account(struct aa_suite_result *w, const struct aa_job_result *part, const char *started_at,
		    double wall_seconds, const char *dir, FILE *notes)
{
	if (!w->started_at[0] || strcmp(started_at, w->started_at) < 0) /* ISO 8601 UTC sorts as text */
		snprintf(w->started_at, sizeof w->started_at, "%s", started_at);
	if (isfinite(wall_seconds))
		w->wall_seconds += wall_seconds;
	if (w->case_count > 0 && notes && strcmp(part->device_name, w->cases[0]->device_name) != 0)
		fprintf(notes, "%s ran on %s, shard 0 on %s: their times are not comparable\n", dir, part->device_name,
			w->cases[0]->device_name);
}

/* A job's shards: frames placed at their job ordinals. */
static int merge_frames(struct aa_shard_merge *out, const struct shard_doc *docs, const struct aa_job_spec *whole,
			FILE *notes, struct aa_error *err)
{
	struct aa_job_result *w = calloc(1, sizeof *w), *part = calloc(1, sizeof *part);
	int rc = -1;
	if (!w || !part) {
		free(w);
		free(part);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	}
	w->spec = *whole;
	w->method_count = whole->method_count;
	w->reference.frames = calloc((size_t)whole->frames, sizeof *w->reference.frames);
	w->reference.frame_count = whole->frames;
	bool ok = w->reference.frames != NULL;
	for (int i = 0; i < whole->method_count; i++) {
		struct aa_method_result *m = &w->methods[i];
		snprintf(m->label, sizeof m->label, "%s", whole->methods[i].label);
		m->method = whole->methods[i].method;
		m->params = whole->methods[i].params;
		m->frames = calloc((size_t)whole->frames, sizeof *m->frames);
		m->timed = calloc((size_t)whole->frames * (size_t)whole->timing_repeat, sizeof *m->timed);
		m->frame_count = whole->frames;
		m->timed_count = whole->frames * whole->timing_repeat;
		ok = ok && m->frames && m->timed;
	}
	out->result->cases[0] = w;
	out->result->case_count = 1;
	if (!ok) {
		aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		goto done;
	}
	for (int s = 0; s < out->shard_count; s++) {
		const struct shard_doc *d = doc_of(docs, s);
		int begin, end;
		aa_shard_range(whole->frames, s, out->shard_count, &begin, &end);
		aa_job_result_free(part);
		if (aa_results_from_json(d->doc, json_object_get(d->shard, "error_threshold_curves"), part, err) < 0) {
			aa_error_prefix(err, "%s/results.json", d->dir);
			goto done;
		}
		if (part->spec.first_frame != whole->first_frame + begin || part->spec.frames != end - begin) {
			aa_error_set(err, AA_ERR_INVALID, "", "%s: frames %d-%d, but shard %d of %d of this job is frames "
				     "%d-%d", d->dir, part->spec.first_frame, part->spec.first_frame + part->spec.frames - 1, s,
				     out->shard_count, whole->first_frame + begin, whole->first_frame + end - 1);
			goto done;
		}
		if (s == 0) { /* what does not depend on the frames: the first shard's */
			memcpy(w->scene_name, part->scene_name, sizeof w->scene_name);
			memcpy(w->scene_file, part->scene_file, sizeof w->scene_file);
			w->scene_triangles = part->scene_triangles;
			memcpy(w->device_name, part->device_name, sizeof w->device_name);
			memcpy(w->driver_info, part->driver_info, sizeof w->driver_info);
			w->timestamp_period_ns = part->timestamp_period_ns;
			w->plan_count = part->plan_count;
			memcpy(w->plan, part->plan, sizeof w->plan);
			w->warning_count = part->warning_count;
			w->warnings_dropped = part->warnings_dropped;
			memcpy(w->warnings, part->warnings, sizeof w->warnings);
			w->reference.samples = part->reference.samples;
			w->reference.auto_samples = part->reference.auto_samples;
			w->reference.target_psnr = part->reference.target_psnr;
			memcpy(w->reference.pattern, part->reference.pattern, sizeof w->reference.pattern);
			w->reference.memory_bytes = part->reference.memory_bytes;
			for (int i = 0; i < w->method_count; i++) {
				struct aa_method_result *m = &w->methods[i];
				memcpy(m->path_taken, part->methods[i].path_taken, sizeof m->path_taken);
				m->memory_count = part->methods[i].memory_count;
				memcpy(m->memory, part->methods[i].memory, sizeof m->memory);
				m->memory_bytes = part->methods[i].memory_bytes;
			}
		}
		account(out->result, part, part->started_at, part->wall_seconds, d->dir, notes);
		place_shard(w, part, begin);
	}
	memcpy(w->started_at, out->result->started_at, sizeof w->started_at);
	w->wall_seconds = out->result->wall_seconds;
	for (int s = 1; s < out->shard_count; s++) {
		int begin, end;
		aa_shard_range(whole->frames, s, out->shard_count, &begin, &end);
		border_flicker(out, s, begin, notes);
	}
	rc = 0;
done:
	aa_job_result_free(part);
	free(part);
	return rc;
}

/* A suite's shards: whole cases, each read as it was written, in the suite's order. */
static int merge_cases(struct aa_shard_merge *out, const struct shard_doc *docs, const struct aa_job_spec *whole,
		       FILE *notes, struct aa_error *err)
{
	for (int s = 0; s < out->shard_count; s++) {
		const struct shard_doc *d = doc_of(docs, s);
		int begin, end;
		aa_shard_cases(whole, s, out->shard_count, &begin, &end);
		const json_t *cases = json_object_get(d->doc, "cases");
		if ((int)json_array_size(cases) != end - begin)
			return aa_error_set(err, AA_ERR_INVALID, "", "%s: %zu cases, but shard %d of %d of this suite has %d",
					    d->dir, json_array_size(cases), s, out->shard_count, end - begin);
		for (int c = begin; c < end; c++) {
			const json_t *doc = json_array_get(cases, (size_t)(c - begin));
			char id[512];
			aa_case_id(whole, c, id, sizeof id);
			const char *got = json_string_value(json_object_get(doc, "id"));
			if (!got || strcmp(got, id) != 0)
				return aa_error_set(err, AA_ERR_INVALID, "", "%s: case %d is %s, but this suite's case %d is %s",
						    d->dir, c - begin, got ? got : "(no id)", c, id);
			struct aa_job_result *r = calloc(1, sizeof *r);
			if (!r)
				return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
			out->result->cases[c] = r;
			out->result->case_count = c + 1;
			const json_t *curves = json_array_get(json_object_get(d->shard, "error_threshold_curves"),
							      (size_t)(c - begin));
			if (aa_results_from_json(doc, curves, r, err) < 0) {
				aa_error_prefix(err, "%s/results.json: cases[%d]", d->dir, c - begin);
				return -1;
			}
			/* the case as the unsharded suite runs it: its labels and names are the suite's */
			aa_job_case(whole, c, &r->spec);
		}
		const json_t *sd = d->doc;
		account(out->result, out->result->cases[begin], json_string_value(json_object_get(sd, "started_at"))
			? json_string_value(json_object_get(sd, "started_at")) : "",
			json_is_number(json_object_get(sd, "wall_seconds")) ? json_number_value(json_object_get(sd, "wall_seconds"))
									     : NAN, d->dir, notes);
	}
	return 0;
}

int aa_shard_merge(const char *const *dirs, int dir_count, struct aa_shard_merge *out, FILE *notes,
		   struct aa_error *err)
{
	memset(out, 0, sizeof *out);
	struct shard_doc *docs = calloc((size_t)(dir_count > 0 ? dir_count : 1), sizeof *docs);
	struct aa_job_spec whole;
	const struct shard_doc *first = NULL;
	int rc = -1;
	if (!docs) {
		aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		goto done;
	}
	for (int k = 0; k < dir_count; k++) {
		struct shard_doc *d = &docs[k];
		bool absent;
		d->dir = dirs[k];
		d->doc = load_results(d->dir, &absent, err);
		if (absent) {
			if (notes)
				fprintf(notes, "%s: no results.json (the shard did not finish)\n", d->dir);
			continue;
		}
		if (!d->doc)
			goto done;
		d->shard = json_object_get(d->doc, "shard");
		d->hash = json_string_value(json_object_get(d->shard, "job_hash"));
		d->index = (int)json_integer_value(json_object_get(d->shard, "index"));
		d->count = (int)json_integer_value(json_object_get(d->shard, "count"));
		d->warmup = (int)json_integer_value(json_object_get(d->shard, "warmup"));
		if (!json_is_object(d->shard) || !d->hash || d->count < 1 || d->index < 0 || d->index >= d->count) {
			aa_error_set(err, AA_ERR_INVALID, "", "%s: not the results of a shard (no valid \"shard\" in "
				     "results.json; shards come from 'aalab run --shard I/N')", d->dir);
			goto done;
		}
		if (!first) {
			first = d;
			continue;
		}
		if (strcmp(d->hash, first->hash) != 0 || d->count != first->count || d->warmup != first->warmup) {
			aa_error_set(err, AA_ERR_INVALID, "", "%s is shard %d of %d of job %s (warm-up %d), %s shard %d of %d "
				     "of job %s (warm-up %d): not shards of one job", d->dir, d->index, d->count, d->hash,
				     d->warmup, first->dir, first->index, first->count, first->hash, first->warmup);
			goto done;
		}
		for (const struct shard_doc *e = docs; e < d; e++)
			if (e->doc && e->index == d->index) {
				aa_error_set(err, AA_ERR_INVALID, "", "%s and %s are both shard %d of %d; give each shard once",
					     e->dir, d->dir, d->index, d->count);
				goto done;
			}
	}
	if (!first) {
		aa_error_set(err, AA_ERR_INVALID, "", "no shard results in the %d folder%s given", dir_count,
			     dir_count == 1 ? "" : "s");
		goto done;
	}
	if (aa_job_spec_from_json(json_object_get(first->shard, "job"), &whole, err) < 0) {
		aa_error_prefix(err, "%s: shard.job", first->dir);
		goto done;
	}
	if (check_shards(docs, dir_count, first->count, &whole, err))
		goto done;
	out->shard_count = first->count;
	out->result = calloc(1, sizeof *out->result);
	out->dirs = calloc((size_t)first->count, sizeof *out->dirs);
	if (!out->result || !out->dirs) {
		aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		goto done;
	}
	out->result->spec = whole;
	for (int s = 0; s < first->count; s++)
		if (!(out->dirs[s] = strdup(doc_of(docs, s)->dir))) {
			aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
			goto done;
		}
	rc = whole.is_suite ? merge_cases(out, docs, &whole, notes, err) : merge_frames(out, docs, &whole, notes, err);
done:
	for (int k = 0; docs && k < dir_count; k++)
		json_decref(docs[k].doc);
	free(docs);
	if (rc)
		aa_shard_merge_free(out);
	return rc;
}

void aa_shard_merge_free(struct aa_shard_merge *m)
{
	aa_suite_result_free(m->result);
	for (int s = 0; m->dirs && s < m->shard_count; s++)
		free(m->dirs[s]);
	free(m->dirs);
	memset(m, 0, sizeof *m);
}

/* ---- images ---- */

static int copy_file(const char *from, const char *to, struct aa_error *err)
{
	if (link(from, to) == 0)
		return 0; /* the same file system: no copy needed */
	int in = open(from, O_RDONLY), outfd = in < 0 ? -1 : open(to, O_WRONLY | O_CREAT | O_TRUNC, 0644);
	char buf[65536];
	ssize_t n = 0;
	while (outfd >= 0 && (n = read(in, buf, sizeof buf)) > 0)
		if (write(outfd, buf, (size_t)n) != n) {
			n = -1;
			break;
		}
	int failed = in < 0 || outfd < 0 || n < 0;
	int saved = errno;
	if (in >= 0)
		close(in);
	if (outfd >= 0 && close(outfd) < 0)
		failed = 1;
	if (failed)
		return aa_error_set(err, AA_ERR_IO, "", "cannot copy %s to %s: %s", from, to, strerror(saved));
	return 0;
}

static int make_dirs(char *path)
{
	for (char *p = path + 1; *p; p++)
		if (*p == '/') {
			*p = '\0';
			int bad = mkdir(path, 0755) < 0 && errno != EEXIST;
			*p = '/';
			if (bad)
				return -1;
		}
	return 0;
}

/* One image of shard s's frame ordinal k, into dir under the whole job's ordinal. */
static int merge_image(const char *shard_dir, const char *dir, const char *kind, const char *label, int k,
		       int ordinal, bool linear, struct aa_error *err)
{
	char rel[512], from[4800], to[4800];
	if (linear)
		aa_results_linear_relpath(label, k, rel, sizeof rel);
	else
		aa_results_frame_relpath(kind, label, k, rel, sizeof rel);
	snprintf(from, sizeof from, "%s/%s", shard_dir, rel);
	if (linear)
		aa_results_linear_relpath(label, ordinal, rel, sizeof rel);
	else
		aa_results_frame_relpath(kind, label, ordinal, rel, sizeof rel);
	snprintf(to, sizeof to, "%s/%s", dir, rel);
	if (access(from, F_OK) != 0)
		return aa_error_set(err, AA_ERR_INVALID, "", "%s is missing: an incomplete shard", from);
	if (make_dirs(to) < 0)
		return aa_error_set(err, AA_ERR_IO, "", "cannot create the folders of %s: %s", to, strerror(errno));
	return copy_file(from, to, err);
}

/* Every file under from into to (folders made), but the reports and results.json, which the merge
 * writes anew: a link to a shard's report would be written through. */
static int link_tree(const char *from, const char *to, struct aa_error *err)
{
	DIR *d = opendir(from);
	if (!d)
		return errno == ENOENT ? 0 : aa_error_set(err, AA_ERR_IO, "", "cannot read %s: %s", from, strerror(errno));
	if (mkdir(to, 0755) < 0 && errno != EEXIST) {
		closedir(d);
		return aa_error_set(err, AA_ERR_IO, "", "cannot create %s: %s", to, strerror(errno));
	}
	int rc = 0;
	struct dirent *e;
	while (rc == 0 && (e = readdir(d))) {
		if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") || !strcmp(e->d_name, "report.html") ||
		    !strcmp(e->d_name, "results.json"))
			continue;
		char a[4200], b[4200];
		snprintf(a, sizeof a, "%s/%s", from, e->d_name);
		snprintf(b, sizeof b, "%s/%s", to, e->d_name);
		struct stat st;
		if (stat(a, &st) < 0)
			rc = aa_error_set(err, AA_ERR_IO, "", "cannot read %s: %s", a, strerror(errno));
		else
			rc = S_ISDIR(st.st_mode) ? link_tree(a, b, err) : copy_file(a, b, err);
	}
	closedir(d);
	return rc;
}

int aa_shard_merge_images(const struct aa_shard_merge *m, const char *dir, struct aa_error *err)
{
	const struct aa_job_spec *spec = &m->result->spec;
	if (spec->is_suite) { /* whole cases: their folders as they are */
		char to[4200];
		snprintf(to, sizeof to, "%s/cases", dir);
		for (int s = 0; s < m->shard_count; s++) {
			char from[4200];
			snprintf(from, sizeof from, "%s/cases", m->dirs[s]);
			if (link_tree(from, to, err))
				return -1;
		}
		return 0;
	}
	if (!spec->keep_frames)
		return 0;
	for (int s = 0; s < m->shard_count; s++) {
		int begin, end;
		aa_shard_range(spec->frames, s, m->shard_count, &begin, &end);
		/* a shard run with --no-images has no frames/ at all, like an unsharded run with it */
		char frames_dir[4200];
		snprintf(frames_dir, sizeof frames_dir, "%s/frames", m->dirs[s]);
		if (access(frames_dir, F_OK) != 0)
			continue;
		for (int k = 0; k < end - begin; k++) {
			if (merge_image(m->dirs[s], dir, "frames", "reference", k, begin + k, false, err) ||
			    (spec->linear_frames && merge_image(m->dirs[s], dir, NULL, "reference", k, begin + k, true, err)))
				return -1;
			for (int i = 0; i < spec->method_count; i++) {
				const char *label = spec->methods[i].label;
				if (merge_image(m->dirs[s], dir, "frames", label, k, begin + k, false, err) ||
				    merge_image(m->dirs[s], dir, "diff", label, k, begin + k, false, err) ||
				    merge_image(m->dirs[s], dir, "flip", label, k, begin + k, false, err) ||
				    (spec->linear_frames && merge_image(m->dirs[s], dir, NULL, label, k, begin + k, true, err)))
					return -1;
			}
		}
	}
	return 0;
}

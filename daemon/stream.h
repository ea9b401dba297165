/* Watch streams (a job's events and frames, as they come) and stored files (get): stream.c. */
#ifndef AALABD_STREAM_H
#define AALABD_STREAM_H

#include <stddef.h>

#include <jansson.h>

struct conn;
struct job;

enum { FRAMES_NONE, FRAMES_PNG, FRAMES_RGBA8, FRAMES_RGBA16F };

/* A connection's watch (conn->watch, malloc'ed): the connection holds the job while it watches (jobs.h). */
struct watch {
	struct job *job;
	unsigned long next_seq;
	json_t *tag;
	int frames;               /* FRAMES_NONE / FRAMES_PNG / FRAMES_RGBA8 / FRAMES_RGBA16F */
	unsigned long frames_dropped;
};

/* Sends what the watched job has logged since, while the client has room for it; ends the watch after
 * the job's final event. */
void stream_pump_watch(struct conn *c);
/* Ends c's watch, if any, releasing its job (the connection closed). */
void stream_end_watch(struct conn *c);
void op_get(struct conn *c, json_t *msg, json_t *tag);
void stream_cache_clear(void); /* frees the frames kept for watchers (at exit) */
/* Checks a file name inside a job directory (results.json, report.html, events.jsonl, scene.json,
 * frames|diff/NAME/NNNN.png) and writes its path; -1 if it is not one of those. */
int job_file_path(const char *jobs_dir, const char *id, const char *rel, char *out, size_t size);

#endif

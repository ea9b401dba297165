/* User methods (docs/user-methods.md): a method file names passes of the user's GLSL, what each pass reads
 * and writes, and typed parameters. It is parsed into a struct aa_user_method that presents itself as a
 * struct aa_method (its first member), so the frame plan, timing, memory and metrics treat it exactly
 * as a built-in method. The built-in `user` is how a job names one: "user:file=my_aa.json,strength=0.5". */
#ifndef AA_USER_METHOD_H
#define AA_USER_METHOD_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "types/method.h"

#define AA_USER_MAX_PASSES 8
#define AA_USER_MAX_READS 8           /* a fragment pass binds AA_PASS_MAX_SOURCES; a compute pass its reads
                                       * and its output, within AA_COMPUTE_MAX_BINDINGS */
#define AA_USER_FILE_MAX (256 * 1024) /* bytes of a method file or of one shader file */
#define AA_USER_NAME_MAX 24           /* method, pass and parameter names (a pass name is a timer span) */
#define AA_USER_PATH_MAX 256          /* a file name as written, joined to its folder */

/* Where method and shader files come from: the disk for `aalab run`, the files a client sent with its
 * job for aalabd (which never reads a user's path on its own disk). */
struct aa_file_source {
	/* Reads `name` into *text (malloc'ed, NUL-terminated; *size bytes before the NUL). Errors name the
	 * file: AA_ERR_NOT_FOUND, AA_ERR_IO, or AA_ERR_LIMIT beyond AA_USER_FILE_MAX. */
	int (*read)(void *ctx, const char *name, char **text, size_t *size, struct aa_error *err);
	void *ctx;
};
/* Files on disk; relative names from the current directory. */
extern const struct aa_file_source aa_file_source_disk;
/* The files of a JSON object {"name": "text", ...} (a job's files sent to aalabd), which must outlive
 * the source; any other name is not found. */
struct json_t;
void aa_file_source_json(const struct json_t *files, struct aa_file_source *out);
/* `name` as written inside the file `referrer` (a method file naming its shader): a relative name is
 * taken from the referrer's folder. */
void aa_file_join(const char *referrer, const char *name, char *out, size_t size);

/* What a pass reads (docs/user-methods.md, "Inputs"). */
enum aa_user_input {
	AA_USER_IN_COLOUR,   /* the frame's linear scene colour (RGBA16F) */
	AA_USER_IN_DEPTH,    /* reversed-Z depth: 1 at the near plane, 0 at the far plane and background */
	AA_USER_IN_VELOCITY, /* RG16F, pixels moved since the previous frame */
	AA_USER_IN_NORMALS,  /* RGBA16F geometric normal, world space, facing the camera; w 0 on background */
	AA_USER_IN_IDS,      /* R32UI model ID, 0 on background */
	AA_USER_IN_PASS,     /* an earlier pass's output this frame */
	AA_USER_IN_PREVIOUS, /* a pass's output of the previous frame ("history": the last pass's) */
};

struct aa_user_read {
	enum aa_user_input input;
	int pass;                /* AA_USER_IN_PASS and AA_USER_IN_PREVIOUS: the pass */
	bool linear;             /* bilinear filtering, clamp to edge (else nearest) */
	char glsl_name[AA_USER_NAME_MAX + 16]; /* colour, history, previous_NAME, NAME, ... */
};

struct aa_user_pass {
	char name[AA_USER_NAME_MAX + 1];
	char shader[AA_USER_PATH_MAX];      /* its shader file, joined to the method file's folder */
	bool compute;                       /* a compute shader (8x8 groups), else a full-screen fragment pass */
	int format;                         /* index into the table of aa_user_format_* */
	int read_count;
	struct aa_user_read reads[AA_USER_MAX_READS];
	bool kept;                          /* read as previous:NAME, so kept for the next frame (2 images) */
	char *source;                       /* the shader file's text */
	size_t source_size;
	uint32_t *spirv;                    /* compiled by aa_user_method_compile */
	size_t spirv_size;
};

struct aa_user_method {
	struct aa_method method;            /* first: what the engine, the plan and the results see */
	atomic_int refs;
	char name[AA_USER_NAME_MAX + 1];    /* the file's "name": the method's label */
	char file[AA_USER_PATH_MAX];        /* the method file, as the job names it (file=...) */
	char summary[200];
	char seed[AA_USER_PATH_MAX + 32];
	char sha256[65];                    /* of the method file and every shader file, names and bytes */
	struct aa_param_def params[AA_MAX_PARAMS];
	char param_names[AA_MAX_PARAMS][AA_USER_NAME_MAX + 1];
	char param_help[AA_MAX_PARAMS][200];
	char *choice_text[AA_MAX_PARAMS];   /* enum choices, NUL-separated, and the pointer arrays into it */
	const char **choices[AA_MAX_PARAMS];
	int jitter_length;                  /* Halton(2,3) points per cycle; 0: the scene is not jittered */
	int pass_count;
	struct aa_user_pass passes[AA_USER_MAX_PASSES];
	bool compiled;
	bool compiled_from_cache;           /* every pass's SPIR-V came from the cache */
	double compile_ms;                  /* wall time of the last aa_user_method_compile */
};

/* Reads and checks a method file through src. path names the job field for err->path ("methods[2]");
 * messages name the file and the field or line ("my_aa.json: passes[1].reads[0]: ..."). The method
 * comes back with one reference. */
int aa_user_method_load(const char *file, const struct aa_file_source *src, const char *path,
			struct aa_user_method **out, struct aa_error *err);
/* The text after "user:" in a method string: "file=my_aa.json" and the file's parameters as key=value.
 * On success *method is a user method holding one reference (aa_method_unref drops it). */
int aa_user_method_parse(const char *list, const struct aa_file_source *src, const char *path,
			 const struct aa_method **method, struct aa_method_params *params, struct aa_error *err);
bool aa_method_is_user(const struct aa_method *m);
/* NULL for a built-in method. */
const struct aa_user_method *aa_user_method_of(const struct aa_method *m);
/* References of user methods; both do nothing for built-in methods (and NULL). */
void aa_method_ref(const struct aa_method *m);
void aa_method_unref(const struct aa_method *m);
/* "user:file=FILE" and the non-default parameters: the method string that reads the method again. */
void aa_user_method_spec_text(const struct aa_method *m, const struct aa_method_params *p, char *out,
			      size_t size);

/* The GLSL compiled for pass i: "#version 450", the pass's #extension lines, the declarations of
 * docs/user-methods.md (inputs, push constants, output, helpers), "#line 1" and the user's source with
 * its #extension lines blanked, so compiler messages give the user's line numbers. malloc'ed. */
char *aa_user_pass_glsl(const struct aa_user_method *um, int i, size_t *size);
/* Compiles every pass (glslang, through the SPIR-V cache) unless done before. A compile error is
 * AA_ERR_INVALID: "FILE:LINE: message". Not thread-safe: one thread compiles a method. */
int aa_user_method_compile(struct aa_user_method *um, struct aa_error *err);

/* The bytes the push constants of a pass take (the header of docs/user-methods.md plus the parameters). */
uint32_t aa_user_push_size(const struct aa_user_method *um);
/* Pass formats: VkFormat value, GLSL image format qualifier and name ("rgba16f"). */
uint32_t aa_user_format_vk(int format);
const char *aa_user_format_name(int format);

/* The `user` method's create (engine/methods/user_method.c): what the method struct's create_self is. */
struct aa_renderer;
struct aa_method_result;
int aa_user_method_create(const struct aa_method *m, struct aa_renderer *r, const struct aa_method_params *p,
			  struct aa_method_result *info, struct aa_method_state **out, struct aa_error *err);
extern const struct aa_method aa_user_method_functions; /* render, reset, destroy of every user method */
/* `user` as `aalab methods` describes it (not in aa_methods: it runs only as a method file's method). */
extern const struct aa_method aa_method_user;

#endif

/* The one way aalab opens a file that an outside input names (a scene, a mesh, a texture, a job, a
 * configuration, a token): without blocking, and only when it is a regular file. open(2) of a FIFO
 * blocks until someone writes to it, and a device may never end, so the file is opened with O_NONBLOCK,
 * fstat'ed, refused unless regular (the error names the field), and only then read (O_NONBLOCK cleared).
 * Every reader of such files goes through here, libraries included: OpenImageIO reads a path checked here
 * first (engine/image/image_files.c), assimp an I/O system whose every open comes here
 * (engine/scene/mesh_file.c). */
#ifndef AA_FILE_OPEN_H
#define AA_FILE_OPEN_H

#include <stdio.h>

#include "util/error.h"

/* A file descriptor open for reading on a regular file, or -1 with err set: AA_ERR_NOT_FOUND when it
 * does not exist, AA_ERR_INVALID when it is a FIFO, socket, device or folder ("FIELD: 'PATH' is a FIFO,
 * not a regular file"), AA_ERR_IO otherwise. field names the input (err->path), may be "". */
int aa_file_open_regular(const char *path, const char *field, struct aa_error *err);
/* The same as a stdio stream ("r" or "rb"). */
FILE *aa_file_fopen_regular(const char *path, const char *field, struct aa_error *err);

#endif

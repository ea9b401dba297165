/* A label as a file or directory name that cannot escape its parent. */
#ifndef AA_FILE_NAME_H
#define AA_FILE_NAME_H

#include <stddef.h>

/* The label with ':' -> '_', '=' -> '-', ',' -> '_' and every byte but [A-Za-z0-9._-] -> '_'
 * ("ssaa:samples=16" -> "ssaa_samples-16"); "", "." and ".." become "_". The directory of a method's
 * images, of a case. */
void aa_label_dirname(const char *label, char *out, size_t size);

#endif

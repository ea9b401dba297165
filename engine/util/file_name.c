/* A label as a file or directory name that cannot escape its parent. */
#include <stdio.h>
#include <string.h>

#include "util/file_name.h"

void aa_label_dirname(const char *label, char *out, size_t size)
{
	if (size == 0)
		return;
	size_t n = 0;
	for (; label[n] && n + 1 < size; n++) {
		const char c = label[n];
		if (c == ':' || c == ',')
			out[n] = '_';
		else if (c == '=')
			out[n] = '-';
		else if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
			 c == '_' || c == '-')
			out[n] = c;
		else
			out[n] = '_'; /* anything else ('/', spaces, bytes of UTF-8) must not shape the path */
	}
	out[n] = '\0';
	/* "", "." and ".." would name the parent or the directory itself. */
	if (n == 0 || strspn(out, ".") == n)
		snprintf(out, size, "_");
}

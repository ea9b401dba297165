/* What messages about JSON input say of it: the type of a value, user text made safe to print; and
 * reading a document's fields that may be missing. */
#ifndef AA_JSON_TEXT_H
#define AA_JSON_TEXT_H

#include <stddef.h>

#include <jansson.h>

/* Cuts leading and trailing whitespace of s in place; returns where the text now starts. */
char *aa_trim(char *s);
/* "an object", "a string", "an integer", ...: for "expected X, got <this>". */
const char *aa_json_type_name(const json_t *v);
/* User text for a path or message: at most 48 bytes, control characters as '?'. */
const char *aa_shown_text(const char *text, char *buf, size_t size);
/* obj[key] as a number, NAN when it is missing or not one; as a string, "" when missing or not one. */
double aa_json_number(const json_t *obj, const char *key);
const char *aa_json_string(const json_t *obj, const char *key);

#endif

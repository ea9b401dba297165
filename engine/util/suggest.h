/* "Did you mean": the known word closest to a misspelt one, for errors that name what was meant. */
#ifndef AA_SUGGEST_H
#define AA_SUGGEST_H

#include <stddef.h>

/* Levenshtein distance (insertions, deletions, substitutions); 99 for words over 63 bytes. */
int aa_edit_distance(const char *a, const char *b);
/* The candidate closest to word, when it is near enough to be a typo (at most 2 edits, and fewer edits
 * than the candidate has letters); NULL otherwise. candidates ends with NULL when count is negative. */
const char *aa_suggest(const char *word, const char *const *candidates, int count);
/* " (did you mean 'X'?)" when aa_suggest finds one, else "", into out. */
void aa_suggest_text(const char *word, const char *const *candidates, int count, char *out, size_t size);

#endif

/* "Did you mean": the closest known word by edit distance, so that "smma" suggests "smaa" and "colour"
 * suggests "color". */
#include <stdio.h>
#include <string.h>

#include "util/suggest.h"

int aa_edit_distance(const char *a, const char *b)
{
	size_t la = strlen(a), lb = strlen(b);
	if (la > 63 || lb > 63)
		return 99;
	int row[64];
	for (size_t j = 0; j <= lb; j++)
		row[j] = (int)j;
	for (size_t i = 1; i <= la; i++) {
		int diag = row[0];
		row[0] = (int)i;
		for (size_t j = 1; j <= lb; j++) {
			int up = row[j];
			int best = diag + (a[i - 1] != b[j - 1]);
			if (row[j] + 1 < best)
				best = row[j] + 1;
			if (row[j - 1] + 1 < best)
				best = row[j - 1] + 1;
			row[j] = best;
			diag = up;
		}
	}
	return row[lb];
}

const char *aa_suggest(const char *word, const char *const *candidates, int count)
{
	const char *best_word = NULL;
	int best = 3; /* more than two edits is another word, not a typo */
	for (int i = 0; word && (count < 0 ? candidates[i] != NULL : i < count); i++) {
		const int d = aa_edit_distance(word, candidates[i]);
		if (d < best && d < (int)strlen(candidates[i])) {
			best = d;
			best_word = candidates[i];
		}
	}
	return best_word;
}

void aa_suggest_text(const char *word, const char *const *candidates, int count, char *out, size_t size)
{
	const char *s = aa_suggest(word, candidates, count);
	if (s)
		snprintf(out, size, " (did you mean '%s'?)", s);
	else if (size)
		out[0] = '\0';
}

/* Golden values: numbers with no exact answer (a method's PSNR on a scene), pinned in a reviewable text
 * file under tests/golden/ with a tolerance each, so that a change that moves them fails a test.
 *
 * A file holds one value a line: "KEY<TAB>VALUE", where KEY is words separated by spaces ("thin-wires
 * fxaa psnr"); '#' starts a comment. A test checks every value it computes with golden_check and ends with
 * golden_finish, which fails on a value outside its tolerance, on a key the file lacks and on a key of the
 * file the test no longer computes. With $AALAB_GOLDEN_OUT set, nothing is compared: the values are
 * written to that file instead (`make update-golden` does this and shows the diff before accepting it). */
#ifndef AA_TEST_GOLDEN_H
#define AA_TEST_GOLDEN_H

#include <stdbool.h>

/* name: the file under $top_srcdir/tests/golden/ (e.g. "quality.tsv"). */
void golden_open(const char *name);
/* Compares (or records) one value; tolerance is absolute. NaN matches only "nan". */
void golden_check(const char *key, double value, double tolerance);
/* Fails the current cmocka test when a value is off, missing or stale; writes the file in update mode. */
void golden_finish(void);
/* True when the values are being written rather than compared. */
bool golden_updating(void);

#endif

/* Boolean environment variables. */
#ifndef AA_ENV_FLAG_H
#define AA_ENV_FLAG_H

#include <stdbool.h>

/* A boolean environment variable: unset, empty, 0, false, no or off (any case) is false; 1, true, yes, on
 * and anything else is true, so that a misspelt value leaves a safety check like validation on. */
bool aa_env_flag(const char *name);
bool aa_env_flag_value(const char *value);

#endif

/* Boolean environment variables. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "util/env_flag.h"

bool aa_env_flag_value(const char *value)
{
	static const char *const off[] = {"", "0", "false", "no", "off"};
	if (!value)
		return false;
	for (size_t i = 0; i < sizeof off / sizeof off[0]; i++)
		if (strcasecmp(value, off[i]) == 0)
			return false;
	return true;
}

bool aa_env_flag(const char *name)
{
	return aa_env_flag_value(getenv(name));
}

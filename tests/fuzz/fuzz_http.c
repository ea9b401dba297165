/* libFuzzer target: aalabd's HTTP request-head parser (daemon/http_parse.c) over a pipelined stream. */
#include <stdint.h>
#include <string.h>

#include "http_parse.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *p = (const char *)data;
	while (size > 0) {
		struct http_request req;
		const char *why;
		long taken = http_parse_request(p, size, &req, &why);
		if (taken <= 0) {
			if (taken < 0 && (!why || !*why))
				__builtin_trap(); /* every refusal says why */
			break;
		}
		if ((size_t)taken > size || req.target[0] != '/' || !req.method[0])
			__builtin_trap();
		p += taken;
		size -= (size_t)taken;
	}
	return 0;
}

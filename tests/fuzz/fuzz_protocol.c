/* libFuzzer target: aalabd's protocol request lines (daemon/protocol_parse.c), one per input line, as
 * the daemon's framing hands them over. */
#include <stdint.h>
#include <string.h>

#include "protocol_parse.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *p = (const char *)data, *end = p + size;
	while (p < end) {
		const char *nl = memchr(p, '\n', (size_t)(end - p));
		size_t len = nl ? (size_t)(nl - p) : (size_t)(end - p);
		struct protocol_line pl;
		protocol_parse_line(p, len, 1 << 20, &pl);
		if (pl.kind == LINE_REQUEST && (!pl.msg || !pl.op || !json_is_object(pl.msg)))
			__builtin_trap(); /* a request must come with its object and op */
		if (pl.kind == LINE_ERROR && (!pl.code || !pl.path))
			__builtin_trap();
		protocol_line_release(&pl);
		p += len + 1;
	}
	return 0;
}

/* SHA-256 (FIPS 180-4) of a byte string: the job hash of results.json, so that the results of one job
 * (and of its shards) can be recognised wherever they were rendered. */
#ifndef AA_SHA256_H
#define AA_SHA256_H

#include <stddef.h>
#include <stdint.h>

void aa_sha256(const void *data, size_t size, uint8_t digest[32]);
/* The digest as 64 lowercase hex digits and a NUL (hex must hold 65 bytes). */
void aa_sha256_hex(const void *data, size_t size, char hex[65]);

#endif

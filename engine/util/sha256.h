/* SHA-256 (FIPS 180-4): the content hash that names compiled user shaders in the SPIR-V cache,
 * identifies a user method's files in results, and is the job hash of results.json (so that the results
 * of one job, and of its shards, can be recognised wherever they were rendered). */
#ifndef AA_SHA256_H
#define AA_SHA256_H

#include <stddef.h>
#include <stdint.h>

struct aa_sha256 {
	uint32_t state[8];
	uint64_t length;       /* bytes hashed so far */
	uint8_t block[64];
	size_t used;           /* bytes of block filled */
};

void aa_sha256_init(struct aa_sha256 *h);
void aa_sha256_update(struct aa_sha256 *h, const void *data, size_t size);
/* Finishes the hash: 32 bytes into digest. */
void aa_sha256_final(struct aa_sha256 *h, uint8_t digest[32]);
/* A digest as 64 lowercase hex digits and a NUL. */
void aa_sha256_digest_hex(const uint8_t digest[32], char out[65]);

/* One byte string at once. */
void aa_sha256(const void *data, size_t size, uint8_t digest[32]);
/* The digest of a byte string as 64 lowercase hex digits and a NUL (hex must hold 65 bytes). */
void aa_sha256_hex(const void *data, size_t size, char hex[65]);

#endif

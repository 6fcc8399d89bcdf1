/*
 * sha256.c - SHA-256 of a file with OpenSSL's EVP digest API.
 */
#include <openssl/evp.h>
#include <stdio.h>

#include "rig/store.h"

int rig_sha256_file(const char *path, char hex[RIG_SHA256_HEX],
		    struct rig_error *err)
{
	unsigned char buf[65536], md[EVP_MAX_MD_SIZE];
	unsigned int md_len = 0, i;
	EVP_MD_CTX *ctx;
	FILE *f = fopen(path, "rb");
	size_t n;
	int ok;

	if (!f)
		return rig_error_set(err, RIG_EIO, "%s: cannot open", path);
	ctx = EVP_MD_CTX_new();
	ok = ctx && EVP_DigestInit_ex(ctx, EVP_sha256(), NULL);
	while (ok && (n = fread(buf, 1, sizeof(buf), f)) > 0)
		ok = EVP_DigestUpdate(ctx, buf, n);
	ok = ok && !ferror(f) && EVP_DigestFinal_ex(ctx, md, &md_len);
	EVP_MD_CTX_free(ctx);
	fclose(f);
	if (!ok)
		return rig_error_set(err, RIG_EIO, "%s: cannot hash", path);
	for (i = 0; i < md_len; i++)
		snprintf(hex + 2 * i, 3, "%02x", md[i]);
	return RIG_OK;
}

/*
 * sha256.c - SHA-256 of a frame file with OpenSSL's EVP digest API,
 * streamed in 64 KiB blocks, and its check against the manifest.
 */
#include <openssl/evp.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sweep_store.h"

int stray_sweep_sha256_file(const char *path,
			    char hex[STRAY_SWEEP_SHA256_HEX],
			    struct stray_error *err)
{
	static unsigned char buf[65536];
	unsigned char md[EVP_MAX_MD_SIZE];
	unsigned int md_len = 0, i;
	EVP_MD_CTX *ctx = EVP_MD_CTX_new();
	FILE *f = fopen(path, "rb");
	int missing = !f && errno == ENOENT;
	int ok = ctx && f && EVP_DigestInit_ex(ctx, EVP_sha256(), NULL);
	size_t n;

	if (missing) {		/* the manifest lists it: bad input, exit 2 */
		EVP_MD_CTX_free(ctx);
		return stray_error_at(err, STRAY_ENOTFOUND, path, 0, "file",
			"listed in manifest.csv but missing from the folder");
	}
	while (ok && (n = fread(buf, 1, sizeof(buf), f)) > 0)
		ok = EVP_DigestUpdate(ctx, buf, n);
	ok = ok && !ferror(f) && EVP_DigestFinal_ex(ctx, md, &md_len) &&
	     md_len == 32;
	if (f)
		fclose(f);
	EVP_MD_CTX_free(ctx);
	if (!ok)
		return stray_error_at(err, STRAY_EIO, path, 0, "file",
				      f ? "cannot read the frame file"
					: "cannot open the frame file");
	for (i = 0; i < md_len; i++)
		snprintf(hex + 2 * i, 3, "%02x", md[i]);
	return STRAY_OK;
}

int stray_sweep_sha256_check(const char *path, const char *hex,
			     struct stray_error *err)
{
	char got[STRAY_SWEEP_SHA256_HEX];
	int rc;

	if ((rc = stray_sweep_sha256_file(path, got, err)) != STRAY_OK)
		return rc;
	if (strcmp(got, hex) != 0) {
		stray_error_at(err, STRAY_EINVAL, path, 0, "sha256",
			       "does not match manifest.csv (file changed or corrupt)");
		stray_error_text(err, got);
		return STRAY_EINVAL;
	}
	return STRAY_OK;
}

/*
 * sha256.c - SHA-256 of a frame file with OpenSSL's EVP digest API,
 * streamed in 64 KiB blocks (or of the bytes already in memory), and its
 * check against the manifest.
 */
#include <openssl/evp.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sweep_store.h"

static void to_hex(const unsigned char *md, unsigned md_len, char *hex)
{
	static const char digit[] = "0123456789abcdef";
	unsigned i;

	for (i = 0; i < md_len; i++) {
		hex[2 * i] = digit[md[i] >> 4];
		hex[2 * i + 1] = digit[md[i] & 15];
	}
	hex[2 * md_len] = '\0';
}

int stray_sweep_sha256_file(const char *path,
			    char hex[STRAY_SWEEP_SHA256_HEX],
			    struct stray_error *err)
{
	static unsigned char buf[65536];
	unsigned char md[EVP_MAX_MD_SIZE];
	unsigned int md_len = 0;
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
	to_hex(md, md_len, hex);
	return STRAY_OK;
}

int stray_sweep_sha256_mem(const void *data, size_t len,
			   char hex[STRAY_SWEEP_SHA256_HEX])
{
	unsigned char md[EVP_MAX_MD_SIZE];
	unsigned int md_len = 0;

	if (!EVP_Digest(data, len, md, &md_len, EVP_sha256(), NULL) ||
	    md_len != 32)
		return STRAY_EIO;
	to_hex(md, md_len, hex);
	return STRAY_OK;
}

static int compare(const char *path, const char *got, const char *hex,
		   struct stray_error *err)
{
	if (strcmp(got, hex) != 0) {
		stray_error_at(err, STRAY_EINVAL, path, 0, "sha256",
			       "does not match manifest.csv (file changed or corrupt)");
		stray_error_text(err, got);
		return STRAY_EINVAL;
	}
	return STRAY_OK;
}

int stray_sweep_sha256_check(const char *path, const char *hex,
			     struct stray_error *err)
{
	char got[STRAY_SWEEP_SHA256_HEX];
	int rc;

	if ((rc = stray_sweep_sha256_file(path, got, err)) != STRAY_OK)
		return rc;
	return compare(path, got, hex, err);
}

int stray_sweep_sha256_check_mem(const char *path, const void *data,
				 size_t len, const char *hex,
				 struct stray_error *err)
{
	char got[STRAY_SWEEP_SHA256_HEX];

	if (stray_sweep_sha256_mem(data, len, got) != STRAY_OK)
		return stray_error_at(err, STRAY_EIO, path, 0, "file",
				      "cannot read the frame file");
	return compare(path, got, hex, err);
}

/*
 * fuzz_fdrfw_blob.c - libFuzzer target for firmware_fdr's table blob
 * (fdrfw_table_parse, fdrfw_table_check) and, for tables that pass, the
 * per-frame path on arbitrary input bytes (NaN, inf, huge, denormal).
 *
 * The first byte picks the mode: even, the bytes are a blob as received
 * (the CRC gate); odd, the blob is resealed first so the range checks and
 * the frame behind them see the fuzzer's values.  Bytes past the blob are
 * the frame's inputs.  Seeds: tests/fuzz/seeds/fdrfw_blob (a table from
 * `stray firmware-table --out-bin`).
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fdrfw/fdrfw.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct fdrfw_table t;
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;
	size_t blob_len;
	int reseal;

	if (size < 1)
		return 0;
	reseal = data[0] & 1;
	data++;
	size--;
	blob_len = size < FDRFW_BLOB_SIZE ? size : FDRFW_BLOB_SIZE;
	if (fdrfw_table_parse(data, blob_len, &t) != FDRFW_OK)
		return 0;
	if (reseal)
		fdrfw_table_seal(&t);
	memset(&in, 0, sizeof(in));
	memcpy(&in, data + blob_len,
	       size - blob_len < sizeof(in) ? size - blob_len : sizeof(in));
	/* An unchecked table must never be used: init refuses it and the
	 * frame then reports invalid input. */
	(void)fdrfw_init(&ctx, &t);
	(void)fdrfw_frame(&ctx, &in, &out);
	in.use_given_dirs = !in.use_given_dirs;
	(void)fdrfw_frame(&ctx, &in, &out);
	return 0;
}

/*
 * builtin_data.S - the shipped spectra (the CSV files of libstray/data, provenance in
 * libstray/data/PROVENANCE.md) assembled into the library verbatim, so the
 * `stray` binary needs no data directory.  Each blob is NUL-terminated.
 */
#define BLOB(sym, file)                   \
	.global sym##_start;              \
	.global sym##_end;                \
	.balign 16;                       \
sym##_start:                              \
	.incbin file;                     \
sym##_end:                                \
	.byte 0

	.section .rodata
BLOB(stray_blob_sun_e490, "libstray/data/sun_am0_astm_e490.csv")
BLOB(stray_blob_sun_g173, "libstray/data/sun_am0_astm_g173_etr.csv")
BLOB(stray_blob_vega, "libstray/data/vega_calspec_alpha_lyr_stis_011.csv")
BLOB(stray_blob_qe, "libstray/data/qe_mt9p031_approx.csv")
BLOB(stray_blob_bessell_v, "libstray/data/bessell_v_passband.csv")

	.section .note.GNU-stack,"",@progbits

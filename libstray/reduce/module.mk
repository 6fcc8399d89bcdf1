# libstray/reduce: lab frames to the lens curve (thesis §3.2).
#
# Listed in MODULES after tools, because it extends what tools/module.mk
# defines:
#   - libstray/reduce/*.c: the reduction math (libc/libm only, no heap)
#     and sweep.c, the one call that streams a sweep folder through it
#     (stray_reduce_sweep), reading the folder through the sweep store
#     (libstray/sweep: cfitsio, libcsv, OpenSSL), with its helpers
#     bigmem.c (buffers on 2 MiB pages) and prefetch.c (the next frame
#     read and hashed by a second thread, POSIX threads of libc); all
#     archived into libstray.a, linked with $(STRAY_LDLIBS);
#   - its plots go through the OpenCV image writer (tools/module.mk);
#   - tests/reduce: unit tests, the synthetic-sweep generator
#     (tests/reduce/synth_*.c, the truth stays there) and the end-to-end
#     hidden-effect tests; the bench bench/bench_reduce.

REDUCE_SRC := $(wildcard libstray/reduce/*.c)
REDUCE_OBJ := $(REDUCE_SRC:%.c=$(B)/obj/%.o)
$(STRAY_LIB): $(REDUCE_OBJ)
# accum.c's usual-row loop is written to vectorise (no reassociation: the
# same bits as scalar code)
$(B)/obj/libstray/reduce/accum.o: EXTRA_CFLAGS += -ftree-vectorize
# so are the darks' per-pixel statistics and the 16-bit decode of a frame
$(B)/obj/libstray/reduce/pixmask.o: EXTRA_CFLAGS += -ftree-vectorize
$(B)/obj/libstray/sweep/fits_read.o: EXTRA_CFLAGS += -ftree-vectorize
# and the frame-wide sums of common.c and response.c (pixel_sums.h: a
# fixed order of eight partial sums, so the same bits on every machine)
$(B)/obj/libstray/reduce/common.o: EXTRA_CFLAGS += -ftree-vectorize
$(B)/obj/libstray/reduce/response.o: EXTRA_CFLAGS += -ftree-vectorize

# Tests: one binary per file.  Unit tests of the math link libstray;
# the sweep tests link the generator and run build/bin/stray.
REDUCE_TEST_SYNTH := $(B)/obj/tests/reduce/synth_sweep.o
REDUCE_TESTS := $(patsubst tests/reduce/%.c,$(B)/tests/reduce/%,\
	$(wildcard tests/reduce/test_*.c))
TESTS += $(REDUCE_TESTS)

$(B)/obj/tests/reduce/%.o: EXTRA_CFLAGS += -Itests -I/usr/include/cjson

# The end-to-end ones run build/bin/stray: they need it built first.
$(B)/tests/reduce/test_sweep $(B)/tests/reduce/test_sweep_errors: $(STRAY_BIN)
$(B)/tests/reduce/%: $(B)/obj/tests/reduce/%.o $(REDUCE_TEST_SYNTH) \
		$(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(REDUCE_TEST_SYNTH) $(STRAY_LIB) \
		$(CMOCKA_LIBS) $(STRAY_LDLIBS)

# The sweep store's manifest/FITS parsers under libFuzzer (`make fuzz`,
# `make fuzz-smoke`).
# (the library archives come from tests/module.mk, read after this file)
build/fuzz/fuzz_reduce_input: tests/fuzz/fuzz_reduce_input.c \
		build/fuzz/obj/libsweep_fuzz.a build/fuzz/obj/libstray_fuzz.a
	@mkdir -p $(dir $@)
	$(CLANG) -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
		$(CPPFLAGS_HOST) -I/usr/include/cjson \
		-DSTRAY_DATA_DIR=\"libstray/data\" -o $@ $^ $(STRAY_LDLIBS)

# make bench: full-frame throughput against memcpy in the same run.
BENCHES += $(B)/bench/bench_reduce
$(B)/obj/bench/bench_reduce.o: EXTRA_CFLAGS += -Itests/reduce
$(B)/bench/bench_reduce: $(B)/obj/bench/bench_reduce.o $(REDUCE_TEST_SYNTH) \
		$(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $^ $(STRAY_LDLIBS)

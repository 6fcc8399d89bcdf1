# libstray/reduce: lab frames to the lens curve (thesis §3.2).
#
# Listed in MODULES after tools, because it extends what tools/module.mk
# defines:
#   - libstray/reduce/*.c: pure reduction math (libc/libm only, no heap),
#     archived into libstray.a with the rest of the library;
#   - the I/O that feeds it lives in tools/ (cfitsio frames, libcsv
#     manifest, OpenSSL SHA-256: tools/sweep_*.c), with the OpenCV image
#     writer tools/image_cv.cpp; this file adds their link flags;
#   - tests/reduce: unit tests, the synthetic-sweep generator
#     (tests/reduce/synth_*.c, the truth stays there) and the end-to-end
#     hidden-effect tests; the bench bench/bench_reduce.

REDUCE_SRC := $(wildcard libstray/reduce/*.c)
REDUCE_OBJ := $(REDUCE_SRC:%.c=$(B)/obj/%.o)
$(STRAY_LIB): $(REDUCE_OBJ)

REDUCE_IO_LDLIBS := -lcfitsio -lcrypto -lcsv
OPENCV_CFLAGS := -I/usr/include/opencv4
OPENCV_LDLIBS := -lopencv_imgcodecs -lopencv_imgproc -lopencv_core

# The C++ image writer (OpenCV 4 has no C API) and the link flags.
IMAGE_CV_OBJ := $(B)/obj/tools/image_cv.o
$(IMAGE_CV_OBJ): tools/image_cv.cpp
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -Wall -Wextra -Werror $(OPT) $(SANFLAGS) -MMD -MP \
		-Itools $(OPENCV_CFLAGS) -c $< -o $@
TOOLS_OBJ += $(IMAGE_CV_OBJ)
$(STRAY_BIN): $(IMAGE_CV_OBJ)
TOOLS_LDLIBS += $(REDUCE_IO_LDLIBS) $(OPENCV_LDLIBS) -lstdc++

# Tests: one binary per file.  Unit tests of the math link libstray;
# the sweep tests link the generator and run build/bin/stray.
REDUCE_TEST_SYNTH := $(B)/obj/tests/reduce/synth_sweep.o
REDUCE_TOOL_IO := $(B)/obj/tools/sweep_manifest.o \
	$(B)/obj/tools/sweep_fits.o
REDUCE_TESTS := $(patsubst tests/reduce/%.c,$(B)/tests/reduce/%,\
	$(wildcard tests/reduce/test_*.c))
TESTS += $(REDUCE_TESTS)

$(B)/obj/tests/reduce/%.o: EXTRA_CFLAGS += -Itests -Itools \
	-I/usr/include/cjson

# The end-to-end ones run build/bin/stray: they need it built first.
$(B)/tests/reduce/test_sweep $(B)/tests/reduce/test_sweep_errors: $(STRAY_BIN)
$(B)/tests/reduce/%: $(B)/obj/tests/reduce/%.o $(REDUCE_TEST_SYNTH) \
		$(REDUCE_TOOL_IO) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(REDUCE_TEST_SYNTH) $(REDUCE_TOOL_IO) \
		$(STRAY_LIB) $(CMOCKA_LIBS) -lcjson $(REDUCE_IO_LDLIBS) \
		$(STRAY_LDLIBS)

# The manifest/FITS parsers under libFuzzer (`make fuzz`, `make fuzz-smoke`).
build/fuzz/fuzz_reduce_input: tests/fuzz/fuzz_reduce_input.c \
		tools/sweep_manifest.c tools/sweep_fits.c $(STRAY_CORE_SRC) \
		$(STRAY_HOST_SRC) libstray/host/builtin_data.S
	@mkdir -p $(dir $@)
	$(CLANG) -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
		$(CPPFLAGS_HOST) -Itools -I/usr/include/cjson \
		-DSTRAY_DATA_DIR=\"libstray/data\" -o $@ $^ \
		-lcfitsio -lcrypto -lcsv -lcjson -lm

# make bench: full-frame throughput against memcpy in the same run.
BENCHES += $(B)/bench/bench_reduce
$(B)/obj/bench/bench_reduce.o: EXTRA_CFLAGS += -Itools -Itests/reduce
$(B)/bench/bench_reduce: $(B)/obj/bench/bench_reduce.o $(REDUCE_TEST_SYNTH) \
		$(B)/obj/tools/sweep_reduce.o $(REDUCE_TOOL_IO) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $^ $(REDUCE_IO_LDLIBS) $(STRAY_LDLIBS)

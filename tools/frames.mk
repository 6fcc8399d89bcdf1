# tools/frames.mk - `stray frames` (issue 13 items 3-5): the C++ star
# detectors (OpenCV behind tools/frames_detect.h), the cmocka tests in
# tests/frames and the bench bench/bench_frames.  The renderer is in
# libstray/frames, the extended FDR model in libstray/core/fdr_field.c.

FRAMES_DETECT_OBJ := $(B)/obj/tools/frames_detect.o
$(FRAMES_DETECT_OBJ): tools/frames_detect.cpp tools/frames_detect.h
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -Wall -Wextra -Werror $(OPT) $(SANFLAGS) -MMD -MP \
		-Itools -I/usr/include/opencv4 -c $< -o $@
TOOLS_OBJ += $(FRAMES_DETECT_OBJ)
$(STRAY_BIN): $(FRAMES_DETECT_OBJ)

# The analysis objects the tests and the bench link (not cmd_frames).
FRAMES_ANALYSIS_OBJ := $(FRAMES_DETECT_OBJ) $(B)/obj/tools/frames_run.o \
	$(B)/obj/tools/frames_diagnose.o
FRAMES_LDLIBS := -lopencv_imgproc -lopencv_core -lstdc++

FRAMES_TESTS := $(patsubst tests/frames/%.c,$(B)/tests/frames/%,\
	$(wildcard tests/frames/test_*.c))
TESTS += $(FRAMES_TESTS)
$(B)/obj/tests/frames/%.o: EXTRA_CFLAGS += -Itools -Itests \
	-I/usr/include/cjson
# The CLI test runs build/bin/stray: it needs it built first.
$(B)/tests/frames/test_frames_cli: $(STRAY_BIN)
$(B)/tests/frames/%: $(B)/obj/tests/frames/%.o $(FRAMES_ANALYSIS_OBJ) \
		$(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(FRAMES_ANALYSIS_OBJ) $(STRAY_LIB) \
		-lcmocka -lcjson $(FRAMES_LDLIBS) $(STRAY_LDLIBS)

BENCHES += $(B)/bench/bench_frames
$(B)/obj/bench/bench_frames.o: EXTRA_CFLAGS += -Itools
$(B)/bench/bench_frames: $(B)/obj/bench/bench_frames.o $(FRAMES_ANALYSIS_OBJ) \
		$(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(FRAMES_ANALYSIS_OBJ) $(STRAY_LIB) \
		$(FRAMES_LDLIBS) $(STRAY_LDLIBS)

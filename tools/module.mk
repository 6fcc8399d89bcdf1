# tools: the `stray` command, one file per subcommand, and its plots.

STRAY_BIN := $(B)/bin/stray
TOOLS_SRC := $(wildcard tools/*.c)
TOOLS_OBJ := $(TOOLS_SRC:%.c=$(B)/obj/%.o)
TOOLS_LDLIBS := -lplplot -lcjson

$(TOOLS_OBJ): EXTRA_CFLAGS += -Itools -I/usr/include/cjson -I/usr/include/plplot
# Public headers: the commands' entry points (tools/entry.h, for stray-mpi)
# and the tracer's runner that the commands which trace are given.
$(TOOLS_OBJ): EXTRA_CFLAGS += -Itools/include -Itracer/include

$(STRAY_BIN): $(TOOLS_OBJ) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $(TOOLS_OBJ) $(STRAY_LIB) $(TOOLS_LDLIBS) $(STRAY_LDLIBS)

all: $(STRAY_BIN)

install-tools: $(STRAY_BIN)
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 755 $(STRAY_BIN) $(DESTDIR)$(PREFIX)/bin/
install: install-tools

# OpenCV (4 has no C API): the C++ image writer of the plots, maps and
# frames (tools/image_cv.cpp) and the star detectors of `stray frames`
# (tools/frames_detect.cpp), behind C headers.
OPENCV_CFLAGS := -I/usr/include/opencv4
OPENCV_LDLIBS := -lopencv_imgcodecs -lopencv_imgproc -lopencv_core
CV_CXX = $(CXX) -std=c++17 -Wall -Wextra -Werror $(OPT) $(SANFLAGS) -MMD -MP \
	-Itools -Ilibstray/include $(OPENCV_CFLAGS)

IMAGE_CV_OBJ := $(B)/obj/tools/image_cv.o
$(IMAGE_CV_OBJ): tools/image_cv.cpp
	@mkdir -p $(dir $@)
	$(CV_CXX) -c $< -o $@
TOOLS_OBJ += $(IMAGE_CV_OBJ)
$(STRAY_BIN): $(IMAGE_CV_OBJ)
TOOLS_LDLIBS += $(OPENCV_LDLIBS) -lstdc++

# `stray frames` (issue 13): the detectors, the analysis objects its
# tests (tests/frames) and bench (bench/bench_frames) link; the renderer
# is in libstray/frames, the extended FDR model in libstray/core/fdr_field.c.
FRAMES_DETECT_OBJ := $(B)/obj/tools/frames_detect.o
$(FRAMES_DETECT_OBJ): tools/frames_detect.cpp tools/frames_detect.h
	@mkdir -p $(dir $@)
	$(CV_CXX) -c $< -o $@
TOOLS_OBJ += $(FRAMES_DETECT_OBJ)
$(STRAY_BIN): $(FRAMES_DETECT_OBJ)

# The analysis objects the tests and the bench link (not cmd_frames).
FRAMES_ANALYSIS_OBJ := $(FRAMES_DETECT_OBJ) $(B)/obj/tools/frames_run.o \
	$(B)/obj/tools/frames_diagnose.o $(B)/obj/tools/frames_adc.o \
	$(B)/obj/tools/frames_mapterm.o $(B)/obj/tools/frames_io.o
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

# `stray availability` (issue 15): the heads fly in parallel (OpenMP).
$(B)/obj/tools/avail_mission.o: EXTRA_CFLAGS += -fopenmp
TOOLS_LDLIBS += -fopenmp
# Its CLI test checks the Sun angle against ERFA.
$(B)/tests/tools/test_availability: $(B)/obj/tests/tools/test_availability.o \
		tests/tools/run_cli.h $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< -lcmocka -lcjson -lerfa -lm
# make bench: one year at 10 s for three heads (scripts/bench.sh runs it).
BENCHES += bench/bench_availability.sh
# Issue 31's CCSDS probes: ERFA says where leap seconds are; flightcheck
# frames come from the generator.
$(B)/tests/tools/test_hardening2_ccsds: $(B)/obj/tests/tools/test_hardening2_ccsds.o \
		tests/tools/run_cli.h $(STRAY_BIN) $(FLIGHT_GEN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< -lcmocka -lcjson -lerfa -lm
# Issue 30's CCSDS conformance from the command line: the ITRF orbit it
# flies is made with ERFA.
$(B)/tests/tools/test_ccsds_cli: $(B)/obj/tests/tools/test_ccsds_cli.o \
		tests/tools/run_cli.h $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< -lcmocka -lcjson -lerfa -lm

# frames: rendered detector frames checked against the FDR model, as a
# library (libframes.a): a run of frames (render, detect, count), the
# star detectors (OpenCV, C++ behind C headers), the frame diagnosis, the
# real sky for a head's attitude, lost stars, the sweep-folder frames,
# the OpenCV image writer, and the focal-plane map (written from a trace,
# read back for the frames).  Public headers in frames/include/frames/;
# `stray frames` (tools/cmd_frames.c) parses, prints and plots.
# Listed in MODULES after tracer: it puts itself ahead of libtracer and
# libstray in the `stray` link (the focal map is made from a trace).

FRAMES_SRC := $(wildcard frames/*.c)
FRAMES_CXX_SRC := $(wildcard frames/*.cpp)
FRAMES_OBJ := $(FRAMES_SRC:%.c=$(B)/obj/%.o) \
	$(FRAMES_CXX_SRC:%.cpp=$(B)/obj/%.o)
FRAMES_LIB := $(B)/lib/libframes.a
FRAMES_CFLAGS := -Iframes/include -Itracer/include

# OpenCV (4 has no C API): the C++ sources behind C headers.
OPENCV_CFLAGS := -I/usr/include/opencv4
OPENCV_LDLIBS := -lopencv_imgcodecs -lopencv_imgproc -lopencv_core
CV_CXX = $(CXX) -std=c++17 -Wall -Wextra -Werror $(OPT) $(SANFLAGS) -MMD -MP -fPIC \
	-Iframes/include -Ilibstray/include $(OPENCV_CFLAGS)
FRAMES_LDLIBS := $(OPENCV_LDLIBS) -lstdc++

$(FRAMES_OBJ): EXTRA_CFLAGS += $(FRAMES_CFLAGS) -I/usr/include/cjson \
	-D_DEFAULT_SOURCE
$(B)/obj/frames/%.o: frames/%.cpp
	@mkdir -p $(dir $@)
	$(CV_CXX) -c $< -o $@

$(eval $(call stray_library,frames,$(FRAMES_LIB),$(FRAMES_OBJ)))

$(TOOLS_OBJ): EXTRA_CFLAGS += -Iframes/include
$(STRAY_BIN): $(FRAMES_LIB)
TOOLS_LDLIBS := $(FRAMES_LIB) $(TOOLS_LDLIBS) $(FRAMES_LDLIBS)

# Tests (tests/frames) and the bench link the library.
FRAMES_TESTS := $(patsubst tests/frames/%.c,$(B)/tests/frames/%,\
	$(wildcard tests/frames/test_*.c))
TESTS += $(FRAMES_TESTS)
$(B)/obj/tests/frames/%.o: EXTRA_CFLAGS += -Iframes/include -Itests \
	-I/usr/include/cjson
# The CLI test runs build/bin/stray: it needs it built first.
$(B)/tests/frames/test_frames_cli: $(STRAY_BIN)
$(B)/tests/frames/%: $(B)/obj/tests/frames/%.o $(FRAMES_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(FRAMES_LIB) $(STRAY_LIB) \
		-lcmocka -lcjson $(FRAMES_LDLIBS) $(STRAY_LDLIBS)

BENCHES += $(B)/bench/bench_frames
$(B)/obj/bench/bench_frames.o: EXTRA_CFLAGS += -Iframes/include
$(B)/bench/bench_frames: $(B)/obj/bench/bench_frames.o $(FRAMES_LIB) \
		$(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(FRAMES_LIB) $(STRAY_LIB) \
		$(FRAMES_LDLIBS) $(STRAY_LDLIBS)

# The focal-map CLI test runs build/bin/stray and reads its FITS back,
# also through the reader `stray frames` uses (frames/focal_map_read.c).
$(B)/obj/tests/tracer/test_cmd_focal_map.o: \
	EXTRA_CFLAGS += -I/usr/include/cjson -Iframes/include
$(B)/tests/tracer/test_cmd_focal_map: \
		$(B)/obj/tests/tracer/test_cmd_focal_map.o $(FRAMES_LIB) \
		$(TRACER_LIB) $(STRAY_LIB) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(FRAMES_LIB) $(TRACER_LIB) $(STRAY_LIB) \
		$(CMOCKA_LIBS) $(TRACER_LDLIBS) -lcjson -lcfitsio \
		$(FRAMES_LDLIBS) $(STRAY_LDLIBS)

# tracer: Monte Carlo stray-light tracer on Embree 3 (issue 3).
# Listed after tools in MODULES: it adds itself to the `stray` link.

TRACER_SRC := $(wildcard tracer/*.c)
TRACER_OBJ := $(TRACER_SRC:%.c=$(B)/obj/%.o)
TRACER_LIB := $(B)/lib/libtracer.a
TRACER_LDLIBS := -lembree3 -lassimp -lcjson -lpthread

$(TRACER_OBJ): EXTRA_CFLAGS += -Itracer/include -I/usr/include/cjson -D_DEFAULT_SOURCE
# the angle screen of the next-event connections is written to vectorise
# (no reassociation: the same bits as scalar code)
$(B)/obj/tracer/beam_screen.o: EXTRA_CFLAGS += -ftree-vectorize -fno-trapping-math
$(B)/obj/tools/cmd_trace.o: EXTRA_CFLAGS += -Itracer/include

$(TRACER_LIB): $(TRACER_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

# `stray trace` lives in tools/; link the tracer into the one binary.
$(STRAY_BIN): $(TRACER_LIB)
TOOLS_LDLIBS += $(TRACER_LIB) $(STRAY_LIB) $(TRACER_LDLIBS)

all: $(TRACER_LIB)

TRACER_TESTS := $(patsubst tests/tracer/%.c,$(B)/tests/tracer/%,\
	$(wildcard tests/tracer/test_*.c))
TESTS += $(TRACER_TESTS)

$(B)/obj/tests/tracer/%.o: EXTRA_CFLAGS += -Itracer/include -Itests/tracer -D_DEFAULT_SOURCE
$(B)/tests/tracer/%: $(B)/obj/tests/tracer/%.o $(TRACER_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(TRACER_LIB) $(STRAY_LIB) $(CMOCKA_LIBS) $(TRACER_LDLIBS) $(STRAY_LDLIBS)

# The CLI test runs build/bin/stray as a user would.
$(B)/tests/tracer/test_cmd_trace: $(STRAY_BIN)
$(B)/obj/tests/tracer/test_cmd_trace.o: EXTRA_CFLAGS += -I/usr/include/cjson
$(B)/tests/tracer/test_cmd_trace: TRACER_LDLIBS += -lcjson

# make bench: speed against in-run baselines; make peer-check: agreement
# with the Mitsuba 3 reference curve in ../shared/peers (not in `make test`).
BENCHES += $(B)/bench/bench_trace
$(B)/obj/bench/bench_trace.o: EXTRA_CFLAGS += -Itracer/include -I/usr/include/cjson -D_DEFAULT_SOURCE
$(B)/bench/bench_trace: $(B)/obj/bench/bench_trace.o $(TRACER_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(TRACER_LIB) $(STRAY_LIB) $(TRACER_LDLIBS) $(STRAY_LDLIBS)

.PHONY: peer-check
peer-check: $(B)/bench/bench_trace
	$(B)/bench/bench_trace --peer

# libFuzzer (clang) on the angle list and --set parsers, run with the
# others (FUZZ_TARGETS in tests/module.mk); seeds in tests/fuzz/seeds/tracer_args.
TRACER_FUZZ := build/fuzz/fuzz_tracer_args
$(TRACER_FUZZ): tests/tracer/fuzz_tracer_args.c tracer/angles.c \
		tracer/baffle_params.c $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
		$(CPPFLAGS_HOST) -D_DEFAULT_SOURCE -Itracer/include \
		-I/usr/include/cjson -DSTRAY_DATA_DIR=\"libstray/data\" \
		-o $@ $^ $(STRAY_LDLIBS)

# The virtual photometer draws its noise from the tracer's Philox streams.
$(B)/obj/tools/cmd_photometer.o: EXTRA_CFLAGS += -Itracer/include


# diagnose: the model-vs-measurement library (issue 5): the registry of
# physical causes (one file each, cause_<name>.c), the evaluator and its
# trace cache over the tracer, the fit, the diagnosis as data.  Public
# headers in diagnose/include/diagnose/ (diag_*.h); its traces run through
# the caller's runner (tracer/runner.h).  `stray diagnose` (tools/) prints,
# plots and writes JSON; stray-mpi (mpi/) passes its farm as the runner.
# Listed in MODULES after tools and tracer: it adds itself to their links.

DIAG_SRC := $(wildcard diagnose/*.c)
DIAG_OBJ := $(DIAG_SRC:%.c=$(B)/obj/%.o)
DIAG_LIB := $(B)/lib/libdiagnose.a
DIAG_CFLAGS := -Idiagnose/include -Itracer/include -D_DEFAULT_SOURCE \
	-I/usr/include/cjson

$(DIAG_OBJ): EXTRA_CFLAGS += $(DIAG_CFLAGS) -Idiagnose
$(DIAG_LIB): $(DIAG_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

all: $(DIAG_LIB)

# `stray diagnose` in tools/: the command, its report, JSON and plots.
DIAG_TOOLS_OBJ := $(patsubst %,$(B)/obj/tools/%.o,cmd_diagnose diag_report \
	diag_json plot_diag)
$(DIAG_TOOLS_OBJ): EXTRA_CFLAGS += $(DIAG_CFLAGS)
$(STRAY_BIN): $(DIAG_LIB)
TOOLS_LDLIBS := $(DIAG_LIB) $(TOOLS_LDLIBS)

# Hidden-effect tests: a truth generator (tests/diagnose/truth.c, calls
# the tracer with its own seed) writes "measured" curves, the tests run
# build/bin/stray diagnose on them.  Minutes under ASan: TESTS_SLOW.
# test_diag_errors (bad input, no tracing), test_diag_runner (the
# library's public headers with a runner of its own, small traces) and
# test_diag_beams (pivot-offset nodes in one pass = full re-traces, small
# traces) and test_diag_speed (issue 27: two fitting threads = one, bit
# for bit, every trace on the caller's thread; small traces) run in both
# passes.
DIAG_TRUTH := $(B)/obj/tests/diagnose/truth.o
DIAG_TESTS := $(patsubst tests/diagnose/%.c,$(B)/tests/diagnose/%,\
	$(wildcard tests/diagnose/test_*.c))
DIAG_TESTS_FAST := $(B)/tests/diagnose/test_diag_errors \
	$(B)/tests/diagnose/test_diag_runner $(B)/tests/diagnose/test_diag_beams \
	$(B)/tests/diagnose/test_diag_speed
TESTS += $(DIAG_TESTS_FAST)
TESTS_SLOW += $(filter-out $(DIAG_TESTS_FAST),$(DIAG_TESTS))

$(B)/obj/tests/diagnose/%.o: EXTRA_CFLAGS += -Itests -Itests/diagnose \
	$(DIAG_CFLAGS) -I/usr/include/cjson
# test_diag_beams checks the trace cache's internals (trace_cache.h)
$(B)/obj/tests/diagnose/test_diag_beams.o: EXTRA_CFLAGS += -Idiagnose

$(B)/tests/diagnose/%: $(B)/obj/tests/diagnose/%.o $(DIAG_TRUTH) \
		$(DIAG_LIB) $(TRACER_LIB) $(STRAY_LIB) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(DIAG_TRUTH) $(DIAG_LIB) $(TRACER_LIB) \
		$(STRAY_LIB) $(CMOCKA_LIBS) -lcjson $(TRACER_LDLIBS) \
		$(STRAY_LDLIBS)

# make bench: a full 90-angle diagnosis against one trace of the same run.
BENCHES += $(B)/bench/bench_diagnose
$(B)/bench/bench_diagnose: $(B)/obj/tests/diagnose/bench_diagnose.o \
		$(DIAG_TRUTH) $(TRACER_LIB) $(STRAY_LIB) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(DIAG_TRUTH) $(TRACER_LIB) \
		$(STRAY_LIB) -lcjson $(TRACER_LDLIBS) $(STRAY_LDLIBS)

# make bench: per-surface-group localisation (issue 17 item 4), >= 20
# groups, re-weighting only, against the one trace it needs.
BENCHES += $(B)/bench/bench_surfaces
$(B)/bench/bench_surfaces: $(B)/obj/tests/diagnose/bench_surfaces.o \
		$(DIAG_TRUTH) $(DIAG_LIB) $(TRACER_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(DIAG_TRUTH) $(DIAG_LIB) $(TRACER_LIB) \
		$(STRAY_LIB) -lcjson $(TRACER_LDLIBS) $(STRAY_LDLIBS)

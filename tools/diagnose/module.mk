# tools/diagnose: `stray diagnose` (issue 5), the registry of physical
# causes (one file each, cause_<name>.c), the evaluator over the tracer,
# the fit and the report.  Listed in MODULES after tools and tracer: it
# adds its objects to the `stray` link as libstray/reduce does.

DIAG_SRC := $(wildcard tools/diagnose/*.c)
DIAG_OBJ := $(DIAG_SRC:%.c=$(B)/obj/%.o)
DIAG_CFLAGS := -Itools -Itools/diagnose -Itracer/include \
	-I/usr/include/cjson -I/usr/include/plplot -D_DEFAULT_SOURCE

$(DIAG_OBJ) $(B)/obj/tools/cmd_diagnose.o: EXTRA_CFLAGS += $(DIAG_CFLAGS)
TOOLS_OBJ += $(DIAG_OBJ)
$(STRAY_BIN): $(DIAG_OBJ)

# Hidden-effect tests: a truth generator (tests/diagnose/truth.c, calls
# the tracer with its own seed) writes "measured" curves, the tests run
# build/bin/stray diagnose on them.  Minutes under ASan: TESTS_SLOW.
# test_diag_errors (bad input, no tracing) runs in both passes.
DIAG_TRUTH := $(B)/obj/tests/diagnose/truth.o
DIAG_TESTS := $(patsubst tests/diagnose/%.c,$(B)/tests/diagnose/%,\
	$(wildcard tests/diagnose/test_*.c))
DIAG_TESTS_FAST := $(B)/tests/diagnose/test_diag_errors
TESTS += $(DIAG_TESTS_FAST)
TESTS_SLOW += $(filter-out $(DIAG_TESTS_FAST),$(DIAG_TESTS))

$(B)/obj/tests/diagnose/%.o: EXTRA_CFLAGS += -Itests -Itests/diagnose \
	-Itracer/include -I/usr/include/cjson -D_DEFAULT_SOURCE

$(B)/tests/diagnose/%: $(B)/obj/tests/diagnose/%.o $(DIAG_TRUTH) \
		$(TRACER_LIB) $(STRAY_LIB) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(DIAG_TRUTH) $(TRACER_LIB) \
		$(STRAY_LIB) $(CMOCKA_LIBS) -lcjson $(TRACER_LDLIBS) \
		$(STRAY_LDLIBS)

# make bench: a full 90-angle diagnosis against one trace of the same run.
BENCHES += $(B)/bench/bench_diagnose
$(B)/bench/bench_diagnose: $(B)/obj/tests/diagnose/bench_diagnose.o \
		$(DIAG_TRUTH) $(TRACER_LIB) $(STRAY_LIB) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(DIAG_TRUTH) $(TRACER_LIB) \
		$(STRAY_LIB) -lcjson $(TRACER_LDLIBS) $(STRAY_LDLIBS)

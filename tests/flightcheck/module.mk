# tests/flightcheck: `stray flightcheck` (issue 18) on flight frames made
# by the truth generator (truth.c, test side only) with a hidden scale.
# The analysis is libmission (mission/flightcheck*.c).
FLIGHTCHECK_OBJ := $(MISSION_LIB)
FLIGHTCHECK_TRUTH_OBJ := $(B)/obj/tests/flightcheck/truth.o
$(B)/obj/tests/flightcheck/%.o: EXTRA_CFLAGS += -Imission/include -Itests \
	-Itests/flightcheck -Ifirmware_fdr/include
FLIGHTCHECK_TESTS := $(patsubst tests/flightcheck/%.c,$(B)/tests/flightcheck/%,\
	$(wildcard tests/flightcheck/test_*.c))
TESTS += $(FLIGHTCHECK_TESTS)
$(B)/tests/flightcheck/%: $(B)/obj/tests/flightcheck/%.o $(FLIGHTCHECK_OBJ) \
		$(FLIGHTCHECK_TRUTH_OBJ) $(STRAY_LIB) $(FDRFW_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -fopenmp -o $@ $< $(FLIGHTCHECK_OBJ) \
		$(FLIGHTCHECK_TRUTH_OBJ) $(STRAY_LIB) $(FDRFW_LIB) -lcmocka \
		$(STRAY_LDLIBS)
# The generator as a program (demo, bench); not a test.
FLIGHT_GEN := $(B)/tests/flightcheck/make_flight
$(FLIGHT_GEN): $(B)/obj/tests/flightcheck/make_flight.o $(FLIGHTCHECK_TRUTH_OBJ) \
		$(STRAY_LIB) $(FDRFW_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(FLIGHTCHECK_TRUTH_OBJ) $(STRAY_LIB) \
		$(FDRFW_LIB) $(STRAY_LDLIBS)
all: $(FLIGHT_GEN)
# make bench: the per-frame step on full frames (target >= 10 frames/s).
BENCHES += $(B)/bench/bench_flightcheck
$(B)/obj/bench/bench_flightcheck.o: EXTRA_CFLAGS += -Imission/include -fopenmp
$(B)/bench/bench_flightcheck: $(B)/obj/bench/bench_flightcheck.o \
		$(MISSION_LIB) $(STRAY_LIB) $(FDRFW_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -fopenmp -o $@ $< $(MISSION_LIB) $(STRAY_LIB) \
		$(FDRFW_LIB) $(STRAY_LDLIBS)
# The diagnosis test runs build/bin/stray (trace, flightcheck, diagnose).
$(B)/obj/tests/flightcheck/test_flightcheck_diag.o: EXTRA_CFLAGS += \
	-I/usr/include/cjson
$(B)/tests/flightcheck/test_flightcheck_diag: $(STRAY_BIN)
# The real-sky test runs make_flight and build/bin/stray.
$(B)/obj/tests/flightcheck/test_flightcheck_sky.o: EXTRA_CFLAGS += \
	-I/usr/include/cjson
$(B)/tests/flightcheck/test_flightcheck_sky: $(STRAY_BIN) $(FLIGHT_GEN)

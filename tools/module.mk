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

# The image writer, the star detectors and the frames are libframes
# (frames/module.mk), which adds itself and OpenCV to the link.
# `stray availability` (issue 15) is libmission (mission/module.mk).
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

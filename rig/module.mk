# rig: strayrigd, the lab sweep daemon; device drivers above the HAL seam,
# real backends (libusb, hidapi, libgpiod) and simulators below it.  The
# sweep folder is written through libstray's sweep store (libstray.a).

RIG_SRC := $(filter-out rig/daemon/strayrigd.c,\
	$(wildcard rig/*.c rig/hal/*.c rig/backend/*.c rig/proto/*.c \
		rig/drv/*.c rig/sim/*.c rig/sweep/*.c rig/daemon/*.c \
		rig/indi/*.c))
# The INDI backend's client is C++ (libindi's INDI::BaseClient), behind
# the C calls of rig/include/rig/indi.h.
RIG_INDI_CXX_OBJ := $(B)/obj/rig/indi/indi_client.o
RIG_OBJ := $(RIG_SRC:%.c=$(B)/obj/%.o) $(RIG_INDI_CXX_OBJ)
RIG_LIB := $(B)/lib/librig.a
RIG_BIN := $(B)/bin/strayrigd
RIG_CFLAGS := -Irig/include -I/usr/include/libusb-1.0 -I/usr/include/hidapi \
	-I/usr/include/cjson
RIG_LDLIBS := $(STRAY_LIB) -lusb-1.0 -lhidapi-hidraw -lgpiod -lz -lcjson \
	-lindiclient -lstdc++ -lpthread $(STRAY_LDLIBS)

$(RIG_INDI_CXX_OBJ): rig/indi/indi_client.cpp rig/include/rig/indi.h
	@mkdir -p $(dir $@)
	$(CXX) -std=c++17 -Wall -Wextra -Werror $(OPT) $(SANFLAGS) -MMD -MP \
		-Irig/include -I/usr/include/libindi -c $< -o $@

$(RIG_OBJ) $(B)/obj/rig/daemon/strayrigd.o: EXTRA_CFLAGS += $(RIG_CFLAGS)

$(RIG_LIB): $(RIG_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

$(RIG_BIN): $(B)/obj/rig/daemon/strayrigd.o $(RIG_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(RIG_LIB) $(RIG_LDLIBS)

all: $(RIG_BIN)

# The simulator's headers (sim.h, sim_config.h, vlab.h, ...) are its own.
RIG_CFLAGS += -Irig/sim/include

# Tests: one cmocka binary per source file.  Driver tests wrap the HAL
# (-Wl,--wrap=rig_hal_*), the end-to-end ones run against the simulators.
RIG_TESTS := $(patsubst tests/rig/%.c,$(B)/tests/rig/%,\
	$(wildcard tests/rig/test_*.c))
# test_sigma: eight demo sweeps and 25 kills, ~25 s (minutes under ASan).
# test_indi_sweep: seven sweeps and two probes through indiserver's simulators, ~80 s,
# the simulators' own timers (issue 26).
RIG_TESTS_SLOW := $(B)/tests/rig/test_sigma $(B)/tests/rig/test_indi_sweep
TESTS += $(filter-out $(RIG_TESTS_SLOW),$(RIG_TESTS))
TESTS_SLOW += $(RIG_TESTS_SLOW)
RIG_WRAP := -Wl,--wrap=rig_hal_usb_open,--wrap=rig_hal_usb_control \
	-Wl,--wrap=rig_hal_usb_write,--wrap=rig_hal_usb_read \
	-Wl,--wrap=rig_hal_usb_close,--wrap=rig_hal_now,--wrap=rig_hal_sleep

$(B)/obj/tests/rig/%.o: EXTRA_CFLAGS += $(RIG_CFLAGS) -Itests/rig

$(B)/tests/rig/test_stage_wrap: LDWRAP := $(RIG_WRAP)
$(B)/tests/rig/test_hal_fail_wrap: LDWRAP := \
	-Wl,--wrap=rig_hal_usb_open,--wrap=rig_hal_usb_control \
	-Wl,--wrap=rig_hal_usb_write,--wrap=rig_hal_usb_read \
	-Wl,--wrap=rig_hal_hid_open,--wrap=rig_hal_hid_write \
	-Wl,--wrap=rig_hal_hid_read,--wrap=rig_hal_gpio_open \
	-Wl,--wrap=rig_hal_gpio_set,--wrap=rig_hal_gpio_get
$(B)/tests/rig/test_daemon: $(STRAY_BIN)
# The end-to-end test runs `stray reduce` and reads its CSV with libstray.
$(B)/tests/rig/test_e2e_reduce: $(STRAY_BIN)
# issue 29: strayrigd and stray run as programs
$(B)/tests/rig/test_lab_ops $(B)/tests/rig/test_lab_safety $(B)/tests/rig/test_lab_time $(B)/tests/rig/test_lab_reduce: $(STRAY_BIN)
$(B)/tests/rig/%: $(B)/obj/tests/rig/%.o $(RIG_LIB) $(RIG_BIN) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) $(LDWRAP) -o $@ $< $(RIG_LIB) $(LDEXTRA) \
		$(CMOCKA_LIBS) $(RIG_LDLIBS)

install-rig: $(RIG_BIN)
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 755 $(RIG_BIN) $(DESTDIR)$(PREFIX)/bin/
install: install-rig

# Fuzz targets of the rig's parsers (tests/module.mk runs them: `make
# fuzz`, and `make fuzz-smoke` in `make test`); each links only the
# sources it exercises.
RIG_FUZZ_CFLAGS = -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
	$(CPPFLAGS_HOST) $(RIG_CFLAGS)

build/fuzz/fuzz_apt: tests/fuzz/fuzz_apt.c rig/proto/apt.c rig/status.c
	@mkdir -p $(dir $@)
	$(CLANG) $(RIG_FUZZ_CFLAGS) -o $@ $^

build/fuzz/fuzz_framelink: tests/fuzz/fuzz_framelink.c rig/proto/framelink.c \
		rig/status.c
	@mkdir -p $(dir $@)
	$(CLANG) $(RIG_FUZZ_CFLAGS) -o $@ $^ -lz

build/fuzz/fuzz_wheel_report: tests/fuzz/fuzz_wheel_report.c \
		rig/proto/wheel_report.c rig/proto/monitor_report.c rig/status.c
	@mkdir -p $(dir $@)
	$(CLANG) $(RIG_FUZZ_CFLAGS) -o $@ $^

build/fuzz/fuzz_rig_control: tests/fuzz/fuzz_rig_control.c \
		rig/daemon/request.c rig/status.c
	@mkdir -p $(dir $@)
	$(CLANG) $(RIG_FUZZ_CFLAGS) -o $@ $^ -lcjson -lm

build/fuzz/fuzz_rig_config: tests/fuzz/fuzz_rig_config.c rig/config.c \
		rig/config_defaults.c rig/config_json.c rig/devices.c \
		rig/indi/indi_config.c \
		rig/sim/sim_config.c rig/sim/vlab.c rig/status.c
	@mkdir -p $(dir $@)
	$(CLANG) $(RIG_FUZZ_CFLAGS) -o $@ $^ -lcjson -lm

# The umockdev test bed (issue 16, rig/testbed/): the real backends against
# emulated device nodes whose far side is the simulators.  umockdev comes
# with `make deps`; its flags are asked for when a recipe runs (=, not :=),
# so a bare machine's first `make` parses before it is installed.
RIG_TB_BIN := $(B)/bin/rig-testbed
RIG_TB_SHIM := $(B)/lib/rig-testbed-shim.so
UMOCKDEV_CFLAGS = $(shell pkg-config --cflags umockdev-1.0)
UMOCKDEV_LIBS = $(shell pkg-config --libs umockdev-1.0)
# The test bed's files (tb.h): its state, plugging, usbdevfs, hidraw, GPIO,
# the umockdev handler, and testbed.c's set-up and main.
RIG_TB_OBJ := $(patsubst %.c,$(B)/obj/%.o,$(filter-out rig/testbed/shim.c,\
	$(wildcard rig/testbed/*.c)))
$(RIG_TB_OBJ): EXTRA_CFLAGS += $(RIG_CFLAGS) $(UMOCKDEV_CFLAGS)
$(RIG_TB_BIN): $(RIG_TB_OBJ) $(RIG_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $(RIG_TB_OBJ) $(RIG_LIB) $(RIG_LDLIBS) \
		$(UMOCKDEV_LIBS)
$(RIG_TB_SHIM): rig/testbed/shim.c rig/testbed/testbed.h
	@mkdir -p $(dir $@)
	$(CC) -std=c99 $(WARN) -O2 -fPIC -shared -o $@ $< -ldl
all: $(RIG_TB_BIN) $(RIG_TB_SHIM)

# The test bed's check (tests/rig/testbed/test_testbed.sh): the demo sweep
# and a fault schedule through the real backends, frames compared with the
# simulated backend's; it says SKIP on one line where umockdev cannot run.
$(B)/tests/rig/testbed_sweep: tests/rig/testbed/test_testbed.sh $(RIG_BIN) \
		$(RIG_TB_BIN) $(RIG_TB_SHIM)
	@mkdir -p $(dir $@)
	install -m 755 $< $@
TESTS_SLOW += $(B)/tests/rig/testbed_sweep

# strayrig-probe (`stray rig probe`): what the real backend finds, and one
# exchange with each device (rig/probe/probe.c; an INDI lab through the
# daemon's INDI lab, rig/probe/probe_indi.c).
RIG_PROBE_BIN := $(B)/bin/strayrig-probe
RIG_PROBE_OBJ := $(B)/obj/rig/probe/probe.o $(B)/obj/rig/probe/probe_indi.o
$(RIG_PROBE_OBJ): EXTRA_CFLAGS += $(RIG_CFLAGS)
$(RIG_PROBE_BIN): $(RIG_PROBE_OBJ) $(RIG_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $(RIG_PROBE_OBJ) $(RIG_LIB) $(RIG_LDLIBS)
all: $(RIG_PROBE_BIN)
install-rig: install-rig-probe
install-rig-probe: $(RIG_PROBE_BIN)
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 755 $(RIG_PROBE_BIN) $(DESTDIR)$(PREFIX)/bin/
$(B)/tests/rig/testbed_sweep: $(RIG_PROBE_BIN) $(STRAY_BIN)

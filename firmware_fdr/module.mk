# firmware_fdr: the on-board module (flight sources, built for the host and
# for the Cortex-M4F), its ground-side table builder, its tests, and the
# `make firmware` footprint report.

FDRFW_SRC := $(wildcard firmware_fdr/*.c)
FDRFW_GROUND_SRC := $(wildcard firmware_fdr/ground/*.c)
FDRFW_OBJ := $(FDRFW_SRC:%.c=$(B)/obj/%.o)
FDRFW_GROUND_OBJ := $(FDRFW_GROUND_SRC:%.c=$(B)/obj/%.o)
FDRFW_LIB := $(B)/lib/libfdrfw.a
FDRFW_GROUND_LIB := $(B)/lib/libfdrfw_ground.a
# libstray's freestanding sources the module compiles in (not copies).
FDRFW_STRAY_SRC := $(addprefix libstray/core/,fdr.c tail.c root.c error.c \
	curve.c photometry.c)

# Flight code: single precision is enforced by -Wdouble-promotion.
$(FDRFW_OBJ): EXTRA_CFLAGS += -Ifirmware_fdr/include -ffreestanding \
	-Wdouble-promotion
$(FDRFW_GROUND_OBJ): EXTRA_CFLAGS += -Ifirmware_fdr/include

$(FDRFW_LIB): $(FDRFW_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

$(FDRFW_GROUND_LIB): $(FDRFW_GROUND_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

all: $(FDRFW_LIB) $(FDRFW_GROUND_LIB)

# `stray firmware-table` (tools/cmd_firmware_table.c) links both.
# Any subcommand may use the module's headers (cmd_orbit uses its ephemeris).
$(TOOLS_OBJ): EXTRA_CFLAGS += -Ifirmware_fdr/include
$(STRAY_BIN): $(FDRFW_GROUND_LIB) $(FDRFW_LIB) $(STRAY_CORE_LIB)
TOOLS_LDLIBS += $(FDRFW_GROUND_LIB) $(FDRFW_LIB) $(STRAY_CORE_LIB)

# Tests: cmocka, ERFA as the independent ephemeris.
FDRFW_TESTS := $(patsubst tests/firmware_fdr/%.c,$(B)/tests/firmware_fdr/%,\
	$(wildcard tests/firmware_fdr/test_*.c))
TESTS += $(FDRFW_TESTS)

$(B)/obj/tests/firmware_fdr/%.o: EXTRA_CFLAGS += -Ifirmware_fdr/include \
	-Itests/firmware_fdr -I/usr/include/cjson
# The command's test runs build/bin/stray as a user would.
$(B)/tests/firmware_fdr/test_firmware_table: $(STRAY_BIN)
FDRFW_TEST_SUPPORT := $(B)/obj/tests/firmware_fdr/fixture.o \
	$(B)/obj/tests/firmware_fdr/vector_check.o
FDRFW_TEST_DEPS := $(FDRFW_TEST_SUPPORT) $(FDRFW_GROUND_LIB) $(FDRFW_LIB) \
	$(STRAY_LIB)
define FDRFW_TEST_LINK
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(FDRFW_TEST_SUPPORT) \
		$(FDRFW_GROUND_LIB) $(FDRFW_LIB) $(STRAY_LIB) $(CMOCKA_LIBS) \
		-lerfa $(STRAY_LDLIBS)
endef
$(B)/tests/firmware_fdr/%: $(B)/obj/tests/firmware_fdr/%.o $(FDRFW_TEST_DEPS)
	$(FDRFW_TEST_LINK)

# libstray's core built as on the target (STRAY_REAL_FLOAT) for
# test_float_core: its objects, the module's table-to-model mapping and
# the shim float_core.c are linked into one relocatable object that keeps
# only fcore_* global, so the float core sits beside the double libstray
# in one binary and is compared with it.
FCORE_SRC := $(addprefix libstray/core/,fdr.c tail.c root.c error.c) \
	firmware_fdr/model_map.c tests/firmware_fdr/float_core.c
FCORE_OBJ := $(FCORE_SRC:%.c=$(B)/obj/fcore/%.o)
FCORE_REL := $(B)/obj/fcore/float_core_all.o

$(B)/obj/fcore/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) $(CPPFLAGS_HOST) -DSTRAY_REAL_FLOAT \
		-Wdouble-promotion -ffreestanding -Ifirmware_fdr/include \
		-Itests/firmware_fdr -c $< -o $@

$(FCORE_REL): $(FCORE_OBJ)
	$(CC) -r -nostdlib -o $@.all $^
	objcopy --wildcard --keep-global-symbol='fcore_*' $@.all $@
	rm -f $@.all

$(B)/tests/firmware_fdr/test_float_core: \
		$(B)/obj/tests/firmware_fdr/test_float_core.o $(FCORE_REL) \
		$(FDRFW_TEST_DEPS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(FCORE_REL) $(FDRFW_TEST_SUPPORT) \
		$(FDRFW_GROUND_LIB) $(FDRFW_LIB) $(STRAY_LIB) $(CMOCKA_LIBS) \
		-lerfa $(STRAY_LDLIBS)

# The detector tables in the module as it flies (STRAY_REAL_FLOAT, the
# flight sources only: no ground code), the tables from $(STRAY_BIN).
$(B)/tests/firmware_fdr/test_detector_float: \
		tests/firmware_fdr/test_detector_float.c $(FDRFW_SRC) \
		$(FDRFW_STRAY_SRC) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) $(CPPFLAGS_HOST) -DSTRAY_REAL_FLOAT \
		-DSTRAY_WITH_POISSON=0 -Ifirmware_fdr -Ifirmware_fdr/include \
		-o $@ $< $(FDRFW_SRC) $(FDRFW_STRAY_SRC) $(CMOCKA_LIBS) -lm

include firmware_fdr/target/target.mk

# The shared vectors (checked in): regenerate with `make fdrfw-vectors`.
$(B)/obj/tests/firmware_fdr/make_vectors.o: EXTRA_CFLAGS += -D_DEFAULT_SOURCE
$(B)/fdrfw/make_vectors: $(B)/obj/tests/firmware_fdr/make_vectors.o \
		$(B)/obj/tests/firmware_fdr/fixture.o $(FDRFW_GROUND_LIB) \
		$(FDRFW_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $^ $(CMOCKA_LIBS) $(STRAY_LDLIBS)

.PHONY: fdrfw-vectors
fdrfw-vectors: $(B)/fdrfw/make_vectors
	$< tests/vectors/fdrfw_curve.csv tests/vectors/fdrfw_vectors.h

# The blob parser and the frame behind it under libFuzzer (tests/module.mk
# runs every tests/fuzz/fuzz_*.c; this rule adds the module's sources).
build/fuzz/fuzz_fdrfw_blob: tests/fuzz/fuzz_fdrfw_blob.c $(FDRFW_SRC) \
		$(FDRFW_STRAY_SRC)
	@mkdir -p $(dir $@)
	$(CLANG) -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
		$(CPPFLAGS_HOST) -Ifirmware_fdr/include -o $@ $^ -lm

# The demo orbit (mission/orbit.c) against the module's attitude convention.
$(B)/obj/tests/tools/test_orbit.o: EXTRA_CFLAGS += -Ifirmware_fdr/include \
	-Imission/include
$(B)/tests/tools/test_orbit: $(B)/obj/tests/tools/test_orbit.o \
		$(MISSION_LIB) $(FDRFW_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $^ $(CMOCKA_LIBS) -lm

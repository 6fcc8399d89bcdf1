# The Cortex-M4F build of firmware_fdr (arm-none-eabi-gcc, newlib), its
# footprint report (`make firmware`) and the image the emulated test runs
# (qemu-system-arm -M mps2-an386, semihosting).  Fixed folder: the target
# build is the same for the normal and the sanitizer passes.

FW_B := build/firmware
ARM_CC ?= arm-none-eabi-gcc
ARM_SIZE ?= arm-none-eabi-size
QEMU_ARM ?= qemu-system-arm
ARM_ARCH := -mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard
ARM_CFLAGS := -std=c99 -Wall -Wextra -Werror $(ARM_ARCH) -Os -g -MMD -MP \
	-ffreestanding -ffunction-sections -fdata-sections -fstack-usage \
	-fcallgraph-info=su -DSTRAY_NO_ERRMSG -DSTRAY_WITH_POISSON=0 -DSTRAY_REAL_FLOAT \
	-Ilibstray/include \
	-Ifirmware_fdr/include -Ifirmware_fdr/target
ARM_LDFLAGS := $(ARM_ARCH) -nostartfiles -Wl,--gc-sections \
	-Wl,-T,firmware_fdr/target/mps2_an386.ld --specs=nano.specs

FW_FLIGHT_OBJ := $(FDRFW_SRC:%.c=$(FW_B)/obj/%.o)
FW_STRAY_OBJ := $(FDRFW_STRAY_SRC:%.c=$(FW_B)/obj/%.o)
FW_START_OBJ := $(FW_B)/obj/firmware_fdr/target/startup.o
FW_TABLE_C := $(FW_B)/flight_table.c
FW_CURVE := tests/vectors/fdrfw_curve.csv
FW_FOOTPRINT := $(FW_B)/fdrfw_footprint.elf
FW_VECTORS := $(FW_B)/fdrfw_vectors.elf
FW_DET_TABLE_C := $(FW_B)/det_table.c
FW_DET := $(FW_B)/fdrfw_detector.elf

# Everything on the target is single precision (libstray's core with
# STRAY_REAL_FLOAT) and built with -Wdouble-promotion to keep it so.
FW_EXTRA := -Wdouble-promotion

$(FW_B)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) $(FW_EXTRA) -c $< -o $@

# The flight table comes from the ground tool, as it would for flight.
$(FW_TABLE_C): $(FW_CURVE) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(STRAY_BIN) firmware-table --curve $(FW_CURVE) --out-c $@ \
		--name fdrfw_flight_table >/dev/null

$(FW_B)/obj/flight_table.o: $(FW_TABLE_C)
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) -Wdouble-promotion -c $< -o $@

# A detector table (tetra3, issue 28) for the emulated run of its grid.
$(FW_DET_TABLE_C): $(FW_CURVE) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(STRAY_BIN) firmware-table --curve $(FW_CURVE) --detector tetra3 \
		--out-c $@ --name fdrfw_det_table >/dev/null

$(FW_B)/obj/det_table.o: $(FW_DET_TABLE_C)
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) -Wdouble-promotion -c $< -o $@

$(FW_FOOTPRINT): $(FW_START_OBJ) $(FW_B)/obj/firmware_fdr/target/footprint_main.o \
		$(FW_B)/obj/flight_table.o $(FW_FLIGHT_OBJ) $(FW_STRAY_OBJ)
	$(ARM_CC) $(ARM_LDFLAGS) -Wl,-Map,$@.map -o $@ $^ -lm

$(FW_VECTORS): $(FW_START_OBJ) $(FW_B)/obj/firmware_fdr/target/semihost.o \
		$(FW_B)/obj/tests/firmware_fdr/target_vectors.o \
		$(FW_B)/obj/tests/firmware_fdr/vector_check.o \
		$(FW_B)/obj/flight_table.o $(FW_FLIGHT_OBJ) $(FW_STRAY_OBJ)
	$(ARM_CC) $(ARM_LDFLAGS) -o $@ $^ -lm

$(FW_DET): $(FW_START_OBJ) $(FW_B)/obj/firmware_fdr/target/semihost.o \
		$(FW_B)/obj/tests/firmware_fdr/target_detector.o \
		$(FW_B)/obj/det_table.o $(FW_FLIGHT_OBJ) $(FW_STRAY_OBJ)
	$(ARM_CC) $(ARM_LDFLAGS) -o $@ $^ -lm

$(FW_B)/obj/tests/firmware_fdr/%.o: FW_EXTRA := -Itests/firmware_fdr \
	-Ifirmware_fdr

.PHONY: firmware
firmware: $(FW_FOOTPRINT) $(FW_VECTORS) $(FW_DET)
	@firmware_fdr/target/footprint.sh $(FW_B) $(FW_FOOTPRINT) $(FW_VECTORS) \
		$(FW_DET)

# The emulated run and the footprint are tests: their drivers need the
# images built (explicit rules, so make never takes the images for
# intermediates of the pattern rule and skips them).
$(B)/tests/firmware_fdr/test_vectors: \
		$(B)/obj/tests/firmware_fdr/test_vectors.o $(FDRFW_TEST_DEPS) \
		$(FW_VECTORS) $(FW_DET)
	$(FDRFW_TEST_LINK)
$(B)/tests/firmware_fdr/test_footprint: \
		$(B)/obj/tests/firmware_fdr/test_footprint.o $(FDRFW_TEST_DEPS) \
		$(FW_FOOTPRINT)
	$(FDRFW_TEST_LINK)

# Header dependencies of the target objects (the top Makefile reads $(B)'s).
-include $(shell find $(FW_B)/obj -name '*.d' 2>/dev/null)

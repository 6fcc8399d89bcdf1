# straylight - one Makefile at the top; each folder adds its part in
# <folder>/module.mk.  Targets: all, test, demo, bench, deps, install, fuzz,
# nightly.
#
#   make            build library, `stray` and tests into build/
#   make test       deps, then the whole test suite, then again under
#                   ASan+UBSan (build/asan)
#   make demo       the main job on the built-in reference system
#   make install PREFIX=DIR
#   make nightly    the long cases make test leaves out (fuzzing 300 s
#                   per target)

PREFIX ?= /usr/local
B ?= build
SAN ?= 0
CC ?= cc
CLANG ?= clang
PYTHON ?= python3

MODULES := libstray tools libstray/reduce tests tracer frames diagnose review rig mission firmware_fdr mpi tests/flightcheck solib python

WARN := -Wall -Wextra -Werror
OPT ?= -O2 -g
ifeq ($(SAN),1)
OPT := -O1 -g -fno-omit-frame-pointer
SANFLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all
endif

# Host code: C99 plus POSIX; the freestanding core adds -ffreestanding.
# Position-independent, so the same objects make the static libraries and
# the shared ones (issue 32: Python loads them); no semantic
# interposition, so calls inside a library are still inlined as before.
CFLAGS_BASE := -std=c99 $(WARN) $(OPT) $(SANFLAGS) -MMD -MP -fPIC \
	-fno-semantic-interposition
CPPFLAGS_HOST := -D_POSIX_C_SOURCE=200809L -Ilibstray/include
LDLIBS_BASE := -lm

.PHONY: all test check demo demo-check bench deps install clean

# A library of the product (frames, mission): its archive from its
# objects, built by `make`, and installed with its public headers
# (DIR/include/DIR/*.h) by `make install`.
# $(eval $(call stray_library,DIR,ARCHIVE,OBJECTS))
define stray_library
$(2): $(3)
	@mkdir -p $$(dir $$@)
	rm -f $$@ && ar rcs $$@ $$^
all: $(2)
install-$(1): $(2)
	install -d $$(DESTDIR)$$(PREFIX)/lib $$(DESTDIR)$$(PREFIX)/include/$(1)
	install -m 644 $(2) $$(DESTDIR)$$(PREFIX)/lib/
	install -m 644 $(1)/include/$(1)/*.h $$(DESTDIR)$$(PREFIX)/include/$(1)/
install: install-$(1)
endef
# Keep intermediate objects (incremental builds, no "rm" noise).
.SECONDARY:
all:

include $(foreach m,$(MODULES),$(m)/module.mk)

# Generic rules: every object lands under $(B)/obj mirroring the source.
$(B)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) $(CPPFLAGS_HOST) $(EXTRA_CFLAGS) -c $< -o $@

$(B)/obj/%.o: %.S
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_HOST) $(EXTRA_CFLAGS) -c $< -o $@

deps:
	@scripts/install-deps.sh

# The README's test command.  Installs what is missing, builds the three
# trees at once (normal, ASan+UBSan, fuzz targets: one -j2 job server, so
# neither core waits on a serial link), replays every kept fuzz input
# and fuzzes each parser's target for FUZZ_CI_SECONDS (3 s, two at a
# time; the long search is `make nightly`), then one pool of TEST_JOBS jobs at a time
# (tests/run-tests.sh, the slowest first) runs every test binary, every
# one again under AddressSanitizer and UBSan but the TESTS_SLOW, and the
# small demo with its report checked: one pool, so no pass waits on its
# own last binary and the binaries that wait on daemons and mpirun share
# the cores with those that compute.  Three jobs on two cores: the
# binaries that wait (test_indi_sweep waits ~50 s on INDI's simulators
# for 3 CPU seconds; mpirun, daemons and sockets a few seconds each) then
# leave no core idle (issue 27); the build stays at BUILD_JOBS.
TEST_JOBS ?= 3
BUILD_JOBS ?= 2
export TEST_JOBS
test: deps
	@$(MAKE) --no-print-directory -j$(BUILD_JOBS) test-builds
	@$(MAKE) --no-print-directory fuzz-ci
	@$(MAKE) --no-print-directory check-scripts
	@$(MAKE) --no-print-directory check-scripts B=build/asan SAN=1
	@tests/run-tests.sh $(B) scripts/demo-check.sh scripts/python-check.sh \
		$$($(MAKE) -s --no-print-directory check-list) \
		$$($(MAKE) -s --no-print-directory check-list B=build/asan SAN=1)

# The long cases, for a machine with time (a nightly job): the fuzz
# targets FUZZ_NIGHTLY_SECONDS (300 s) each instead of make test's
# FUZZ_CI_SECONDS, every kept input replayed as in make test.  The long
# campaign with its corpus kept for fuzz-merge is still `make fuzz`.
.PHONY: nightly
nightly: deps
	@$(MAKE) --no-print-directory -j$(BUILD_JOBS) test-builds
	@$(MAKE) --no-print-directory fuzz-ci \
		FUZZ_CI_SECONDS=$(FUZZ_NIGHTLY_SECONDS)

.PHONY: test-builds test-build-normal test-build-asan check-build \
	check-scripts check-list
test-builds: test-build-normal test-build-asan fuzz-build
test-build-normal:
	+@$(MAKE) --no-print-directory check-build
# The Cortex-M4 images live in one folder for both trees (build/firmware,
# firmware_fdr/target/target.mk) and the normal tree makes them: the ASan
# tree neither remakes them nor their table (-o), or the two would write
# the same files at once.
FW_SHARED := build/firmware/flight_table.c build/firmware/fdrfw_vectors.elf \
	build/firmware/fdrfw_footprint.elf
test-build-asan:
	+@$(MAKE) --no-print-directory check-build B=build/asan SAN=1 \
		$(addprefix -o ,$(FW_SHARED))

# The README's first command, run small and read as a reader would
# (scripts/demo-check.sh).
demo-check: all
	@scripts/demo-check.sh $(B)

# TESTS_SLOW: tests too slow under the sanitizers, run in the normal pass only.
# The slow ones first: on a fresh tree (no test-times.txt) the pool then
# does not end on one of them alone.
CHECK_BINS = $(if $(filter 1,$(SAN)),,$(TESTS_SLOW)) $(TESTS)
check-build: all $(CHECK_BINS)
check-list:
	@echo $(CHECK_BINS)
check-scripts: check-build
	@scripts/check-core.sh $(STRAY_CORE_LIB)
	@scripts/check-layout.sh
	@scripts/check-equations.sh
	@scripts/check-docs.sh
ifneq ($(SAN),1)	# an instrumented library is not for installing
	@scripts/check-install.sh $(B)
endif
check: check-scripts
	@tests/run-tests.sh $(B) $(CHECK_BINS)

# deps first, then a fresh make for the build: on a bare machine the
# packages arrive with deps, after this Makefile was parsed, and `make -j`
# must not compile beside a running apt-get.
demo: deps
	@$(MAKE) --no-print-directory all
	@scripts/demo.sh $(B)

bench: all $(BENCHES)
	@scripts/bench.sh $(B) $(BENCHES)

clean:
	rm -rf build

-include $(shell find $(B)/obj -name '*.d' 2>/dev/null)

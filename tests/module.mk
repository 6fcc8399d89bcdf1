# tests: one cmocka binary per source file, tests/<module>/test_<file>.c.
# Other folders add their own binaries to TESTS in their module.mk.

CMOCKA_LIBS := -lcmocka
LIBSTRAY_TESTS := $(patsubst tests/libstray/%.c,$(B)/tests/libstray/%,\
	$(wildcard tests/libstray/test_*.c))
TOOLS_TESTS := $(patsubst tests/tools/%.c,$(B)/tests/tools/%,\
	$(wildcard tests/tools/test_*.c))
# Whole-method runs of many commands (a review, three user designs): each
# was run clean under ASan+UBSan when written, but take minutes there; the
# normal pass runs them (TESTS_SLOW, Makefile).
TOOLS_TESTS_SLOW := $(patsubst %,$(B)/tests/tools/%,test_review \
	test_user_design test_user_families)
TESTS += $(LIBSTRAY_TESTS) $(filter-out $(TOOLS_TESTS_SLOW),$(TOOLS_TESTS))
TESTS_SLOW += $(TOOLS_TESTS_SLOW)

$(B)/tests/libstray/%: $(B)/obj/tests/libstray/%.o $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(STRAY_LIB) $(CMOCKA_LIBS) $(STRAY_LDLIBS)

# CLI tests run build/bin/stray as a user would; they need it built first.
$(B)/tests/tools/%: $(B)/obj/tests/tools/%.o tests/tools/run_cli.h $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(CMOCKA_LIBS) -lcjson -lm

$(B)/obj/tests/tools/%.o: EXTRA_CFLAGS += -I/usr/include/cjson
# Flight frames come from the truth generator (tests/flightcheck).
$(B)/tests/tools/test_hardening2_fits: $(B)/tests/flightcheck/make_flight

# Parsers under libFuzzer (clang), run by scripts/fuzz.sh two at a time
# (FUZZ_JOBS), each on tests/fuzz/corpus/<target> and tests/fuzz/seeds/<target>:
#   make fuzz-ci     in `make test`: each target replays every file of its
#                    kept corpus and seeds (fails when one is not run:
#                    scripts/fuzz.sh), then mutates until FUZZ_CI_SECONDS
#                    (3 s from its start) are up; fails on any crash.  The
#                    kept corpus is what finds the known bugs fast (issue
#                    14's double free: 1 s from it, 7-22 s from the seeds
#                    alone); a longer search is the nightly one (issue 27:
#                    15 s each was 345 of make test's CPU seconds)
#   make nightly     the same for FUZZ_NIGHTLY_SECONDS (300 s) each
#   make fuzz        the long campaign: FUZZ_RUNS runs (10^7) per target,
#                    at most FUZZ_SECONDS (3600) each (0: no time limit;
#                    fuzz_scene_json, ~150 runs/s through assimp, stops at
#                    the hour); new inputs kept in build/fuzz/corpus-<target>
#   make fuzz-merge  minimise those into tests/fuzz/corpus/ (-merge=1)
# Both print executions and crashes per target; crash inputs land in
# build/fuzz/artifacts/.
FUZZ_JOBS ?= 2
FUZZ_CI_SECONDS ?= 3
FUZZ_NIGHTLY_SECONDS ?= 300
FUZZ_SECONDS ?= 3600
FUZZ_RUNS ?= 10000000
FUZZ_TARGETS := $(patsubst tests/fuzz/%.c,build/fuzz/%,\
	$(wildcard tests/fuzz/fuzz_*.c)) build/fuzz/fuzz_tracer_args
FUZZ_CFLAGS = -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
	$(CPPFLAGS_HOST) -I/usr/include/cjson -DSTRAY_DATA_DIR=\"libstray/data\"

# The library sources the targets share are compiled once into archives
# under build/fuzz/obj (each target used to compile all of libstray
# again: 14 copies, three minutes of CPU in `make test`); a target links
# only the members it needs.  -MMD: a header change rebuilds them.
FUZZ_OBJ := build/fuzz/obj
FUZZ_LIB_SRC := $(STRAY_CORE_SRC) $(STRAY_HOST_SRC) libstray/host/builtin_data.S
FUZZ_LIB_A := $(FUZZ_OBJ)/libstray_fuzz.a
FUZZ_SWEEP_A := $(FUZZ_OBJ)/libsweep_fuzz.a
FUZZ_TRACER_A := $(FUZZ_OBJ)/libtracer_fuzz.a
fuzz_objs = $(patsubst %,$(FUZZ_OBJ)/%.o,$(basename $(1)))
$(FUZZ_OBJ)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) $(FUZZ_OBJ_FLAGS) -MMD -MP -c $< -o $@
$(FUZZ_OBJ)/%.o: %.S
	@mkdir -p $(dir $@)
	$(CLANG) $(CPPFLAGS_HOST) -c $< -o $@
$(call fuzz_objs,$(wildcard tracer/*.c)): \
	FUZZ_OBJ_FLAGS := -D_DEFAULT_SOURCE -Itracer/include
$(FUZZ_OBJ)/libstray/host/builtin_data.o: $(STRAY_DATA)
$(FUZZ_LIB_A): $(call fuzz_objs,$(FUZZ_LIB_SRC))
$(FUZZ_SWEEP_A): $(call fuzz_objs,$(STRAY_SWEEP_SRC))
$(FUZZ_TRACER_A): $(call fuzz_objs,$(wildcard tracer/*.c))
$(FUZZ_LIB_A) $(FUZZ_SWEEP_A) $(FUZZ_TRACER_A):
	rm -f $@ && ar rcs $@ $^
-include $(shell find $(FUZZ_OBJ) -name '*.d' 2>/dev/null)

build/fuzz/%: tests/fuzz/%.c $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -o $@ $^ -lcsv -lcjson -lerfa -lm

# The sweep manifest alone (fuzz_reduce_input shares its time with FITS).
build/fuzz/fuzz_sweep_manifest: tests/fuzz/fuzz_sweep_manifest.c \
		$(FUZZ_SWEEP_A) $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -o $@ $^ $(STRAY_LDLIBS)

# The lab's log of `stray sweep import` (issue 26) alone.
build/fuzz/fuzz_import_log: tests/fuzz/fuzz_import_log.c \
		libstray/sweep/import_log.c libstray/sweep/csv_line.c \
		libstray/sweep/format.c $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -o $@ $^ $(STRAY_LDLIBS)

# A frame of other software as the import reads it: FITS (cfitsio) and
# TIFF (libtiff), both from memory.
build/fuzz/fuzz_import_frame: tests/fuzz/fuzz_import_frame.c \
		libstray/sweep/import_frame.c libstray/sweep/import_tiff.c \
		libstray/sweep/format.c $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -o $@ $^ $(STRAY_LDLIBS)

# The FITS readers of issue 31: a flight frame as flightcheck reads it,
# and a focal map (frames/focal_map_read.c, from a file on disk).
build/fuzz/fuzz_flight_frame: tests/fuzz/fuzz_flight_frame.c \
		$(FUZZ_SWEEP_A) $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -o $@ $^ $(STRAY_LDLIBS)
build/fuzz/fuzz_focal_map: tests/fuzz/fuzz_focal_map.c \
		frames/focal_map_read.c $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -Iframes/include -Itracer/include -o $@ $^ \
		$(STRAY_LDLIBS)
# A library call's options object (tools/api_args.c, issue 32) alone.
build/fuzz/fuzz_api_options: tests/fuzz/fuzz_api_options.c tools/api_args.c
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -Itools -Itools/include -o $@ $^ -lcjson -lm
# The heads file of `stray availability` (issue 31): its parser alone.
build/fuzz/fuzz_heads: tests/fuzz/fuzz_heads.c mission/avail_heads.c $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -Imission/include -Imission -o $@ $^ \
		$(STRAY_LDLIBS)

# The project file of `stray review` (issue 25) and the plan made from it.
build/fuzz/fuzz_review_project: tests/fuzz/fuzz_review_project.c \
		review/project.c review/project_keys.c review/mission.c \
		review/plan.c $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -D_DEFAULT_SOURCE -Ireview/include -o $@ $^ \
		$(STRAY_LDLIBS)

# Scene files: the JSON, then the OBJ/STL meshes it names through assimp.
build/fuzz/fuzz_scene_json: tests/fuzz/fuzz_scene_json.c $(FUZZ_TRACER_A) \
		$(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -D_DEFAULT_SOURCE -Itracer/include -o $@ $^ \
		$(TRACER_LDLIBS) -lstdc++ $(STRAY_LDLIBS)

# One mesh file: the byte count pre-scan, then assimp (tracer/mesh_prescan.c).
build/fuzz/fuzz_mesh_file: tests/fuzz/fuzz_mesh_file.c $(FUZZ_TRACER_A) \
		$(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -D_DEFAULT_SOURCE -Itracer/include -o $@ $^ \
		$(TRACER_LDLIBS) -lstdc++ $(STRAY_LDLIBS)

# The pre-scan alone, without assimp (fast).
build/fuzz/fuzz_mesh_prescan: tests/fuzz/fuzz_mesh_prescan.c \
		tracer/mesh_prescan.c $(FUZZ_LIB_A)
	@mkdir -p $(dir $@)
	$(CLANG) $(FUZZ_CFLAGS) -D_DEFAULT_SOURCE -Itracer/include -o $@ $^ \
		$(STRAY_LDLIBS)

.PHONY: fuzz fuzz-build fuzz-ci fuzz-smoke fuzz-merge
fuzz-build: $(FUZZ_TARGETS)
fuzz-ci:
	@$(MAKE) --no-print-directory -j$(FUZZ_JOBS) $(FUZZ_TARGETS)
	@echo "== fuzz: $(words $(FUZZ_TARGETS)) targets, every kept input replayed, $(FUZZ_CI_SECONDS) s each, $(FUZZ_JOBS) at a time"
	@scripts/fuzz.sh ci $(FUZZ_CI_SECONDS) 0 $(FUZZ_JOBS) $(FUZZ_TARGETS)
fuzz-smoke: fuzz-ci

fuzz:
	@$(MAKE) --no-print-directory -j$(FUZZ_JOBS) $(FUZZ_TARGETS)
	@echo "== fuzz: $(words $(FUZZ_TARGETS)) targets, $(FUZZ_RUNS) runs each, at most $(FUZZ_SECONDS) s (0: no limit)"
	@scripts/fuzz.sh long $(FUZZ_SECONDS) $(FUZZ_RUNS) $(FUZZ_JOBS) $(FUZZ_TARGETS)

fuzz-merge: $(FUZZ_TARGETS)
	@scripts/fuzz.sh merge $(FUZZ_TARGETS)

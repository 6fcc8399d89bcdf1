# tests: one cmocka binary per source file, tests/<module>/test_<file>.c.
# Other folders add their own binaries to TESTS in their module.mk.

CMOCKA_LIBS := -lcmocka
LIBSTRAY_TESTS := $(patsubst tests/libstray/%.c,$(B)/tests/libstray/%,\
	$(wildcard tests/libstray/test_*.c))
TOOLS_TESTS := $(patsubst tests/tools/%.c,$(B)/tests/tools/%,\
	$(wildcard tests/tools/test_*.c))
TESTS += $(LIBSTRAY_TESTS) $(TOOLS_TESTS)

$(B)/tests/libstray/%: $(B)/obj/tests/libstray/%.o $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(STRAY_LIB) $(CMOCKA_LIBS) $(STRAY_LDLIBS)

# CLI tests run build/bin/stray as a user would; they need it built first.
$(B)/tests/tools/%: $(B)/obj/tests/tools/%.o tests/tools/run_cli.h $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(CMOCKA_LIBS) -lcjson -lm

$(B)/obj/tests/tools/%.o: EXTRA_CFLAGS += -I/usr/include/cjson

# Parsers under libFuzzer (clang): `make fuzz` runs each for FUZZ_SECONDS;
# `make test` replays a fixed number of runs with a fixed seed.
FUZZ_SECONDS ?= 60
FUZZ_RUNS ?= 20000
FUZZ_TARGETS := $(patsubst tests/fuzz/%.c,build/fuzz/%,$(wildcard tests/fuzz/fuzz_*.c))
FUZZ_LIB_SRC := $(STRAY_CORE_SRC) $(STRAY_HOST_SRC) libstray/host/builtin_data.S

build/fuzz/%: tests/fuzz/%.c $(FUZZ_LIB_SRC)
	@mkdir -p $(dir $@)
	$(CLANG) -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
		$(CPPFLAGS_HOST) -I/usr/include/cjson -DSTRAY_DATA_DIR=\"libstray/data\" \
		-o $@ $^ -lcsv -lcjson -lm

fuzz: $(FUZZ_TARGETS)
	@for f in $(FUZZ_TARGETS); do \
		n=$$(basename $$f); mkdir -p build/fuzz/corpus-$$n; \
		echo "== $$n ($(FUZZ_SECONDS) s)"; \
		$$f -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 \
			build/fuzz/corpus-$$n tests/fuzz/seeds/$${n#fuzz_} 2>&1 \
			| grep -E 'stat::number_of_executed_units|ERROR|SUMMARY' ; \
	done

# New inputs go to a scratch corpus (the first folder), never the seeds.
fuzz-smoke: $(FUZZ_TARGETS)
	@for f in $(FUZZ_TARGETS); do \
		n=$$(basename $$f); echo "== $$n ($(FUZZ_RUNS) runs, seed 1)"; \
		rm -rf build/fuzz/smoke-$$n; mkdir -p build/fuzz/smoke-$$n; \
		$$f -runs=$(FUZZ_RUNS) -seed=1 build/fuzz/smoke-$$n tests/fuzz/seeds/$${n#fuzz_} \
			>build/fuzz/$$n.log 2>&1 || { cat build/fuzz/$$n.log; exit 1; }; \
		grep -E '^#[0-9]+.*DONE' build/fuzz/$$n.log | tail -n 1; \
	done

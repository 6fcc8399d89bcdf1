# libstray: the freestanding core (linked by firmware_fdr too) and the
# hosted layer (CSV/JSON I/O, built-in spectra, the sweep-folder store:
# cfitsio frames, libcsv manifest, OpenSSL SHA-256, in libstray/sweep;
# libtiff for the TIFF frames `stray sweep import` takes).

STRAY_CORE_SRC := $(wildcard libstray/core/*.c)
STRAY_HOST_SRC := $(wildcard libstray/host/*.c) \
	$(wildcard libstray/frames/*.c)
STRAY_CORE_OBJ := $(STRAY_CORE_SRC:%.c=$(B)/obj/%.o)
STRAY_HOST_OBJ := $(STRAY_HOST_SRC:%.c=$(B)/obj/%.o) \
	$(B)/obj/libstray/host/builtin_data.o
STRAY_SWEEP_SRC := $(wildcard libstray/sweep/*.c)
STRAY_SWEEP_OBJ := $(STRAY_SWEEP_SRC:%.c=$(B)/obj/%.o)
STRAY_LIB := $(B)/lib/libstray.a
STRAY_CORE_LIB := $(B)/lib/libstray_core.a
STRAY_LDLIBS := -lcfitsio -ltiff -lcrypto -lcsv -lcjson -lerfa -lm
STRAY_DATA := $(wildcard libstray/data/*.csv)

# The core must build freestanding: no hosted headers, no builtins assumed.
$(STRAY_CORE_OBJ): EXTRA_CFLAGS += -ffreestanding
$(STRAY_HOST_OBJ): EXTRA_CFLAGS += -I/usr/include/cjson
# The built-in spectra are the shipped CSV files, assembled in verbatim.
$(B)/obj/libstray/host/builtin_data.o: EXTRA_CFLAGS += -DSTRAY_DATA_DIR=\"libstray/data\"
$(B)/obj/libstray/host/builtin_data.o: $(STRAY_DATA)

# The build's git revision in every output's provenance: rewritten only
# when it changes, so provenance.o is rebuilt then and only then.
STRAY_GIT_REV := $(shell git describe --always --dirty 2>/dev/null || echo unknown)
$(B)/gen/git-rev: FORCE
	@mkdir -p $(dir $@)
	@echo '$(STRAY_GIT_REV)' | cmp -s - $@ || echo '$(STRAY_GIT_REV)' > $@
$(B)/obj/libstray/host/provenance.o: $(B)/gen/git-rev
$(B)/obj/libstray/host/provenance.o: EXTRA_CFLAGS += -DSTRAY_GIT_REV=\"$(STRAY_GIT_REV)\"
.PHONY: FORCE
FORCE:

$(STRAY_CORE_LIB): $(STRAY_CORE_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

$(STRAY_LIB): $(STRAY_CORE_OBJ) $(STRAY_HOST_OBJ) $(STRAY_SWEEP_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

all: $(STRAY_LIB) $(STRAY_CORE_LIB)

# The pkg-config file names the prefix it is installed under.
install-libstray: $(STRAY_LIB) $(STRAY_CORE_LIB) libstray/stray.pc.in
	install -d $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include/stray
	install -m 644 $(STRAY_LIB) $(STRAY_CORE_LIB) $(DESTDIR)$(PREFIX)/lib/
	install -m 644 libstray/include/stray/*.h $(DESTDIR)$(PREFIX)/include/stray/
	sed -e 's|@PREFIX@|$(PREFIX)|' libstray/stray.pc.in \
		> $(DESTDIR)$(PREFIX)/lib/pkgconfig/stray.pc
	# the real star catalogue (--catalogue) and its provenance
	install -d $(DESTDIR)$(PREFIX)/share/straylight
	install -m 644 libstray/data/hip2_hp6.5.dat libstray/data/PROVENANCE.md \
		$(DESTDIR)$(PREFIX)/share/straylight/
install: install-libstray

# Benchmarks of the physics core (make bench).
BENCHES += $(B)/bench/bench_fdr
$(B)/bench/bench_fdr: $(B)/obj/bench/bench_fdr.o $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(STRAY_LIB) $(STRAY_LDLIBS)

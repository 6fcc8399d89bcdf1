# solib: the shared libraries (issue 32), built from the same objects as
# the static ones (every host object is -fPIC, Makefile) and installed
# beside them by `make install` with a pkg-config file each:
#   libstray     the physics, file formats, sweep store and reduction
#   libtracer    the Monte Carlo tracer (Embree)
#   libdiagnose  the model-vs-measurement diagnosis
#   libreview    the design review
#   libframes    rendered frames, star detectors, focal maps (OpenCV)
#   libmission   availability, flightcheck, orbits, flight tables
#   libstraycmd  the `stray` commands as flat C calls (tools/api.c, public
#                header tools/include/tools/api.h): what Python binds to
# Each is libX.so.MAJOR.MINOR.0 with soname libX.so.MAJOR and the
# libX.so link; they find each other beside themselves ($ORIGIN), so a
# folder of them (a prefix's lib/, the Python wheel) is self-contained
# apart from the Debian packages of scripts/install-deps.sh.  Listed
# last in MODULES: it takes every other module's objects.  Not built
# under the sanitizers (an instrumented library is not for loading into
# Python).  The firmware (firmware_fdr/target) is untouched.

STRAY_SOVERSION := $(shell sed -n 's/^\#define STRAY_VERSION "\(.*\)"/\1/p' \
	libstray/include/stray/provenance.h)
STRAY_SOMAJOR := $(firstword $(subst ., ,$(STRAY_SOVERSION)))
SO_MINOR := $(word 2,$(subst ., ,$(STRAY_SOVERSION)))
SO_FULL := $(STRAY_SOMAJOR).$(SO_MINOR).0
SO_LDFLAGS := -shared -Wl,--no-undefined -Wl,-rpath,'$$ORIGIN' -L$(B)/lib

# $(call so_link,name,objects,libs): libname.so.FULL and its two links.
define so_link
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) $(SO_LDFLAGS) -Wl,-soname,lib$(1).so.$(STRAY_SOMAJOR) \
		-o $(B)/lib/lib$(1).so.$(SO_FULL) $(2) $(3)
	ln -sf lib$(1).so.$(SO_FULL) $(B)/lib/lib$(1).so.$(STRAY_SOMAJOR)
	ln -sf lib$(1).so.$(STRAY_SOMAJOR) $(B)/lib/lib$(1).so
endef

SO_STRAY := $(B)/lib/libstray.so
SO_TRACER := $(B)/lib/libtracer.so
SO_DIAG := $(B)/lib/libdiagnose.so
SO_REVIEW := $(B)/lib/libreview.so
SO_FRAMES := $(B)/lib/libframes.so
SO_MISSION := $(B)/lib/libmission.so
SO_CMD := $(B)/lib/libstraycmd.so
SO_LIBS := $(SO_STRAY) $(SO_TRACER) $(SO_DIAG) $(SO_REVIEW) $(SO_FRAMES) \
	$(SO_MISSION) $(SO_CMD)

# The commands' objects: every tools object but the program's main.
SO_CMD_OBJ = $(filter-out $(B)/obj/tools/stray.o,$(TOOLS_OBJ))

$(SO_STRAY): $(STRAY_CORE_OBJ) $(STRAY_HOST_OBJ) $(STRAY_SWEEP_OBJ) \
		$(REDUCE_OBJ)
	$(call so_link,stray,$^,$(STRAY_LDLIBS) -lpthread)
$(SO_TRACER): $(TRACER_OBJ) $(SO_STRAY)
	$(call so_link,tracer,$(TRACER_OBJ),-lstray $(TRACER_LDLIBS) -lm)
$(SO_DIAG): $(DIAG_OBJ) $(SO_TRACER)
	$(call so_link,diagnose,$(DIAG_OBJ),-ltracer -lstray -lcjson -lm)
$(SO_REVIEW): $(REVIEW_OBJ) $(SO_STRAY)
	$(call so_link,review,$(REVIEW_OBJ),-lstray -lplplot -lcjson -lm)
$(SO_FRAMES): $(FRAMES_OBJ) $(SO_TRACER)
	$(call so_link,frames,$(FRAMES_OBJ),-ltracer -lstray $(FRAMES_LDLIBS) \
		-lcjson $(STRAY_LDLIBS))
# the flight module's two archives go in whole-objects-needed, as in stray
$(SO_MISSION): $(MISSION_OBJ) $(SO_FRAMES) $(FDRFW_GROUND_LIB) $(FDRFW_LIB)
	$(call so_link,mission,$(MISSION_OBJ),-lframes -ltracer -lstray \
		$(FDRFW_GROUND_LIB) $(FDRFW_LIB) -lplplot -lcjson -fopenmp \
		$(STRAY_LDLIBS) -lpthread)
$(SO_CMD): $(SO_CMD_OBJ) $(SO_DIAG) $(SO_REVIEW) $(SO_MISSION) \
		$(FDRFW_GROUND_LIB) $(FDRFW_LIB)
	$(call so_link,straycmd,$(SO_CMD_OBJ),-lmission -lframes -ldiagnose \
		-lreview -ltracer -lstray $(FDRFW_GROUND_LIB) $(FDRFW_LIB) -lplplot -lcjson \
		$(OPENCV_LDLIBS) -lstdc++ -fopenmp $(STRAY_LDLIBS) -lpthread)

# What python/setup.py asks for (pip install ./python).
.PHONY: shared-libs
shared-libs: $(SO_LIBS)

ifneq ($(SAN),1)
all: $(SO_LIBS)

# pkg-config files of the shared libraries (stray.pc is libstray's own).
SO_PC := tracer diagnose review frames mission straycmd
install-solib: $(SO_LIBS) $(patsubst %,solib/%.pc.in,$(SO_PC))
	install -d $(DESTDIR)$(PREFIX)/lib/pkgconfig \
		$(DESTDIR)$(PREFIX)/include/tracer \
		$(DESTDIR)$(PREFIX)/include/diagnose \
		$(DESTDIR)$(PREFIX)/include/straycmd
	for l in stray tracer diagnose review frames mission straycmd; do \
		install -m 755 $(B)/lib/lib$$l.so.$(SO_FULL) $(DESTDIR)$(PREFIX)/lib/ && \
		ln -sf lib$$l.so.$(SO_FULL) $(DESTDIR)$(PREFIX)/lib/lib$$l.so.$(STRAY_SOMAJOR) && \
		ln -sf lib$$l.so.$(STRAY_SOMAJOR) $(DESTDIR)$(PREFIX)/lib/lib$$l.so || exit 1; \
	done
	install -m 644 tracer/include/tracer/*.h $(DESTDIR)$(PREFIX)/include/tracer/
	install -m 644 diagnose/include/diagnose/*.h $(DESTDIR)$(PREFIX)/include/diagnose/
	install -m 644 tools/include/tools/api.h $(DESTDIR)$(PREFIX)/include/straycmd/
	install -d $(DESTDIR)$(PREFIX)/include/review
	install -m 644 review/include/review/*.h $(DESTDIR)$(PREFIX)/include/review/
	for p in $(SO_PC); do \
		sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(STRAY_SOVERSION)|' \
			solib/$$p.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/$$p.pc || exit 1; \
	done
install: install-solib
endif

# mission: what happens in orbit, as a library (libmission.a): flying the
# flight module along an OEM/AEM for several heads (availability), the
# heads file, the demo mission's orbit and attitude generation, the
# flight-table reader, and the flight-frame analysis (flightcheck).
# Public headers in mission/include/mission/; `stray availability`,
# `stray orbit` and `stray flightcheck` (tools/) parse, print and plot.
# Listed in MODULES after tools and before firmware_fdr: it puts itself
# ahead of libfdrfw and libstray in the `stray` link.

MISSION_SRC := $(wildcard mission/*.c)
MISSION_OBJ := $(MISSION_SRC:%.c=$(B)/obj/%.o)
MISSION_LIB := $(B)/lib/libmission.a
MISSION_CFLAGS := -Imission/include -Ifirmware_fdr/include
MISSION_LDLIBS := -fopenmp

$(MISSION_OBJ): EXTRA_CFLAGS += $(MISSION_CFLAGS) -Imission \
	-I/usr/include/cjson
# The heads fly in parallel, and flight frames are analysed in parallel
# (OpenMP).
$(B)/obj/mission/avail_mission.o $(B)/obj/mission/flightcheck_run.o: \
	EXTRA_CFLAGS += -fopenmp

$(eval $(call stray_library,mission,$(MISSION_LIB),$(MISSION_OBJ)))

$(TOOLS_OBJ): EXTRA_CFLAGS += -Imission/include
$(STRAY_BIN): $(MISSION_LIB)
TOOLS_LDLIBS := $(MISSION_LIB) $(TOOLS_LDLIBS) $(MISSION_LDLIBS)

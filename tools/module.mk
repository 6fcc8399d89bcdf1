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

# `stray frames`: the OpenCV star detectors, its tests and bench.
include tools/frames.mk

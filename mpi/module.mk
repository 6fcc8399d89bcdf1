# mpi: `stray-mpi`, the traces of `stray trace`, `stray sweep` and
# `stray diagnose` spread over MPI ranks (issue 9; Open MPI from Debian).
# A binary of its own (see mpi/stray_mpi.c for why): the three commands
# through their public entry points (tools/entry.h), given the farm as
# their runner (tracer/runner.h), in place of stray.c's main.  It links
# the tools objects those commands need and the diagnose library.

# Resolved when a recipe runs (=, not :=): on a bare machine pkg-config
# and Open MPI arrive with `make deps`, after the Makefile is parsed.
MPI_CFLAGS = $(shell pkg-config --cflags ompi-c 2>/dev/null)
MPI_LDLIBS = $(shell pkg-config --libs ompi-c 2>/dev/null)
STRAY_MPI_BIN := $(B)/bin/stray-mpi
MPI_PIECE_OBJ := $(B)/obj/mpi/piece.o
MPI_OBJ := $(patsubst %.c,$(B)/obj/%.o,$(wildcard mpi/*.c))
MPI_TOOLS_OBJ := $(patsubst %,$(B)/obj/tools/%.o,cli cli_capture cli_outputs cmd_trace cmd_sweep \
	design_report fdr_options plot trace_run trace_focal) $(DIAG_TOOLS_OBJ)

$(MPI_OBJ): EXTRA_CFLAGS += -Impi -Itools/include -Itracer/include \
	-I/usr/include/cjson $(MPI_CFLAGS) -D_DEFAULT_SOURCE

$(STRAY_MPI_BIN): $(MPI_OBJ) $(MPI_TOOLS_OBJ) $(FRAMES_LIB) $(DIAG_LIB) \
		$(TRACER_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $(MPI_OBJ) $(MPI_TOOLS_OBJ) $(FRAMES_LIB) \
		$(DIAG_LIB) $(TRACER_LIB) $(STRAY_LIB) $(TRACER_LDLIBS) -lplplot \
		-lcjson $(FRAMES_LDLIBS) $(STRAY_LDLIBS) $(MPI_LDLIBS) -lpthread

all: $(STRAY_MPI_BIN)

install-mpi: $(STRAY_MPI_BIN)
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 755 $(STRAY_MPI_BIN) $(DESTDIR)$(PREFIX)/bin/
install: install-mpi

# test_pieces: pieces in any order assemble to tracer_trace's bits (no
# MPI, both passes).  test_mpi_*: mpirun on localhost, normal pass only.
$(B)/obj/tests/mpi/%.o: EXTRA_CFLAGS += -Impi -Itracer/include \
	-Itests/tracer -I/usr/include/cjson -D_DEFAULT_SOURCE
$(B)/tests/mpi/test_pieces: $(B)/obj/tests/mpi/test_pieces.o \
		$(MPI_PIECE_OBJ) $(TRACER_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $^ $(CMOCKA_LIBS) $(TRACER_LDLIBS) \
		$(STRAY_LDLIBS)
TESTS += $(B)/tests/mpi/test_pieces

# test_farm_set: the one queue of pieces across a sweep's traces (no MPI).
$(B)/tests/mpi/test_farm_set: $(B)/obj/tests/mpi/test_farm_set.o \
		$(B)/obj/mpi/farm_set.o $(B)/obj/mpi/farm_job.o \
		$(MPI_PIECE_OBJ) $(TRACER_LIB) $(STRAY_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $^ $(CMOCKA_LIBS) $(TRACER_LDLIBS) \
		$(STRAY_LDLIBS) -lpthread
TESTS += $(B)/tests/mpi/test_farm_set

MPI_TESTS := $(B)/tests/mpi/test_mpi_trace $(B)/tests/mpi/test_mpi_faults \
	$(B)/tests/mpi/test_mpi_diagnose
$(MPI_TESTS): $(B)/tests/mpi/%: $(B)/obj/tests/mpi/%.o $(STRAY_MPI_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(CMOCKA_LIBS)
TESTS_SLOW += $(MPI_TESTS)

# make bench: strong scaling 1 -> 2 ranks, efficiency, bytes per piece.
BENCHES += $(B)/bench/bench_mpi
$(B)/bench/bench_mpi: bench/bench_mpi.sh $(STRAY_MPI_BIN) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	cp $< $@ && chmod +x $@

# test_sweep: `stray sweep` without MPI (grid, errors, resume); both passes.
$(B)/obj/tests/mpi/test_sweep.o: EXTRA_CFLAGS += -Itracer/include
$(B)/tests/mpi/test_sweep: $(B)/obj/tests/mpi/test_sweep.o \
		$(TRACER_LIB) $(STRAY_LIB) $(STRAY_BIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(TRACER_LIB) $(STRAY_LIB) \
		$(CMOCKA_LIBS) $(TRACER_LDLIBS) $(STRAY_LDLIBS)
TESTS += $(B)/tests/mpi/test_sweep

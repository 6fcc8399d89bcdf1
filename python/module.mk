# python: the `straylight` package (python/straylight, issue 32) on the
# shared libraries (solib/module.mk), its pytest suite against the `stray`
# of the same build, and the example notebook run by nbclient.
#
#   make python-check   in `make check` (normal pass): a venv of pinned
#                       packages (python/requirements-test.txt, PyPI),
#                       cached in $(B)/py-venv and remade only when the
#                       pins change; the package installed into it as a
#                       user would (pip install ./python); pytest; then
#                       examples/straylight.ipynb executed clean.

PY_VENV := $(B)/py-venv
PY_VENV_STAMP := $(PY_VENV)/.pins
PY_SRC := $(wildcard python/straylight/*.py) python/setup.py \
	python/pyproject.toml

$(PY_VENV_STAMP): python/requirements-test.txt
	@rm -rf $(PY_VENV)
	$(PYTHON) -m venv $(PY_VENV)
	$(PY_VENV)/bin/python -m pip install -q -r $<
	@cp $< $@

# pip builds in python/ (in-tree): the libraries of this build ($(B)).
$(PY_VENV)/.installed: $(PY_VENV_STAMP) $(PY_SRC) $(SO_LIBS)
	STRAYLIGHT_BUILD=$(abspath $(B)) $(PY_VENV)/bin/python -m pip install \
		-q --force-reinstall --no-deps --no-build-isolation ./python
	@touch $@

.PHONY: python-check
python-check: $(PY_VENV)/.installed $(STRAY_BIN) $(RIG_BIN)
	@echo "== python: pytest (straylight against $(STRAY_BIN))"
	@cd $(B) && STRAY_BIN=$(abspath $(STRAY_BIN)) \
		$(abspath $(PY_VENV))/bin/python -m pytest -q -p no:cacheprovider \
		$(abspath python/tests)
	@echo "== python: examples/straylight.ipynb (nbclient)"
	@rm -rf $(B)/notebook && mkdir -p $(B)/notebook
	@$(PY_VENV)/bin/python python/tools/run_notebook.py \
		examples/straylight.ipynb $(B)/notebook 2>$(B)/notebook/stderr.log \
		|| { tail -n 30 $(B)/notebook/stderr.log; exit 1; }

ifneq ($(SAN),1)
check: python-check
endif

# The flat C calls themselves (tests/api): linked from the objects `stray`
# is, so both passes run it (ASan+UBSan too).
API_TEST := $(B)/tests/api/test_api
TESTS += $(API_TEST)
$(B)/obj/tests/api/%.o: EXTRA_CFLAGS += -Itools/include -D_DEFAULT_SOURCE
$(API_TEST): $(B)/obj/tests/api/test_api.o $(filter-out \
		$(B)/obj/tools/stray.o,$(TOOLS_OBJ)) $(STRAY_LIB) $(TRACER_LIB) \
		$(DIAG_LIB) $(REVIEW_LIB) $(FDRFW_GROUND_LIB) $(FDRFW_LIB) \
		$(STRAY_CORE_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_BASE) -o $@ $< $(filter-out $(B)/obj/tools/stray.o,\
		$(TOOLS_OBJ)) $(TOOLS_LDLIBS) $(STRAY_LDLIBS) $(CMOCKA_LIBS) \
		-lpthread

# brdffit -- library (libbrdffit.a, libbrdffit.so), program (brdffit), tests, benchmark.
#
#   make             build/libbrdffit.a build/libbrdffit.so build/brdffit
#   make demo        build, then run the batch on the embedded synthetic material
#                    (report in build/demo; prints the path of its index.html)
#   make test        build and run the Check suite and the Python package's tests
#                    (python/tests, pytest; uses ../shared when present)
#   make sanitize    the suite under AddressSanitizer + UndefinedBehaviorSanitizer
#   make bench       the benchmark (bench/), figures as in README.md
#   make bench-python  only its Python part (eval from NumPy against C)
#   make install PREFIX=/usr/local   header, libraries, brdffit.pc, program, and
#                    the Python package (python/brdffit) beside the library
#   make clean

PREFIX   ?= /usr/local
BUILD    ?= build
CC       ?= cc
OPT      ?= -O2
SONAME    = libbrdffit.so.0
VERSION   = 0.1.0

# On a fresh machine the first `make` installs the Debian packages it needs
# (.ci/install-deps: a no-op when they are there).
DEPS_OK := $(shell sh .ci/install-deps >&2 && echo ok)
ifneq ($(DEPS_OK),ok)
$(error build dependencies missing: see the message above)
endif

PKGS       = cminpack
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null || echo -I/usr/include/cminpack-1)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lcminpack)
CHECK_CFLAGS := $(shell pkg-config --cflags check 2>/dev/null)
CHECK_LIBS   := $(shell pkg-config --libs check 2>/dev/null || echo -lcheck -lsubunit -lrt -lpthread -lm)

# Include paths: the library sees its own internals and the kernel headers;
# the program sees the public header and its own; the tests, which reach
# into both on purpose, see all; the benchmark sees the library's.
CPPFLAGS += -Iinclude -DCL_TARGET_OPENCL_VERSION=120 -DCL_USE_DEPRECATED_OPENCL_1_2_APIS
LIB_INC   = -Isrc/lib -Ikernels $(PKG_CFLAGS)
CLI_INC   = -Isrc/cli
TEST_INC  = $(LIB_INC) $(CLI_INC) -Itests
# -MMD -MP: each object's header dependencies, written beside it (.d)
CFLAGS   += -std=c11 $(OPT) -g -Wall -Wextra -fPIC -MMD -MP $(SAN)
LDLIBS   += $(PKG_LIBS) -lOpenCL -lm
LDFLAGS  += $(SAN)

LIB_SRC  = $(wildcard src/lib/*.c)
LIB_OBJ  = $(LIB_SRC:src/lib/%.c=$(BUILD)/lib/%.o) $(BUILD)/lib/kernel_source.o
# The kernel sources in the order they are concatenated for
# clCreateProgramWithSource (each after what it uses).  The one place that
# order is written.
KERNEL_SOURCES = kernels/bf_common.h kernels/bf_models.h kernels/bf_he.h kernels/bf_lobe.h \
                 kernels/bf_layout.h kernels/bf_pass.h kernels/bf_pass.cl
CLI_SRC  = $(wildcard src/cli/*.c)
# The program's files but its main: the tests link them to test svg.c etc.
CLI_SUPPORT_OBJ = $(filter-out $(BUILD)/cli/brdffit.o,$(CLI_SRC:src/cli/%.c=$(BUILD)/cli/%.o))
TEST_SRC = $(wildcard tests/*.c)
BENCH_SRC = $(wildcard bench/*.c)

all: $(BUILD)/libbrdffit.a $(BUILD)/libbrdffit.so $(BUILD)/brdffit

$(BUILD)/lib $(BUILD)/cli $(BUILD)/tests $(BUILD)/bench:
	mkdir -p $@

# The kernel sources, embedded at build time as C strings, in KERNEL_SOURCES order.
$(BUILD)/lib/kernel_source.c: $(KERNEL_SOURCES) | $(BUILD)/lib
	{ echo '/* generated from kernels/ by the Makefile: do not edit */'; \
	  echo '#include <stddef.h>'; \
	  echo 'const char *const bf_kernel_sources[] = {'; \
	  for f in $(KERNEL_SOURCES); do \
	    echo "/* $$f */"; \
	    sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/^/"/' -e 's/$$/\\n"/' $$f; \
	    echo ','; \
	  done; \
	  echo '};'; \
	  echo 'const size_t bf_kernel_source_count = sizeof bf_kernel_sources / sizeof bf_kernel_sources[0];'; \
	} > $@.tmp && mv $@.tmp $@

$(BUILD)/lib/%.o: src/lib/%.c | $(BUILD)/lib
	$(CC) $(CPPFLAGS) $(LIB_INC) $(CFLAGS) -c -o $@ $<

$(BUILD)/lib/kernel_source.o: $(BUILD)/lib/kernel_source.c
	$(CC) $(CPPFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/libbrdffit.a: $(LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/libbrdffit.so: $(LIB_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) $(LDFLAGS) -o $(BUILD)/$(SONAME) $^ $(LDLIBS)
	ln -sf $(SONAME) $@

$(BUILD)/cli/%.o: src/cli/%.c | $(BUILD)/cli
	$(CC) $(CPPFLAGS) $(CLI_INC) $(CFLAGS) -c -o $@ $<

$(BUILD)/brdffit: $(CLI_SRC:src/cli/%.c=$(BUILD)/cli/%.o) $(BUILD)/libbrdffit.a
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/tests/%.o: tests/%.c | $(BUILD)/tests
	$(CC) $(CPPFLAGS) $(TEST_INC) $(CHECK_CFLAGS) $(CFLAGS) -c -o $@ $<

# expat: the tests' independent XML parser
$(BUILD)/test_brdffit: $(TEST_SRC:tests/%.c=$(BUILD)/tests/%.o) $(CLI_SUPPORT_OBJ) $(BUILD)/libbrdffit.a
	$(CC) $(LDFLAGS) -o $@ $^ $(CHECK_LIBS) -lexpat $(LDLIBS)

# The benchmark reads its tables with the tests' helpers (tests/testutil.c).
$(BUILD)/bench/%.o: bench/%.c | $(BUILD)/bench
	$(CC) $(CPPFLAGS) $(LIB_INC) -Itests $(CFLAGS) -c -o $@ $<

$(BUILD)/bench_brdffit: $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%.o) $(BUILD)/tests/testutil.o $(BUILD)/libbrdffit.a
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

# The environment every run gets: PoCL needs a writable cache directory.
RUN_ENV = POCL_CACHE_DIR="$${POCL_CACHE_DIR:-$(CURDIR)/$(BUILD)/pocl-cache}"

demo: all
	@mkdir -p $(BUILD)/pocl-cache
	$(RUN_ENV) ./$(BUILD)/brdffit batch --demo --out $(BUILD)/demo

test: $(BUILD)/test_brdffit $(BUILD)/brdffit $(BUILD)/libbrdffit.so
	@mkdir -p $(BUILD)/pocl-cache
	$(RUN_ENV) BRDFFIT_CLI=./$(BUILD)/brdffit ./$(BUILD)/test_brdffit
	$(RUN_ENV) BRDFFIT_CLI=$(CURDIR)/$(BUILD)/brdffit BRDFFIT_LIBRARY=$(CURDIR)/$(BUILD)/$(SONAME) \
	    sh python/tests/run -q

# The same suite built with ASan + UBSan in its own build directory.  LLVM
# (inside PoCL) keeps allocations until exit: tests/lsan.supp names them.
sanitize:
	$(MAKE) BUILD=build-san OPT=-O1 SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
	    build-san/test_brdffit build-san/brdffit
	@mkdir -p build-san/pocl-cache
	POCL_CACHE_DIR="$(CURDIR)/build-san/pocl-cache" BRDFFIT_CLI=./build-san/brdffit \
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	./build-san/test_brdffit

bench: $(BUILD)/bench_brdffit bench-python
	@mkdir -p $(BUILD)/pocl-cache
	$(RUN_ENV) ./$(BUILD)/bench_brdffit

# The Python package's eval on 1,000,000 pairs against the same call from C.
$(BUILD)/bench_eval_c: bench/python/eval_c.c include/brdffit.h $(BUILD)/libbrdffit.so
	$(CC) $(CPPFLAGS) $(CFLAGS) -o $@ $< -L$(BUILD) -lbrdffit -Wl,-rpath,$(CURDIR)/$(BUILD) $(LDFLAGS)

bench-python: $(BUILD)/bench_eval_c $(BUILD)/libbrdffit.so
	BRDFFIT_LIBRARY=$(CURDIR)/$(BUILD)/$(SONAME) \
	    "$$(sh python/find-python numpy)" bench/python/eval_numpy.py ./$(BUILD)/bench_eval_c

install: all
	install -d $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/bin
	install -m 644 include/brdffit.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 $(BUILD)/libbrdffit.a $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(BUILD)/$(SONAME) $(DESTDIR)$(PREFIX)/lib/
	ln -sf $(SONAME) $(DESTDIR)$(PREFIX)/lib/libbrdffit.so
	install -m 755 $(BUILD)/brdffit $(DESTDIR)$(PREFIX)/bin/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' brdffit.pc.in \
	    > $(DESTDIR)$(PREFIX)/lib/pkgconfig/brdffit.pc
	$(MAKE) --no-print-directory install-python

# The Python package into $(PYTHONDIR) (default: $(PREFIX)/lib/pythonX.Y/dist-packages
# of the python3 on PATH, where Debian's python3 looks for /usr/local and /usr),
# with a relative link to the installed library next to it (where it looks first
# after $$BRDFFIT_LIBRARY).  Skipped, with a note, when there is no python3.
PY_SRC = $(wildcard python/brdffit/*.py)
install-python:
	@dir='$(PYTHONDIR)'; \
	if [ -z "$$dir" ]; then \
	    v=$$(python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null) || \
	    { echo "install: no python3, the Python package (python/) is not installed"; exit 0; }; \
	    dir='$(PREFIX)'/lib/python$$v/dist-packages; \
	fi; \
	set -x; \
	install -d "$(DESTDIR)$$dir/brdffit" && \
	install -m 644 $(PY_SRC) "$(DESTDIR)$$dir/brdffit/" && \
	ln -sf "$$(realpath -m --relative-to="$$dir/brdffit" '$(PREFIX)/lib/$(SONAME)')" \
	    "$(DESTDIR)$$dir/brdffit/$(SONAME)"

clean:
	rm -rf $(BUILD) build-san

# The header dependencies the compiler recorded (-MMD -MP).
-include $(wildcard $(BUILD)/*/*.d)

.PHONY: all demo test sanitize bench bench-python install install-python clean
.DELETE_ON_ERROR:

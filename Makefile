# SPDX-License-Identifier: MIT
# brdffit -- library (libbrdffit.a, libbrdffit.so), program (brdffit), tests, benchmark.
#
#   make             build/libbrdffit.a build/libbrdffit.so build/brdffit build/brdffit.1
#   make demo        build, then run the batch on the embedded synthetic material
#                    (report in build/demo; prints the path of its index.html)
#   make test        build and run the Check suite and the Python package's tests
#                    (python/tests, pytest; uses ../shared when present)
#   make sanitize    the suite under AddressSanitizer + UndefinedBehaviorSanitizer
#   make tsan        the threaded tests under ThreadSanitizer (clang)
#   make fuzz        the fuzz targets (tests/fuzz/, libFuzzer), FUZZ_SECONDS each (default 60)
#   make bench       the benchmark (bench/), figures: docs/performance.md
#   make bench-python  only its Python part (eval from NumPy against C)
#   make bench-mitsuba  the Mitsuba 3 plugin's render time (docs/mitsuba.md)
#   make bench-database  the 100 tables x every model end to end (a few minutes)
#   make bench-ceres  brdffit's fit against a tuned Ceres Solver fit (installs Ceres)
#   make fidelity    every published material x model against the paper and a stored run
#   make fidelity-quick  the same on ten materials
#   make deps        install the Debian packages the build needs (.ci/install-deps)
#   make install PREFIX=/usr/local [DESTDIR=...]   headers, libraries, brdffit.pc,
#                    program, its manual page, and the Python package (python/brdffit)
#                    beside the library
#   make uninstall PREFIX=/usr/local [DESTDIR=...]  removes what install put there
#   make clean

.DEFAULT_GOAL := all

PREFIX   ?= /usr/local
BUILD    ?= build
CC       ?= cc
OPT      ?= -O2
SONAME    = libbrdffit.so.$(firstword $(subst ., ,$(VERSION)))
# The version: the header's BRDFFIT_VERSION_MAJOR/MINOR/PATCH, the one place it is written.
VERSION  := $(shell sed -n 's/^\#define BRDFFIT_VERSION_\(MAJOR\|MINOR\|PATCH\) *\([0-9][0-9]*\).*/\2/p' \
                include/brdffit.h | paste -sd. -)

# ---- build dependencies ----
# `make deps` installs the Debian packages the build needs (.ci/install-deps,
# a no-op when they are there).  A build runs it once, the first time, through
# the stamp $(DEPS_STAMP) (an order-only prerequisite of the build folders);
# `make install` / `uninstall` only check (never apt), `make clean` and
# `make -n` never run it.  pkg-config is asked when a recipe runs (`=`, not
# `:=`), so a first build sees the packages it has just installed.
DEPS_STAMP = $(BUILD)/.deps-ok
deps:
	sh .ci/install-deps
$(DEPS_STAMP):
	sh .ci/install-deps $(if $(filter install uninstall,$(MAKECMDGOALS)),--check)
	@mkdir -p $(@D) && touch $@

PKGS       = cminpack
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null || echo -I/usr/include/cminpack-1)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lcminpack)
CHECK_CFLAGS = $(shell pkg-config --cflags check 2>/dev/null)
CHECK_LIBS   = $(shell pkg-config --libs check 2>/dev/null || echo -lcheck -lsubunit -lrt -lpthread -lm)
# The program's image files: OpenEXR's C API (only its Core library) and libpng.
CLI_CFLAGS = $(shell pkg-config --cflags OpenEXR libpng 2>/dev/null)
CLI_LIBS   = $(or $(filter -lOpenEXRCore%,$(shell pkg-config --libs OpenEXR 2>/dev/null)),-lOpenEXRCore) \
             $(shell pkg-config --libs libpng 2>/dev/null || echo -lpng)

# Include paths: the library sees its own internals and the kernel headers;
# the program sees the public header and its own; the tests, which reach
# into both on purpose, see all; the benchmark sees the library's.
CPPFLAGS += -Iinclude -DCL_TARGET_OPENCL_VERSION=120 -DCL_USE_DEPRECATED_OPENCL_1_2_APIS
LIB_INC   = -Isrc/lib -Ikernels $(PKG_CFLAGS)
# The program's rooms (src/cli/*/: commands, usage, text, pipeline, record,
# report, images) include each other's headers by name.
CLI_DIRS  = $(patsubst %/,%,$(sort $(dir $(wildcard src/cli/*/*.[ch]))))
CLI_INC   = -Isrc/cli $(addprefix -I,$(CLI_DIRS))
TEST_INC  = $(LIB_INC) $(CLI_INC) -Itests
# -MMD -MP: each object's header dependencies, written beside it (.d)
CFLAGS   += -std=c11 $(OPT) -g -Wall -Wextra -fPIC -MMD -MP -pthread $(SAN)
LDLIBS   += $(PKG_LIBS) -lOpenCL -lm -pthread
LDFLAGS  += $(SAN)

LIB_SRC  = $(wildcard src/lib/*.c src/lib/fit/*.c)
LIB_OBJ  = $(LIB_SRC:src/lib/%.c=$(BUILD)/lib/%.o) $(BUILD)/lib/kernel_source.o
# The kernel sources in the order they are concatenated for
# clCreateProgramWithSource (each after what it uses).  The one place that
# order is written.
KERNEL_SOURCES = kernels/bf_common.h kernels/bf_exp.h kernels/bf_models.h \
                 kernels/bf_he_const.h kernels/bf_he_num.h kernels/bf_he_model.h kernels/bf_lobe.h \
                 kernels/bf_he_surface.h kernels/bf_he_series.h kernels/bf_he_tab.h \
                 kernels/bf_he_memo.h kernels/bf_he_stages.h kernels/bf_he_rows.h \
                 kernels/bf_he_pass.h kernels/bf_lobe_pass.h \
                 kernels/bf_layout.h kernels/bf_pass.h kernels/bf_pass.cl
CLI_SRC  = $(wildcard src/cli/*.c src/cli/*/*.c)
# The program's files but its main: the tests link them to test svg.c etc.
CLI_SUPPORT_OBJ = $(filter-out $(BUILD)/cli/brdffit.o,$(CLI_SRC:src/cli/%.c=$(BUILD)/cli/%.o))
TEST_SRC = $(wildcard tests/*.c)
BENCH_SRC = bench/bench.c bench/bench_batch.c bench/bench_cli.c bench/bench_database.c bench/bench_metric.c bench/bench_record.c \
            bench/bench_render.c bench/bench_summary.c \
            bench/bench_stream.c bench/cli_run.c

all: $(BUILD)/libbrdffit.a $(BUILD)/libbrdffit.so $(BUILD)/brdffit $(BUILD)/brdffit.1

$(BUILD)/lib $(BUILD)/cli $(BUILD)/tests $(BUILD)/bench: | $(DEPS_STAMP)
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

# ---- the libraries: only brdffit_* is visible ----
# Library objects are compiled -fvisibility=hidden; include/brdffit.h gives
# its declarations default visibility, so libbrdffit.so exports brdffit_*
# only.  libbrdffit.a holds ONE relocatable object (ld -r) whose hidden
# symbols are made local (objcopy --localize-hidden), so its internals (bf_*)
# cannot collide with a caller's.  The tests and the benchmark reach the
# internals through libbrdffit-internal.a (the plain objects; not installed).
LIB_CFLAGS = -fvisibility=hidden
SOFILE     = libbrdffit.so.$(VERSION)
OBJCOPY   ?= objcopy
# The flags above live here: a changed Makefile rebuilds the library objects.
$(LIB_OBJ): Makefile

# src/lib/fit/*.c into $(BUILD)/lib/fit/ as well
$(BUILD)/lib/fit: | $(BUILD)/lib
	mkdir -p $@

$(BUILD)/lib/%.o: src/lib/%.c | $(BUILD)/lib $(BUILD)/lib/fit
	$(CC) $(CPPFLAGS) $(LIB_INC) $(CFLAGS) $(LIB_CFLAGS) -c -o $@ $<

# The affine pass's block loops become vectors only where sqrt need not set errno.
$(BUILD)/lib/fit/affine_pass.o: CFLAGS += -fno-math-errno

$(BUILD)/lib/kernel_source.o: $(BUILD)/lib/kernel_source.c
	$(CC) $(CPPFLAGS) $(CFLAGS) $(LIB_CFLAGS) -c -o $@ $<

$(BUILD)/libbrdffit-internal.a: $(LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/lib/libbrdffit-all.o: $(LIB_OBJ)
	$(LD) -r -o $@ $^ && $(OBJCOPY) --localize-hidden $@

$(BUILD)/libbrdffit.a: $(BUILD)/lib/libbrdffit-all.o
	rm -f $@ && ar rcs $@ $^

$(BUILD)/$(SOFILE): $(LIB_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/libbrdffit.so: $(BUILD)/$(SOFILE)
	ln -sf $(SOFILE) $(BUILD)/$(SONAME) && ln -sf $(SONAME) $@

$(BUILD)/cli/%.o: src/cli/%.c | $(BUILD)/cli
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(CLI_INC) $(CLI_CFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/brdffit: $(CLI_SRC:src/cli/%.c=$(BUILD)/cli/%.o) $(BUILD)/libbrdffit.a
	$(CC) $(LDFLAGS) -o $@ $^ $(CLI_LIBS) $(LDLIBS)

# The tests' build of the program, never installed: fault injection compiled
# in (-DBRDFFIT_FAULTS; BRDFFIT_FAULT=POINT:N kills it there, src/cli/record/fault.c).
# The files that use the hooks are compiled again into cli-faults/, the others
# are the program's.
FAULT_SRC = $(shell grep -l 'cli_fault_' $(CLI_SRC))
FAULT_OBJ = $(FAULT_SRC:src/cli/%.c=$(BUILD)/cli-faults/%.o)
$(BUILD)/cli-faults: | $(DEPS_STAMP)
	mkdir -p $@

$(BUILD)/cli-faults/%.o: src/cli/%.c | $(BUILD)/cli-faults
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) -DBRDFFIT_FAULTS $(CLI_INC) $(CLI_CFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/brdffit-faults: $(filter-out $(FAULT_SRC:src/cli/%.c=$(BUILD)/cli/%.o),$(CLI_SRC:src/cli/%.c=$(BUILD)/cli/%.o)) \
                         $(FAULT_OBJ) $(BUILD)/libbrdffit.a
	$(CC) $(LDFLAGS) -o $@ $^ $(CLI_LIBS) $(LDLIBS)

# The manual page: the program's help text as roff (src/cli/usage/man.c).
$(BUILD)/brdffit.1: $(BUILD)/brdffit
	$(abspath $<) help --man > $@.tmp && mv $@.tmp $@

$(BUILD)/tests/%.o: tests/%.c | $(BUILD)/tests
	$(CC) $(CPPFLAGS) $(TEST_INC) $(CLI_CFLAGS) $(CHECK_CFLAGS) $(CFLAGS) -c -o $@ $<

# expat: the tests' independent XML parser
$(BUILD)/test_brdffit: $(TEST_SRC:tests/%.c=$(BUILD)/tests/%.o) $(CLI_SUPPORT_OBJ) $(BUILD)/libbrdffit-internal.a
	$(CC) $(LDFLAGS) -o $@ $^ $(CHECK_LIBS) -lexpat $(CLI_LIBS) $(LDLIBS)

# The benchmark reads its tables with the tests' helpers (tests/testutil.c) and
# the program's JSON records with their parser (tests/jsoncheck.c).
$(BUILD)/bench/%.o: bench/%.c | $(BUILD)/bench
	$(CC) $(CPPFLAGS) $(LIB_INC) $(CLI_INC) -Itests $(CFLAGS) -c -o $@ $<

# it also times the program's per-material render and plot files (src/cli)
$(BUILD)/bench_brdffit: $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%.o) $(BUILD)/tests/testutil.o $(BUILD)/tests/jsoncheck.o $(CLI_SUPPORT_OBJ) $(BUILD)/libbrdffit-internal.a
	$(CC) $(LDFLAGS) -o $@ $^ $(CLI_LIBS) $(LDLIBS)

# libFuzzer targets (tests/fuzz/) and their seed writer.
$(BUILD)/fuzz:
	mkdir -p $@

$(BUILD)/fuzz/%.o: tests/fuzz/%.c | $(BUILD)/fuzz
	$(CC) $(CPPFLAGS) $(CLI_INC) $(CFLAGS) -c -o $@ $<

$(BUILD)/fuzz/fuzz_table: $(BUILD)/fuzz/fuzz_table.o $(BUILD)/libbrdffit.a
	$(CC) $(LDFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

$(BUILD)/fuzz/fuzz_options: $(BUILD)/fuzz/fuzz_options.o $(CLI_SUPPORT_OBJ) $(BUILD)/libbrdffit.a
	$(CC) $(LDFLAGS) -fsanitize=fuzzer -o $@ $^ $(CLI_LIBS) $(LDLIBS)

$(BUILD)/fuzz/fuzz_journal: $(BUILD)/fuzz/fuzz_journal.o $(CLI_SUPPORT_OBJ) $(BUILD)/libbrdffit.a
	$(CC) $(LDFLAGS) -fsanitize=fuzzer -o $@ $^ $(CLI_LIBS) $(LDLIBS)

$(BUILD)/fuzz/make_seeds: tests/fuzz/make_seeds.c | $(BUILD)/fuzz
	$(CC) -std=c11 -O1 -Wall -Wextra -o $@ $<

# The environment every run gets: PoCL needs a writable cache directory.
RUN_ENV = POCL_CACHE_DIR="$${POCL_CACHE_DIR:-$(CURDIR)/$(BUILD)/pocl-cache}"

demo: all
	@mkdir -p -m 700 $(BUILD)/pocl-cache
	$(RUN_ENV) ./$(BUILD)/brdffit batch --demo --out $(BUILD)/demo

# The Check suite, the Python package's tests, then tests/packaging.sh
# (exported symbols, the static library's internals, install/uninstall,
# pkg-config, README's example built and run in C and C++, shared and
# static).  All always run; any failing fails the goal.
test: $(BUILD)/test_brdffit all $(BUILD)/brdffit-faults
	@mkdir -p -m 700 $(BUILD)/pocl-cache
	@rc=0; $(RUN_ENV) BRDFFIT_CLI=./$(BUILD)/brdffit BRDFFIT_CLI_FAULTS=./$(BUILD)/brdffit-faults \
	    ./$(BUILD)/test_brdffit || rc=1; \
	$(RUN_ENV) BRDFFIT_CLI=$(CURDIR)/$(BUILD)/brdffit BRDFFIT_LIBRARY=$(CURDIR)/$(BUILD)/$(SONAME) \
	    sh python/tests/run -q || rc=1; \
	$(RUN_ENV) BUILD=$(BUILD) CC="$(CC)" sh tests/packaging.sh || rc=1; \
	exit $$rc

# The same suite built with ASan + UBSan in its own build directory, Check's
# timeouts x4 (ASan slows every test).  LLVM (inside PoCL) keeps allocations
# until exit: tests/lsan.supp names them.
# use_sigaltstack=0: GCC 12's ASan dies ("unable to unmap" its alternate signal
# stack) when threads exit in the threads suite; with it that suite passes clean.
# intercept_tls_get_addr=0: LSan's stop-the-world tracer sometimes crashes at a
# forked test's exit ("Tracer caught signal 11: addr=0x948", "LeakSanitizer has
# encountered a fatal error"; google/sanitizers#1322: the dynamic TLS blocks it
# walks, PoCL's dlopen'd kernels among them), and a test body that passed then
# counts as an error (dozens of the fit suite's tests in some builds; none
# with it).  A pointer kept only in dynamic TLS would then be reported as a
# leak, not hidden.
sanitize:
	$(MAKE) BUILD=build-san OPT=-O1 SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
	    build-san/test_brdffit build-san/brdffit build-san/brdffit-faults build-san/brdffit.1
	@mkdir -p -m 700 build-san/pocl-cache
	POCL_CACHE_DIR="$(CURDIR)/build-san/pocl-cache" BRDFFIT_CLI=./build-san/brdffit \
	BRDFFIT_CLI_FAULTS=./build-san/brdffit-faults \
	CK_TIMEOUT_MULTIPLIER=$${CK_TIMEOUT_MULTIPLIER:-4} \
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:use_sigaltstack=0:intercept_tls_get_addr=0 \
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	./build-san/test_brdffit

# The threaded tests (the threads suite, and the alloc suite's pool) under
# ThreadSanitizer (clang; .ci/install-deps clang installs it), in their own
# build directory.  A report fails the test that ran into it.  tests/tsan.supp
# names what is not ours (PoCL, LLVM).
tsan:
	sh .ci/install-deps clang
	$(MAKE) BUILD=build-tsan CC=clang OPT=-O1 SAN="-fsanitize=thread -fno-omit-frame-pointer" \
	    build-tsan/test_brdffit
	@mkdir -p -m 700 build-tsan/pocl-cache
	for suite in threads alloc; do \
	    POCL_CACHE_DIR="$(CURDIR)/build-tsan/pocl-cache" CK_RUN_SUITE=$$suite \
	    TSAN_OPTIONS=halt_on_error=1:suppressions=$(CURDIR)/tests/tsan.supp \
	    ./build-tsan/test_brdffit || exit 1; \
	done

# The fuzz targets built with clang (libFuzzer + ASan + UBSan) in their own
# build directory, each run for FUZZ_SECONDS from the seed corpus
# tests/fuzz/make_seeds.c writes (build-fuzz/corpus/, grown by the runs).  A
# crash stops the run and leaves its input as build-fuzz/crash-*.
FUZZ_SECONDS ?= 60
FUZZ_SAN = -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
FUZZ_RUN = -max_total_time=$(FUZZ_SECONDS) -rss_limit_mb=4096 -close_fd_mask=3 -print_final_stats=1
fuzz:
	sh .ci/install-deps clang
	$(MAKE) BUILD=build-fuzz CC=clang OPT=-O1 SAN="$(FUZZ_SAN) -fsanitize=fuzzer-no-link" \
	    build-fuzz/fuzz/fuzz_table build-fuzz/fuzz/fuzz_options build-fuzz/fuzz/fuzz_journal \
	    build-fuzz/fuzz/make_seeds
	mkdir -p build-fuzz/corpus/table build-fuzz/corpus/options build-fuzz/corpus/journal
	./build-fuzz/fuzz/make_seeds build-fuzz/corpus
	ASAN_OPTIONS=detect_leaks=1 ./build-fuzz/fuzz/fuzz_table $(FUZZ_RUN) -max_len=4200 \
	    -artifact_prefix=build-fuzz/crash-table- build-fuzz/corpus/table
	ASAN_OPTIONS=detect_leaks=1 ./build-fuzz/fuzz/fuzz_options $(FUZZ_RUN) -max_len=2048 \
	    -artifact_prefix=build-fuzz/crash-options- build-fuzz/corpus/options
	ASAN_OPTIONS=detect_leaks=1 ./build-fuzz/fuzz/fuzz_journal $(FUZZ_RUN) -max_len=8192 \
	    -artifact_prefix=build-fuzz/crash-journal- build-fuzz/corpus/journal

# Every figure the benchmarks print is appended to bench/results.tsv through
# bench/record (BENCH_RECORD= records nothing); BENCH_ARGS: bench_brdffit's
# options (--quick, --models a,b, --parts 1,2, ...).
BENCH_RECORD ?= $(CURDIR)/bench/record
BENCH_RECORD_ARG = $(if $(BENCH_RECORD),--record $(BENCH_RECORD))
bench: $(BUILD)/bench_brdffit $(BUILD)/brdffit bench-python
	@mkdir -p -m 700 $(BUILD)/pocl-cache
	$(RUN_ENV) BRDFFIT_CLI=$(CURDIR)/$(BUILD)/brdffit ./$(BUILD)/bench_brdffit $(BENCH_RECORD_ARG) $(BENCH_ARGS)

# The whole database (bench/bench_database.c): brdffit fit over the 100 tables
# x every model, once reading ahead and BENCH_ROUNDS times each fit alone,
# against the stored run bench/baseline-errors.tsv (docs/performance.md).  A few minutes.
BENCH_ROUNDS ?= 3
bench-database: $(BUILD)/bench_brdffit $(BUILD)/brdffit
	@mkdir -p -m 700 $(BUILD)/pocl-cache
	$(RUN_ENV) BRDFFIT_CLI=$(CURDIR)/$(BUILD)/brdffit ./$(BUILD)/bench_brdffit --database \
	    --rounds $(BENCH_ROUNDS) --baseline bench/baseline-errors.tsv $(BENCH_RECORD_ARG)

# The glTF models beside GGX on the 100 tables (bench/gltf_database.py):
# medians of the Errors and of their ratios to GGX's, where metallic ends,
# the parameters on a bound (docs/gltf.md).  A few minutes.
bench-gltf: $(BUILD)/brdffit
	python3 bench/gltf_database.py $(CURDIR)/$(BUILD)/brdffit $(BUILD)/bench-gltf \
	    $(if $(BENCH_RECORD),--record)

# The Mitsuba 3 plugin (bench/mitsuba_render.py): a 256 x 256 sphere at 64
# samples a pixel through brdffit.mitsuba with llvm_ad_rgb, in the tests'
# venv (BRDFFIT_TEST_VENV, else build/test-venv, with mitsuba; docs/mitsuba.md).
MITSUBA_VENV ?= $(or $(BRDFFIT_TEST_VENV),$(CURDIR)/$(BUILD)/test-venv)
bench-mitsuba: $(BUILD)/brdffit $(BUILD)/libbrdffit.so
	BRDFFIT_LIBRARY=$(CURDIR)/$(BUILD)/$(SONAME) \
	    $(MITSUBA_VENV)/bin/python bench/mitsuba_render.py $(CURDIR)/$(BUILD)/brdffit \
	    $(BUILD)/bench-mitsuba $(if $(BENCH_RECORD),--record)

# The Python package's eval on 1,000,000 pairs against the same call from C.
$(BUILD)/bench_eval_c: bench/python/eval_c.c include/brdffit.h $(BUILD)/libbrdffit.so
	$(CC) $(CPPFLAGS) $(CFLAGS) -o $@ $< -L$(BUILD) -lbrdffit -Wl,-rpath,$(CURDIR)/$(BUILD) $(LDFLAGS)

bench-python: $(BUILD)/bench_eval_c $(BUILD)/libbrdffit.so
	BRDFFIT_LIBRARY=$(CURDIR)/$(BUILD)/$(SONAME) \
	    "$$(sh python/find-python numpy)" bench/python/eval_numpy.py ./$(BUILD)/bench_eval_c $(BENCH_RECORD_ARG)

# brdffit's fit against a tuned Ceres Solver fit of the same problem
# (bench/ceres/fit_ceres.cc says what it solves and how it is tuned), per
# model and table, each figure appended to bench/results.tsv (bench/record).
# Ceres comes from Debian (.ci/install-deps ceres); nothing else needs it.
# CERES_ARGS: more options (--models, --materials, --reps, ...).
CXX      ?= g++
CERES_CXXFLAGS = -std=c++17 $(OPT) -g -Wall -Wextra -MMD -MP -pthread -I/usr/include/eigen3
CERES_LIBS     = -lceres -lglog -lgflags
$(BUILD)/bench-ceres: | $(DEPS_STAMP)
	mkdir -p $@

$(BUILD)/bench-ceres/fc_shim.o: bench/ceres/fc_shim.c bench/ceres/fc_shim.h | $(BUILD)/bench-ceres
	$(CC) $(CPPFLAGS) $(LIB_INC) $(CFLAGS) -c -o $@ $<

$(BUILD)/bench-ceres/fit_ceres.o: bench/ceres/fit_ceres.cc bench/ceres/fc_shim.h | $(BUILD)/bench-ceres
	sh .ci/install-deps ceres
	$(CXX) $(CPPFLAGS) -Ibench/ceres -Itests $(CERES_CXXFLAGS) -c -o $@ $<

$(BUILD)/bench_ceres: $(BUILD)/bench-ceres/fit_ceres.o $(BUILD)/bench-ceres/fc_shim.o $(BUILD)/tests/testutil.o $(BUILD)/libbrdffit-internal.a
	$(CXX) $(LDFLAGS) -o $@ $^ $(CERES_LIBS) $(LDLIBS)

bench-ceres:
	sh .ci/install-deps ceres
	$(MAKE) $(BUILD)/bench_ceres
	@mkdir -p -m 700 $(BUILD)/pocl-cache
	$(RUN_ENV) ./$(BUILD)/bench_ceres --record bench/record $(CERES_ARGS)

# ---- install / uninstall ----
# The header, both libraries (libbrdffit.so.VERSION, its soname link and the
# .so link), brdffit.pc, the program, and the drop-in evaluator headers a
# renderer includes (docs/library.md): kernels/bf_lobe.h and kernels/bf_gltf.h
# and every header they include, as <brdffit/bf_lobe.h>, <brdffit/bf_gltf.h>.
LIBDIR     = $(PREFIX)/lib
INCLUDEDIR = $(PREFIX)/include
BINDIR     = $(PREFIX)/bin
MAN1DIR    = $(PREFIX)/share/man/man1
DROPIN_HEADERS = $(sort $(foreach h,kernels/bf_lobe.h kernels/bf_gltf.h,\
                   $(shell $(CC) -MM -MT x -x c $(h) | sed -e 's/^x://' -e 's/\\//g')))
# brdffit.pc's Libs carries -Wl,-rpath,${libdir} for every prefix but / and
# /usr, so that a program linked through `pkg-config --libs brdffit` finds
# libbrdffit.so.1 where it was installed, without LD_LIBRARY_PATH.  /usr/lib
# is the dynamic loader's own; /usr/local/lib gets the run path too: Debian's
# ld.so.conf names it, but the loader finds a library there only after
# ldconfig has run, which `make install` does not do (the run path is harmless
# once it has).
comma := ,
PC_RPATH = $(if $(filter / /usr,$(PREFIX) $(patsubst %/,%,$(PREFIX))),,-Wl$(comma)-rpath$(comma)$${libdir})
$(BUILD)/bench_fidelity: $(BUILD)/bench/fidelity.o $(BUILD)/libbrdffit-internal.a
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

# Every published material x every model, against the published parameters
# and the stored run bench/baseline-errors.tsv (docs/fidelity.md).
fidelity: $(BUILD)/bench_fidelity
	@mkdir -p -m 700 $(BUILD)/pocl-cache
	$(RUN_ENV) ./$(BUILD)/bench_fidelity --baseline bench/baseline-errors.tsv $(FIDELITY_ARGS)

# The same on ten of those materials (bench/fidelity.c: QUICK_MATERIALS), a few minutes.
fidelity-quick:
	$(MAKE) fidelity FIDELITY_ARGS='--materials quick $(FIDELITY_ARGS)'

install: all
	install -d $(DESTDIR)$(INCLUDEDIR)/brdffit $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(BINDIR)
	install -m 644 include/brdffit.h $(DESTDIR)$(INCLUDEDIR)/
	install -m 644 $(DROPIN_HEADERS) $(DESTDIR)$(INCLUDEDIR)/brdffit/
	install -m 644 $(BUILD)/libbrdffit.a $(DESTDIR)$(LIBDIR)/
	install -m 755 $(BUILD)/$(SOFILE) $(DESTDIR)$(LIBDIR)/
	ln -sf $(SOFILE) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libbrdffit.so
	install -m 755 $(BUILD)/brdffit $(DESTDIR)$(BINDIR)/
	install -d $(DESTDIR)$(MAN1DIR) && install -m 644 $(BUILD)/brdffit.1 $(DESTDIR)$(MAN1DIR)/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' -e 's|@RPATH@|$(PC_RPATH)|' brdffit.pc.in \
	    > $(DESTDIR)$(LIBDIR)/pkgconfig/brdffit.pc
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
	ln -sf "$$(realpath -m --relative-to="$$dir/brdffit" '$(LIBDIR)/$(SONAME)')" \
	    "$(DESTDIR)$$dir/brdffit/$(SONAME)"

uninstall:
	rm -f $(DESTDIR)$(INCLUDEDIR)/brdffit.h $(DESTDIR)$(LIBDIR)/libbrdffit.a \
	      $(DESTDIR)$(LIBDIR)/$(SOFILE) $(DESTDIR)$(LIBDIR)/$(SONAME) $(DESTDIR)$(LIBDIR)/libbrdffit.so \
	      $(DESTDIR)$(LIBDIR)/pkgconfig/brdffit.pc $(DESTDIR)$(BINDIR)/brdffit \
	      $(DESTDIR)$(MAN1DIR)/brdffit.1
	rm -f $(DESTDIR)$(INCLUDEDIR)/brdffit/*.h
	rmdir $(DESTDIR)$(INCLUDEDIR)/brdffit 2>/dev/null || true
	$(MAKE) --no-print-directory uninstall-python

# What install-python put there (the same folder).
uninstall-python:
	@dir='$(PYTHONDIR)'; \
	if [ -z "$$dir" ]; then \
	    v=$$(python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null) || exit 0; \
	    dir='$(PREFIX)'/lib/python$$v/dist-packages; \
	fi; \
	set -x; \
	rm -f $(addprefix "$(DESTDIR)$$dir/brdffit/",$(notdir $(PY_SRC))) "$(DESTDIR)$$dir/brdffit/$(SONAME)"; \
	rm -rf "$(DESTDIR)$$dir/brdffit/__pycache__"; \
	rmdir "$(DESTDIR)$$dir/brdffit" 2>/dev/null || true

clean:
	rm -rf $(BUILD) build-san build-tsan build-fuzz

# The header dependencies the compiler recorded (-MMD -MP).
-include $(wildcard $(BUILD)/*/*.d $(BUILD)/*/*/*.d)

.PHONY: all demo test sanitize tsan fuzz bench bench-ceres bench-database bench-gltf bench-python bench-mitsuba fidelity fidelity-quick deps install install-python uninstall uninstall-python clean
.DELETE_ON_ERROR:

#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/packaging.sh -- run by `make test` after the Check suite: what the
# built and installed libraries promise a caller.
#
#   symbols    libbrdffit.so exports only brdffit_* (nm -D --defined-only) and
#              has soname libbrdffit.so.1; libbrdffit.a defines no global
#              other than brdffit_*; a caller with its own bf_fail, bf_now, ...
#              links against either and each side calls its own
#   install    `make install DESTDIR=...` puts the header, the drop-in
#              evaluator headers, both libraries and their links, brdffit.pc
#              and the program there; `make uninstall` removes every file
#   pkg-config --cflags (brdffit's folder only), --libs, --static --libs;
#              Libs has the run path ${libdir} for a prefix other than /usr
#   prefix     `make install PREFIX=dir` (no DESTDIR): README's example built
#              with PKG_CONFIG_PATH=dir/lib/pkgconfig and pkg-config runs
#              without LD_LIBRARY_PATH (RUNPATH dir/lib); linked without it, not
#   README     its library example, built from the README text with
#              pkg-config in C and C++, shared and static (the static ones
#              need no libbrdffit.so), run on a synthetic table: it fits the
#              generating Cook-Torrance parameters back
#   drop-in    <brdffit/bf_lobe.h> compiles in C and C++ and equals brdffit_eval;
#              no header of the data pass's machinery is installed
#   no data    without ../shared the suite says so in one line, runs the
#              tests that need no data, and fails
#   deps       `make -n`, `make clean` and `make install` never call apt-get
#   licence    every .c/.h/.cl/.py file has an SPDX-License-Identifier line,
#              and LICENSE is the MIT licence
#
# Environment: BUILD (default build), CC, CXX.  Exit 0 when all pass.
set -u
BUILD=${BUILD:-build}
MAKE=make
CC=${CC:-cc}
CXX=${CXX:-c++}
TOP=$(pwd)
PASSED=0
FAILED=0
T=$(mktemp -d "${TMPDIR:-/tmp}/brdffit-packaging-XXXXXX") || exit 1
trap 'rm -rf "$T"' EXIT

pass() { PASSED=$((PASSED + 1)); }
fail() { FAILED=$((FAILED + 1)); echo "packaging: FAIL: $*" >&2; }
# expect DESCRIPTION COMMAND...: the command succeeds (its output kept in $T/out)
expect() {
    what=$1
    shift
    if "$@" >"$T/out" 2>&1; then pass; else fail "$what"; sed 's/^/    /' "$T/out" >&2; fi
}

VERSION=$(sed -n 's/^#define BRDFFIT_VERSION_\(MAJOR\|MINOR\|PATCH\) *\([0-9][0-9]*\).*/\2/p' include/brdffit.h | paste -sd. -)
SOFILE=$BUILD/libbrdffit.so.$VERSION

# ------------------------------------------------------------------ symbols

not_brdffit() { grep -v -E '^brdffit_' || true; }

expect "soname of $SOFILE is libbrdffit.so.1" \
    sh -c "readelf -d '$SOFILE' | grep -q 'SONAME.*\[libbrdffit.so.1\]'"
nm -D --defined-only "$SOFILE" | awk '{ print $NF }' >"$T/dynsyms"
if [ -s "$T/dynsyms" ] && [ -z "$(not_brdffit <"$T/dynsyms")" ]; then pass; else
    fail "libbrdffit.so exports names other than brdffit_*: $(not_brdffit <"$T/dynsyms" | tr '\n' ' ')"
fi
nm -g --defined-only "$BUILD/libbrdffit.a" | awk 'NF == 3 { print $3 }' >"$T/arsyms"
if [ -s "$T/arsyms" ] && [ -z "$(not_brdffit <"$T/arsyms")" ]; then pass; else
    fail "libbrdffit.a defines globals other than brdffit_*: $(not_brdffit <"$T/arsyms" | tr '\n' ' ')"
fi

LIBS="-lcminpack -lOpenCL -lm"
expect "a caller defining bf_fail links with libbrdffit.a" \
    $CC -std=c11 -Iinclude -o "$T/collide-static" tests/packaging/collide.c "$BUILD/libbrdffit.a" $LIBS
expect "that caller runs (static)" "$T/collide-static"
expect "a caller defining bf_fail links with libbrdffit.so" \
    $CC -std=c11 -Iinclude -o "$T/collide-shared" tests/packaging/collide.c -L"$BUILD" -lbrdffit $LIBS
expect "that caller runs (shared)" env LD_LIBRARY_PATH="$TOP/$BUILD" "$T/collide-shared"

# ------------------------------------------------------------------ install

D=$T/root
P=/usr/local
expect "make install DESTDIR=$D" $MAKE -s install DESTDIR="$D" PREFIX=$P BUILD="$BUILD"
for f in include/brdffit.h include/brdffit/bf_lobe.h include/brdffit/bf_common.h \
         lib/libbrdffit.a "lib/libbrdffit.so.$VERSION" lib/pkgconfig/brdffit.pc bin/brdffit; do
    if [ -f "$D$P/$f" ]; then pass; else fail "make install did not install $P/$f"; fi
done
# the drop-in headers hold the lobes' values (the closed-form lobes, He's
# model) and none of a data pass's machinery
for f in bf_he_model.h bf_models.h bf_gltf.h; do
    if [ -f "$D$P/include/brdffit/$f" ]; then pass; else fail "make install did not install $P/include/brdffit/$f"; fi
done
for f in bf_lobe_pass.h bf_pass.h bf_layout.h bf_he_pass.h bf_he_rows.h bf_he_stages.h \
         bf_he_memo.h bf_he_tab.h bf_he_series.h bf_he_surface.h; do
    if [ -e "$D$P/include/brdffit/$f" ]; then
        fail "make install installed the data pass's $P/include/brdffit/$f"
    else pass; fi
done
if [ "$(readlink "$D$P/lib/libbrdffit.so.1")" = "libbrdffit.so.$VERSION" ] &&
   [ "$(readlink "$D$P/lib/libbrdffit.so")" = "libbrdffit.so.1" ]; then pass; else
    fail "the links libbrdffit.so -> libbrdffit.so.1 -> libbrdffit.so.$VERSION are not installed"
fi
expect "the installed program runs" sh -c "'$D$P/bin/brdffit' --version | grep -q '$VERSION'"

# ------------------------------------------------------------------ pkg-config

PKG_CONFIG_PATH=$D$P/lib/pkgconfig
PKG_CONFIG_SYSROOT_DIR=$D
export PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR
cflags=$(pkg-config --cflags brdffit)
libs=$(pkg-config --libs brdffit)
slibs=$(pkg-config --static --libs brdffit)
if [ "$(echo $cflags)" = "-I$D$P/include" ]; then pass; else
    fail "pkg-config --cflags brdffit is '$cflags', expected only -I$D$P/include"
fi
# the run path of a prefix other than /usr (pkgconf puts the sysroot before it too)
if [ "$(echo $libs)" = "-L$D$P/lib -Wl,-rpath,$D$P/lib -lbrdffit" ]; then pass; else
    fail "pkg-config --libs brdffit is '$libs'"
fi
if [ "$(echo $slibs)" = "-L$D$P/lib -Wl,-rpath,$D$P/lib -lbrdffit -Wl,-Bdynamic -lcminpack -lOpenCL -lm -pthread" ]; then pass; else
    fail "pkg-config --static --libs brdffit is '$slibs'"
fi

# ------------------------------------------------------------------ README's example

# The first ```c block after the marker line in README.md.
awk '/<!-- tests\/packaging.sh builds and runs this program/ { on = 1; next }
     on == 1 && /^```c/ { on = 2; next }
     on == 2 && /^```/ { exit }
     on == 2 { print }' README.md >"$T/example.c"
if grep -q 'int main' "$T/example.c"; then pass; else fail "no example program found in README.md"; fi
expect "the synthetic table for the example" \
    $CC -std=c11 -o "$T/mktable" tests/packaging/mktable.c $cflags $libs
expect "writing it" env LD_LIBRARY_PATH="$D$P/lib" "$T/mktable" "$T/ct.binary"

# fits_back OUTPUT: the example's output is a fit of the model to the table
# Cook-Torrance F0 0.4, m 0.15 made
fits_back() {
    awk '/^F0 / { ok = ($2 > 0.399 && $2 < 0.401 && $4 > 0.1499 && $4 < 0.1501 && $6 < 1e-6) }
         END { exit !ok }' "$1"
}

for lang in c c++; do
    if [ $lang = c ]; then comp="$CC -std=c11 -x c"; else comp="$CXX -std=c++11 -x c++"; fi
    expect "README example, $lang, shared: builds" \
        $comp -Wall -Werror -o "$T/ex-$lang-shared" "$T/example.c" $cflags $libs
    expect "README example, $lang, static: builds" \
        $comp -Wall -Werror -o "$T/ex-$lang-static" "$T/example.c" $cflags -Wl,-Bstatic $slibs
    if readelf -d "$T/ex-$lang-shared" 2>/dev/null | grep -q 'NEEDED.*libbrdffit.so.1'; then pass; else
        fail "README example, $lang, shared: does not load libbrdffit.so.1"
    fi
    if readelf -d "$T/ex-$lang-static" 2>/dev/null | grep -q 'NEEDED.*libbrdffit'; then
        fail "README example, $lang, static: still needs libbrdffit.so"
    else pass; fi
    for kind in shared static; do
        if env LD_LIBRARY_PATH="$D$P/lib" "$T/ex-$lang-$kind" "$T/ct.binary" >"$T/out" 2>&1 &&
           fits_back "$T/out"; then pass; else
            fail "README example, $lang, $kind: did not fit the table back:"
            sed 's/^/    /' "$T/out" >&2
        fi
    done
done

for lang in c c++; do
    if [ $lang = c ]; then comp="$CC -std=c11 -x c"; else comp="$CXX -std=c++11 -x c++"; fi
    expect "drop-in <brdffit/bf_lobe.h>, $lang: builds" \
        $comp -Wall -o "$T/dropin-$lang" tests/packaging/dropin.c $cflags $libs -lm
    expect "drop-in <brdffit/bf_lobe.h>, $lang: equals brdffit_eval" \
        env LD_LIBRARY_PATH="$D$P/lib" "$T/dropin-$lang"
done
unset PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR

expect "make uninstall DESTDIR=$D" $MAKE -s uninstall DESTDIR="$D" PREFIX=$P BUILD="$BUILD"
left=$(find "$D" ! -type d)
if [ -z "$left" ]; then pass; else fail "make uninstall left: $left"; fi

# ------------------------------------------------------------------ /usr: no run path

U=$T/usr-root
expect "make install DESTDIR=$U PREFIX=/usr" $MAKE -s install DESTDIR="$U" PREFIX=/usr BUILD="$BUILD"
if grep -q '^Libs: -L${libdir} *-lbrdffit$' "$U/usr/lib/pkgconfig/brdffit.pc"; then pass; else
    fail "brdffit.pc for /usr: Libs is not only -L\${libdir} -lbrdffit: $(grep '^Libs:' "$U/usr/lib/pkgconfig/brdffit.pc")"
fi
expect "make uninstall DESTDIR=$U PREFIX=/usr" $MAKE -s uninstall DESTDIR="$U" PREFIX=/usr BUILD="$BUILD"

# ------------------------------------------------------------------ a prefix of one's own

# `make install PREFIX=dir` (no DESTDIR): README's example, built through
# pkg-config with only PKG_CONFIG_PATH set, runs without LD_LIBRARY_PATH,
# because brdffit.pc gives it the run path dir/lib.
PP=$T/prefix
expect "make install PREFIX=$PP" $MAKE -s install PREFIX="$PP" BUILD="$BUILD"
pc() { env -u PKG_CONFIG_SYSROOT_DIR PKG_CONFIG_PATH="$PP/lib/pkgconfig" pkg-config "$@" brdffit; }
pp_libs=$(pc --libs)
if [ "$(echo $pp_libs)" = "-L$PP/lib -Wl,-rpath,$PP/lib -lbrdffit" ]; then pass; else
    fail "pkg-config --libs brdffit for PREFIX=$PP is '$pp_libs'"
fi
expect "README example through pkg-config, PREFIX=$PP: builds" \
    $CC -std=c11 -Wall -Werror -o "$T/ex-prefix" "$T/example.c" $(pc --cflags --libs)
if readelf -d "$T/ex-prefix" 2>/dev/null | grep -E -q "(RUNPATH|RPATH).*\[$PP/lib\]"; then pass; else
    fail "README example, PREFIX=$PP: no run path $PP/lib: $(readelf -d "$T/ex-prefix" | grep -E 'RUNPATH|RPATH')"
fi
if env -u LD_LIBRARY_PATH ldd "$T/ex-prefix" 2>&1 | grep -q "libbrdffit.so.1 => $PP/lib/libbrdffit.so.1"; then pass; else
    fail "README example, PREFIX=$PP: does not load $PP/lib/libbrdffit.so.1:"
    env -u LD_LIBRARY_PATH ldd "$T/ex-prefix" 2>&1 | sed 's/^/    /' >&2
fi
if env -u LD_LIBRARY_PATH "$T/ex-prefix" "$T/ct.binary" >"$T/out" 2>&1 && fits_back "$T/out"; then pass; else
    fail "README example, PREFIX=$PP, no LD_LIBRARY_PATH: did not run and fit the table back:"
    sed 's/^/    /' "$T/out" >&2
fi
# the control: linked without the run path it does not find the library
# (unless a libbrdffit.so.1 is installed where the loader looks anyway)
$CC -std=c11 -o "$T/ex-norpath" "$T/example.c" $(pc --cflags) -L"$PP/lib" -lbrdffit >"$T/out" 2>&1
if env -u LD_LIBRARY_PATH "$T/ex-norpath" "$T/ct.binary" >"$T/out" 2>&1; then
    echo "packaging: SKIP the control without the run path: it ran, a libbrdffit.so.1 is" \
         "installed where the loader finds it ($(env -u LD_LIBRARY_PATH ldd "$T/ex-norpath" | grep libbrdffit))"
elif grep -q 'libbrdffit.so.1: cannot open shared object file' "$T/out"; then pass; else
    fail "README example without the run path failed otherwise:"
    sed 's/^/    /' "$T/out" >&2
fi
expect "make uninstall PREFIX=$PP" $MAKE -s uninstall PREFIX="$PP" BUILD="$BUILD"
left=$(find "$PP" ! -type d 2>/dev/null)
if [ -z "$left" ]; then pass; else fail "make uninstall PREFIX=$PP left: $left"; fi

# ------------------------------------------------------------------ without ../shared

# The suite says in one line what is missing, runs what needs no data, and fails.
if env BRDFFIT_SHARED="$T/no-shared" CK_RUN_SUITE=models "$BUILD/test_brdffit" >"$T/out" 2>"$T/err"; then
    fail "the suite passed without ../shared"
elif [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "no-shared/tools/merl-table not found" "$T/err" &&
     grep -q "Checks: [1-9][0-9]*, Failures: 0, Errors: 0" "$T/out"; then pass; else
    fail "the suite without ../shared:"
    sed 's/^/    /' "$T/out" "$T/err" >&2
fi

# ------------------------------------------------------------------ no apt as a side effect

# A machine where the packages look missing (pkg-config --exists fails) and
# apt-get / sudo only record that they were called.
mkdir -p "$T/fakebin"
for tool in apt-get sudo; do
    printf '#!/bin/sh\necho "%s $*" >>"%s/apt-calls"\nexit 0\n' "$tool" "$T" >"$T/fakebin/$tool"
done
printf '#!/bin/sh\nexit 1\n' >"$T/fakebin/pkg-config"
chmod +x "$T/fakebin/"*
nodeps() { env PATH="$T/fakebin:$PATH" "$@" >"$T/out" 2>&1; }
rm -f "$T/apt-calls"
nodeps $MAKE -n BUILD="$T/b1" all test install
# (`make clean` in a copy of the Makefile: here it would remove the checkout's build folders)
mkdir -p "$T/tree" && cp -R Makefile .ci "$T/tree/"
nodeps $MAKE -C "$T/tree" BUILD=b1 clean
nodeps $MAKE install BUILD="$T/b2" DESTDIR="$T/r2" PREFIX=$P
if [ ! -e "$T/apt-calls" ]; then pass; else
    fail "make -n / clean / install called: $(cat "$T/apt-calls")"
fi
# the control: a first build does call it (so the fake would have seen it above)
nodeps $MAKE BUILD="$T/b3" "$T/b3/.deps-ok"
if grep -q 'apt-get install' "$T/apt-calls" 2>/dev/null; then pass; else
    fail "a first build with the packages missing did not run apt-get install"
fi

# ------------------------------------------------------------------ licence

# Every source file says its licence (SPDX) near its top; a file added
# without the line fails here.  Build folders and hidden folders are skipped.
missing=$(find . \( -path './.*' -o -name 'build*' -o -name __pycache__ \) -prune -o \
               -type f \( -name '*.c' -o -name '*.h' -o -name '*.cl' -o -name '*.py' \) -print |
          while read -r f; do
              head -n 3 "$f" | grep -q 'SPDX-License-Identifier: MIT' || echo "$f"
          done)
if [ -z "$missing" ]; then pass; else
    fail "no 'SPDX-License-Identifier: MIT' line in the first 3 lines of: $(echo $missing)"
fi
if [ -f LICENSE ] && grep -q '^MIT License' LICENSE && grep -q 'brdffit developers' LICENSE; then pass; else
    fail "LICENSE is not the MIT licence of the brdffit developers"
fi

echo "packaging: $PASSED passed, $FAILED failed"
[ "$FAILED" -eq 0 ]

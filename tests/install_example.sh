#!/bin/bash
# The installed library as a user sees it: `cmake --install` into a
# temporary prefix, then
#  - the installed files: shared library, public headers only, CMake
#    package, pkg-config file, the CLI;
#  - every public header compiles on its own, as C11 and as C++17;
#  - the library exports the sq_ API only;
#  - examples/remesh.c built against the install by find_package(seamquad)
#    and by pkg-config, run on examples/cube.obj: its quads pass the
#    referee; a missing input gives a message and exit 1.
# Needs SQ_BUILD_DIR, SQ_SOURCE_DIR, SQ_SHARED_DIR (set by ctest).
set -u
fail=0
pass() { echo "ok   $1"; }
bad() { echo "FAIL $1"; fail=1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix

if cmake --install "$SQ_BUILD_DIR" --prefix "$prefix" >"$tmp/install.log" 2>&1; then
    pass "cmake --install into a temporary prefix"
else
    bad "cmake --install"; cat "$tmp/install.log"; exit 1
fi

libdir=$(dirname "$(find "$prefix" -name 'libseamquad.so' | head -1)")
for f in "$prefix/bin/seamquad" "$libdir/libseamquad.so" "$libdir/cmake/seamquad/seamquadConfig.cmake" \
         "$libdir/cmake/seamquad/seamquadConfigVersion.cmake" "$libdir/pkgconfig/seamquad.pc" \
         "$prefix/include/seamquad/sq_remesh.h"; do
    [ -e "$f" ] && pass "installed ${f#$prefix/}" || bad "missing ${f#$prefix/}"
done
if find "$prefix" -name '*.a' | grep -q .; then bad "static archives installed"; else pass "no static archives installed"; fi

# Public headers: each compiles alone (its includes are installed too).
nh=0
for h in "$prefix"/include/seamquad/*.h; do
    name=$(basename "$h")
    nh=$((nh + 1))
    printf '#include <seamquad/%s>\nint main(void) { return 0; }\n' "$name" >"$tmp/h.c"
    cc -std=c11 -Wall -Wextra -Werror -I"$prefix/include" -c "$tmp/h.c" -o "$tmp/h.o" 2>"$tmp/h.err" \
        || { bad "$name does not compile alone as C11"; cat "$tmp/h.err"; }
    cp "$tmp/h.c" "$tmp/h.cpp"
    c++ -std=c++17 -Wall -Wextra -Werror -I"$prefix/include" -c "$tmp/h.cpp" -o "$tmp/h.o" 2>"$tmp/h.err" \
        || { bad "$name does not compile alone as C++17"; cat "$tmp/h.err"; }
done
[ "$nh" -ge 10 ] && pass "$nh public headers compile alone as C11 and C++17" || bad "only $nh public headers"
if ls "$prefix"/include/seamquad/ | grep -q -E 'internal|adapter'; then
    bad "private headers installed: $(ls "$prefix"/include/seamquad/ | grep -E 'internal|adapter')"
fi

# Exports: the sq_ API and nothing else.
other=$(nm -D --defined-only "$libdir/libseamquad.so" | awk '{print $3}' | grep -v '^sq_' | head -5)
[ -z "$other" ] && pass "libseamquad.so exports sq_* only" || bad "libseamquad.so exports $other"

v=$("$prefix/bin/seamquad" --version)
[ "$v" = "seamquad $(sed -n 's/^project(seamquad VERSION \([0-9.]*\).*/\1/p' "$SQ_SOURCE_DIR/CMakeLists.txt")" ] \
    && pass "installed CLI: $v" || bad "installed CLI --version: '$v'"

# The example through find_package(seamquad).
if cmake -S "$SQ_SOURCE_DIR/examples" -B "$tmp/ex" -DCMAKE_PREFIX_PATH="$prefix" >"$tmp/ex.log" 2>&1 &&
   cmake --build "$tmp/ex" >>"$tmp/ex.log" 2>&1; then
    pass "examples/ built against the install with find_package(seamquad)"
else
    bad "examples/ against the install"; cat "$tmp/ex.log"; exit 1
fi
if ldd "$tmp/ex/remesh" | grep libseamquad | grep -q "$prefix"; then
    pass "the example loads libseamquad from the prefix"
else
    bad "the example loads $(ldd "$tmp/ex/remesh" | grep libseamquad)"
fi
if "$tmp/ex/remesh" "$SQ_SOURCE_DIR/examples/cube.obj" "$tmp/cube_quads.obj" 300 >"$tmp/run.out" 2>"$tmp/run.err"; then
    pass "example: $(tail -1 "$tmp/run.out")"
    if python3 "$SQ_SHARED_DIR/tools/check_quad.py" "$SQ_SOURCE_DIR/examples/cube.obj" "$tmp/cube_quads.obj" \
        --self-intersections >"$tmp/ref.out" 2>&1; then
        pass "referee PASS on the example's quads"
    else
        bad "referee rejects the example's quads"; cat "$tmp/ref.out"
    fi
    grep -q '\[100%\]' "$tmp/run.err" && pass "progress reached 100%" || bad "no progress to 100%"
else
    bad "example run failed"; cat "$tmp/run.out" "$tmp/run.err"
fi
"$tmp/ex/remesh" "$tmp/missing.obj" "$tmp/never.obj" >"$tmp/miss.out" 2>"$tmp/miss.err"
rc=$?
if [ $rc -eq 1 ] && grep -q "missing.obj" "$tmp/miss.err" && [ ! -e "$tmp/never.obj" ]; then
    pass "missing input: exit 1, '$(head -1 "$tmp/miss.err")'"
else
    bad "missing input: exit $rc, $(cat "$tmp/miss.err")"
fi

# The same program through pkg-config.
export PKG_CONFIG_PATH="$libdir/pkgconfig"
if cc -std=c11 -Wall -Wextra -Werror "$SQ_SOURCE_DIR/examples/remesh.c" $(pkg-config --cflags --libs seamquad) \
      -o "$tmp/remesh_pc" 2>"$tmp/pc.err"; then
    pass "examples/remesh.c built with pkg-config ($(pkg-config --modversion seamquad))"
    if LD_LIBRARY_PATH="$libdir" "$tmp/remesh_pc" "$SQ_SOURCE_DIR/examples/cube.obj" "$tmp/cube_pc.obj" 300 \
          >/dev/null 2>&1 && cmp -s "$tmp/cube_quads.obj" "$tmp/cube_pc.obj"; then
        pass "pkg-config build gives the same quads"
    else
        bad "pkg-config build: run failed or other quads"
    fi
else
    bad "pkg-config build"; cat "$tmp/pc.err"
fi

exit $fail

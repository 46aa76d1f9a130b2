#!/usr/bin/env bash
# Slow external check: polydual as an installed library. Installs the build
# directory of POLYDUAL_BINARY into SCRATCH_DIR/prefix, checks the layout, then
# builds, against that prefix only, (1) examples/convert_mesh in Release and in
# Debug (Debian's Ceres exists in Release only: the package maps the
# consumer's Debug to it) and runs it on tests/data/cube5.msh, comparing its
# counts with `polydual convert --json`; (2) a generated project that compiles
# every installed header alone and runs the `generate` component.
# usage: install_example.sh POLYDUAL_BINARY SCRATCH_DIR
set -euo pipefail
bin=$1
out=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(dirname "$(dirname "$here")")
build=$(dirname "$bin")
prefix=$out/prefix
fail() { echo "install_example: $*" >&2; exit 1; }

# Only the example and the input mesh come from the source tree, copied, so
# that no include or package can resolve into it.
rm -rf "$out"
mkdir -p "$out"
cp -r "$root/examples/convert_mesh" "$out/convert_mesh"
cp "$root/tests/data/cube5.msh" "$out/cube5.msh"

cmake --install "$build" --prefix "$prefix" > "$out/install.log"

# The layout: the command, two archives, the package, headers only under
# include/polydual (no lib/cli, lib/alloc; nothing from tests, bench, fuzz).
unexpected=$(cd "$prefix" && find . -type f | sed 's|^\./||' | grep -Ev \
  '^(bin/polydual|lib/polydual/polydual-(gmsh|lbfgs)\.so|lib/libpolydual_(core|generate)\.a|lib/cmake/polydual/polydual-(config|config-version|targets|targets-[a-z]+|generate-targets|generate-targets-[a-z]+)\.cmake|include/polydual/[a-z_]+/[a-z0-9_]+\.h)$' || true)
[ -z "$unexpected" ] || fail "unexpected installed files: $unexpected"
for f in bin/polydual lib/polydual/polydual-gmsh.so lib/polydual/polydual-lbfgs.so lib/libpolydual_core.a lib/libpolydual_generate.a lib/cmake/polydual/polydual-config.cmake \
         lib/cmake/polydual/polydual-config-version.cmake include/polydual/pipeline/convert.h \
         include/polydual/io/read_tet_mesh.h include/polydual/generate/domains.h; do
  [ -f "$prefix/$f" ] || fail "missing $prefix/$f"
done
for d in cli alloc; do
  [ ! -e "$prefix/include/polydual/$d" ] || fail "include/polydual/$d installed (executables only)"
done

# configure_build NAME SOURCE BUILD_TYPE: a fresh build against the prefix only.
configure_build() {
  cmake -S "$2" -B "$out/build-$1" -DCMAKE_BUILD_TYPE="$3" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > "$out/build-$1.log" 2>&1 ||
    { cat "$out/build-$1.log"; fail "configuring $1 failed"; }
  cmake --build "$out/build-$1" -j2 >> "$out/build-$1.log" 2>&1 ||
    { tail -40 "$out/build-$1.log"; fail "building $1 failed"; }
  local dir
  dir=$(sed -n 's/^polydual_DIR:PATH=//p' "$out/build-$1/CMakeCache.txt")
  [ "$dir" = "$prefix/lib/cmake/polydual" ] || fail "$1 found polydual in '$dir', not in the prefix"
  ! grep -q -- "$root/lib" "$out/build-$1/compile_commands.json" || fail "$1 compiles against the source tree"
}

# The installed command loads Gmsh only for generate, from lib/polydual.
! ldd "$prefix/bin/polydual" | grep -q gmsh || fail "the installed polydual links libgmsh (only its module should)"
"$prefix/bin/polydual" generate cube --tets 500 -o "$out/gen500.msh" 2> "$out/gen500.log" ||
  { cat "$out/gen500.log"; fail "the installed polydual cannot generate (module in lib/polydual?)"; }
[ -s "$out/gen500.msh" ] || fail "the installed polydual generate wrote no mesh"
# ... and Ceres' solver only for --optimize global, from lib/polydual.
! ldd "$prefix/bin/polydual" | grep -Eq 'libglog|libcholmod|liblapack' ||
  fail "the installed polydual links Ceres' libraries (only its L-BFGS module should)"
"$prefix/bin/polydual" convert "$out/cube5.msh" -o "$out/cube5_global.vtu" --optimize global --quiet \
  > /dev/null 2> "$out/global.log" ||
  { cat "$out/global.log"; fail "the installed polydual cannot run --optimize global (module in lib/polydual?)"; }

"$prefix/bin/polydual" convert "$out/cube5.msh" -o "$out/cube5_cmd.vtu" --json > "$out/cube5_cmd.json"
expected=$(/usr/bin/python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
for k in ("cells", "closed_cells", "invalid_before", "invalid_after"):
    print(k, d[k])' "$out/cube5_cmd.json")

for type in Release Debug; do
  configure_build "example-$type" "$out/convert_mesh" "$type"
  exe=$out/build-example-$type/convert_mesh
  ! ldd "$exe" | grep -q gmsh || fail "convert_mesh ($type) links libgmsh without the generate component"
  "$exe" "$out/cube5.msh" "$out/cube5_$type.vtu" > "$out/example-$type.txt" ||
    { cat "$out/example-$type.txt"; fail "convert_mesh ($type) failed"; }
  [ -s "$out/cube5_$type.vtu" ] || fail "convert_mesh ($type) wrote no $out/cube5_$type.vtu"
  got=$(grep -E '^(cells|closed_cells|invalid_before|invalid_after) ' "$out/example-$type.txt")
  [ "$got" = "$expected" ] || fail "convert_mesh ($type) printed
$got
but polydual convert --json reports
$expected"
  grep -q '^valid yes$' "$out/example-$type.txt" || fail "convert_mesh ($type): result not valid"
  grep -Eq '^stage dual +[0-9.]+ s$' "$out/example-$type.txt" || fail "convert_mesh ($type): no dual stage time"
done
grep -q -- "-g" "$out/build-example-Debug/compile_commands.json" || fail "the Debug example is not a Debug build"

# Every installed header alone in its own TU, with the component `generate`
# (a mesh generated in memory and converted). predicates_inline.h is the
# second half of predicates.h and is included by it only.
headers=$out/headers
mkdir -p "$headers/tu"
tus=""
while IFS= read -r h; do
  [ "$h" = predicates/predicates_inline.h ] && continue
  tu=$headers/tu/$(echo "$h" | tr '/.' '__').cpp
  echo "#include \"$h\"" > "$tu"
  tus="$tus $tu"
done < <(cd "$prefix/include/polydual" && find . -name '*.h' | sed 's|^\./||' | sort)
cat > "$headers/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.20)
project(polydual_headers LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(polydual 0.1 CONFIG REQUIRED COMPONENTS generate)
get_target_property(map Ceres::ceres MAP_IMPORTED_CONFIG_DEBUG)
if(NOT map STREQUAL "Release")
  message(FATAL_ERROR "Ceres::ceres: MAP_IMPORTED_CONFIG_DEBUG is '\${map}', not Release")
endif()
add_library(headers OBJECT $tus)
target_link_libraries(headers PRIVATE polydual::generate)
add_executable(generate_convert generate_convert.cpp)
target_link_libraries(generate_convert PRIVATE polydual::generate)
CMAKE
cat > "$headers/generate_convert.cpp" <<'CPP'
#include <cstdio>

#include "generate/domains.h"
#include "pipeline/convert.h"

int main() {
  const polydual::TetSoup soup = polydual::generate_domain(polydual::Domain::TwoMat, 300);
  const polydual::ConvertResult r = polydual::convert(soup, polydual::PipelineParams{});
  std::printf("tets %zu cells %zu invalid_after %zu\n", soup.tets.size(), r.mesh.num_cells(),
              r.report.invalid_after);
  // At least one cell per primal vertex (one per region around it), all closed.
  return soup.tets.empty() || r.mesh.num_cells() < soup.points.size() || !r.check.validation.ok() ? 1 : 0;
}
CPP
configure_build headers "$headers" Debug
"$out/build-headers/generate_convert" > "$out/generate_convert.txt" ||
  { cat "$out/generate_convert.txt"; fail "generate_convert failed"; }
echo "install_example: ok ($(wc -w <<< "$tus") headers alone; $(cat "$out/generate_convert.txt"))"
cat "$out/example-Release.txt"

#!/usr/bin/env bash
# The install test (ctest install.consumer, tests/install/CMakeLists.txt): installs the build
# tree into a scratch prefix, checks what is there, runs the installed binary (its --version and
# the plot script it runs), then configures, builds and runs the project
# in consumer/ against that prefix alone (find_package(emcontact), emcontact::kernels and
# emcontact::core). Fails (exit 1) with a line naming what is wrong.
# Usage: run_consumer.sh BUILD_DIR WORK_DIR VERSION CMAKE GENERATOR CXX [LAUNCHER]
set -euo pipefail
build=$1 work=$2 version=$3 cmake=$4 generator=$5 cxx=$6 launcher=${7:-}
here=$(cd "$(dirname "$0")" && pwd)
prefix=$work/prefix
fail() { echo "install.consumer: $*" >&2; exit 1; }

rm -rf "$work"
mkdir -p "$work"
"$cmake" --install "$build" --prefix "$prefix" > "$work/install.log" || {
  cat "$work/install.log"; fail "cmake --install $build failed"; }

libdir=$(dirname "$(find "$prefix" -name emcontactConfig.cmake -print -quit)")
[[ $libdir != . ]] || fail "no emcontactConfig.cmake under $prefix"
for f in bin/emcontact share/emcontact/plot_monitors.py include/emcontact/types.hpp \
  include/emcontact/app/run.hpp include/emcontact/contact/search.hpp include/kernels/tet4.hpp \
  include/kernels/search.hpp; do
  [[ -e $prefix/$f ]] || fail "$prefix/$f was not installed"
done
for f in emcontactConfigVersion.cmake emcontactTargets.cmake; do
  [[ -e $libdir/$f ]] || fail "$libdir/$f was not installed"
done
# the package refers to the prefix, never to the source or build tree it came from
src=$(cd "$here/../.." && pwd)
if grep -rlF -e "$src" -e "$(cd "$build" && pwd)" "$libdir"; then
  fail "the installed package names the source or build tree (files above)"
fi
# no private header (src/) and no test or benchmark source of the kernel library
[[ -z $(find "$prefix/include" -name '*.cpp') ]] || fail "sources installed under include/"
"$prefix/bin/emcontact" --version | grep -q "^emcontact $version " ||
  fail "$prefix/bin/emcontact --version does not print emcontact $version"
# Output/plot runs the installed script, not the source tree's: a stand-in that fails with its
# own message makes the run warn with the installed path and that message (and still exit 0)
script=$prefix/share/emcontact/plot_monitors.py
printf 'import sys\nsys.exit("the installed plot script ran")\n' > "$script"
"$prefix/bin/emcontact" "$src/tests/hostile/good_box.xml" --output "$work/run" \
  --set Output/plot=true > "$work/run.out" 2> "$work/run.err" || {
  cat "$work/run.err"; fail "$prefix/bin/emcontact failed on tests/hostile/good_box.xml"; }
grep -qF "$script: the installed plot script ran" "$work/run.err" || {
  cat "$work/run.err"; fail "Output/plot did not run $script"; }

args=(-S "$here/consumer" -B "$work/consumer" -G "$generator" -DCMAKE_BUILD_TYPE=Release
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$prefix")
[[ -z $launcher ]] || args+=(-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher")
"$cmake" "${args[@]}" > "$work/configure.log" 2>&1 || {
  cat "$work/configure.log"; fail "the consumer does not configure against $prefix"; }
"$cmake" --build "$work/consumer" > "$work/build.log" 2>&1 || {
  cat "$work/build.log"; fail "the consumer does not build against $prefix"; }
out=$("$work/consumer/consumer") || { echo "$out"; fail "the consumer failed"; }
echo "$out"
grep -q "^core: emcontact $version " <<< "$out" ||
  fail "emcontact::core's version() is not $version"
grep -q "^consumer: ok$" <<< "$out" || fail "the consumer's checks failed"
echo "install.consumer: ok ($prefix)"

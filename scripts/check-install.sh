#!/usr/bin/env bash
# Checks the installable package from a build folder, as a user of it would meet it:
#   1. cmake --install BUILD --prefix into a fresh temporary folder;
#   2. every #include "..." in the installed headers names an installed header (no private
#      header of engine/src, oracle/src or io/src leaks into the public interface);
#   3. every installed header compiles on its own against the installed package (tests/install/);
#   4. examples/gate-my-engine configures, builds and passes its tests against that prefix
#      (CMAKE_PREFIX_PATH), through find_package(pge);
#   5. with --deb, `cpack -G DEB` makes the two Debian packages, and dpkg-deb lists in them the
#      command, the headers, the libraries and the CMake package, and their dependencies.
# Usage: scripts/check-install.sh [--deb] [--keep] BUILD_DIR
#   --keep  leaves the temporary folder (its path is printed) instead of removing it
# Environment: PGE_JOBS parallel build jobs for the example (default: number of cores).
# Exit code: 0 when every check passes, 1 when one fails, 2 on a bad command line.
set -euo pipefail
deb=0
keep=0
build=
for arg in "$@"; do
  case "$arg" in
    --deb) deb=1 ;;
    --keep) keep=1 ;;
    -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "check-install: unknown option $arg" >&2; exit 2 ;;
    *) build=$arg ;;
  esac
done
if [[ -z "$build" || ! -f "$build/CMakeCache.txt" ]]; then
  echo "check-install: give a configured and built build folder (got '${build}')" >&2
  exit 2
fi
build=$(cd "$build" && pwd)  # before the cd below: BUILD_DIR may be relative to the caller's folder
cd "$(dirname "$0")/.."
jobs=${PGE_JOBS:-$(nproc)}
work=$(mktemp -d "${TMPDIR:-/tmp}/pge-check-install.XXXXXX")
if [[ $keep -eq 1 ]]; then
  echo "check-install: keeping $work"
else
  trap 'rm -rf "$work"' EXIT
fi
prefix=$work/prefix
fail() { echo "check-install: FAILED: $*" >&2; exit 1; }
step() { echo "-- check-install: $* (${SECONDS}s)"; }

step "installing into $prefix"
cmake --install "$build" --prefix "$prefix" >"$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }
for f in bin/pge include/pge/world.hpp include/pge/oracle.hpp include/pge/judge.hpp include/pge/scene_io.hpp \
         include/pge/trace_io.hpp lib/cmake/pge/pgeConfig.cmake; do
  [[ -e "$prefix/$f" ]] || fail "$f is not installed"
done
"$prefix/bin/pge" --help >/dev/null || fail "the installed pge --help"

step "every quoted include of an installed header is installed"
leaks=0
while IFS= read -r line; do
  file=${line%%:*}
  name=$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"${line#*:}")
  if [[ ! -f "$prefix/include/$name" ]]; then
    echo "check-install: ${file#"$prefix/"} includes \"$name\", which is not installed" >&2
    leaks=$((leaks + 1))
  fi
done < <(grep -rH '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$prefix/include")
[[ $leaks -eq 0 ]] || fail "$leaks private or missing headers included by public ones"

step "every installed header compiles alone"
cmake -S tests/install -B "$work/headers" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  >"$work/headers.log" 2>&1 || { cat "$work/headers.log"; fail "configuring tests/install"; }
cmake --build "$work/headers" -j "$jobs" >>"$work/headers.log" 2>&1 || { cat "$work/headers.log"; fail "an installed header does not compile alone"; }

step "examples/gate-my-engine against the installed package"
cmake -S examples/gate-my-engine -B "$work/example" -DCMAKE_PREFIX_PATH="$prefix" \
  >"$work/example.log" 2>&1 || { cat "$work/example.log"; fail "configuring examples/gate-my-engine"; }
grep -q "$prefix/lib/cmake/pge" "$work/example/CMakeCache.txt" || fail "the example did not find pge in $prefix"
cmake --build "$work/example" -j "$jobs" >>"$work/example.log" 2>&1 || { cat "$work/example.log"; fail "building examples/gate-my-engine"; }
ctest --test-dir "$work/example" --output-on-failure -j "$jobs" || fail "examples/gate-my-engine's tests"

if [[ $deb -eq 1 ]]; then
  step "cpack -G DEB"
  (cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/deb" >"$work/cpack.log" 2>&1) \
    || { cat "$work/cpack.log"; fail "cpack -G DEB"; }
  shopt -s nullglob
  runtime=("$work"/deb/pge_*.deb)
  dev=("$work"/deb/libpge-dev_*.deb)
  [[ ${#runtime[@]} -eq 1 && ${#dev[@]} -eq 1 ]] || { ls "$work/deb"; fail "expected pge_*.deb and libpge-dev_*.deb"; }
  # Listings first, then grep: grep -q ending a pipe early would fail it under pipefail.
  runtime_files=$(dpkg-deb -c "${runtime[0]}")
  dev_files=$(dpkg-deb -c "${dev[0]}")
  dev_depends=$(dpkg-deb -f "${dev[0]}" Depends)
  grep -q ' \./usr/bin/pge$' <<<"$runtime_files" || fail "pge_*.deb holds no usr/bin/pge"
  grep -q 'libgmp' <<<"$(dpkg-deb -f "${runtime[0]}" Depends)" || fail "pge_*.deb does not depend on GMP"
  for f in include/pge/world.hpp include/pge/judge.hpp include/pge/trace_io.hpp lib/libpge_oracle.a \
           lib/cmake/pge/pgeConfig.cmake lib/cmake/pge/pgeConfigVersion.cmake; do
    grep -q " \./usr/$f\$" <<<"$dev_files" || fail "libpge-dev_*.deb holds no usr/$f"
  done
  for p in libcgal-dev libgmp-dev libboost-dev libfmt-dev nlohmann-json3-dev; do
    grep -q "$p" <<<"$dev_depends" || fail "libpge-dev_*.deb does not depend on $p"
  done
  dpkg-deb -f "${runtime[0]}" Package Version Depends Recommends
  dpkg-deb -f "${dev[0]}" Package Version Depends
fi
step "all checks passed"

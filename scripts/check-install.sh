#!/usr/bin/env bash
# Checks the installable package from a build folder, as a user of it would meet it:
#   1. cmake --install BUILD --prefix into a fresh temporary folder;
#   2. every #include "..." in the installed headers names an installed header (no private
#      header of engine/src, oracle/src or io/src leaks into the public interface);
#   3. every installed header compiles on its own against the installed package (tests/install/);
#   4. examples/gate-my-engine configures, builds and passes its tests against that prefix
#      (CMAKE_PREFIX_PATH), through find_package(pge);
#   5. with --deb, `cpack -G DEB` makes the two Debian packages, and dpkg-deb lists in them the
#      command, the headers, the libraries and the CMake package, and their dependencies;
#   6. with --deb, as root: `dpkg -i` installs both packages, the installed /usr/bin/pge --help
#      exits 0, examples/gate-my-engine configures against /usr (pgeConfig.cmake found in
#      /usr/lib/cmake/pge), and `dpkg --purge` removes them again, also when a check fails (a
#      trap), leaving the machine as it was. Not root: step 6 is skipped, and says so. If either
#      package is installed already, step 6 is skipped too (it would not leave that install be).
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
    -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
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
# The packages this run installed (step 6), purged on any exit; then the temporary folder.
installed=()
cleanup() {
  if [[ ${#installed[@]} -gt 0 ]]; then
    echo "-- check-install: dpkg --purge ${installed[*]}"
    dpkg --purge "${installed[@]}" >"$work/purge.log" 2>&1 || { cat "$work/purge.log" >&2; echo "check-install: dpkg --purge ${installed[*]} failed: remove them by hand" >&2; }
  fi
  if [[ $keep -eq 0 ]]; then rm -rf "$work"; fi
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP
if [[ $keep -eq 1 ]]; then echo "check-install: keeping $work"; fi
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

  already=$(dpkg-query -W -f='${Package} ${db:Status-Abbrev}\n' pge libpge-dev 2>/dev/null | awk '$2 ~ /^.i/ {printf "%s ", $1}' || true)
  if [[ $EUID -ne 0 ]]; then
    step "not root: the packages are not installed (dpkg -i needs root); skipped"
  elif [[ -n "$already" || -e /usr/bin/pge || -e /usr/lib/cmake/pge ]]; then
    step "pge is in /usr already (${already:-files of no package}): dpkg -i skipped, so as to leave that install as it is"
  else
    step "dpkg -i the two packages"
    installed=(pge libpge-dev)  # from here on the trap purges them, installed or half-installed
    dpkg -i "${runtime[0]}" "${dev[0]}" >"$work/dpkg.log" 2>&1 || { cat "$work/dpkg.log"; fail "dpkg -i (a dependency missing? apt-get install the ones named above)"; }
    /usr/bin/pge --help >"$work/pge-help.log" 2>&1 || { cat "$work/pge-help.log"; fail "the installed /usr/bin/pge --help exited non-zero"; }
    grep -q 'Subcommands:' "$work/pge-help.log" || { cat "$work/pge-help.log"; fail "the installed /usr/bin/pge --help shows no subcommands"; }
    step "examples/gate-my-engine configured against /usr"
    cmake -S examples/gate-my-engine -B "$work/example-deb" -DCMAKE_PREFIX_PATH=/usr \
      >"$work/example-deb.log" 2>&1 || { cat "$work/example-deb.log"; fail "configuring examples/gate-my-engine against the installed packages"; }
    grep -q '^pge_DIR:PATH=/usr/lib/cmake/pge$' "$work/example-deb/CMakeCache.txt" \
      || { grep '^pge_DIR' "$work/example-deb/CMakeCache.txt"; fail "the example did not find pge in /usr/lib/cmake/pge"; }
    step "dpkg --purge the two packages"
    names="${installed[*]}"
    dpkg --purge "${installed[@]}" >"$work/purge.log" 2>&1 || { cat "$work/purge.log"; installed=(); fail "dpkg --purge $names"; }
    installed=()
    [[ ! -e /usr/bin/pge && ! -e /usr/lib/cmake/pge ]] || fail "dpkg --purge left /usr/bin/pge or /usr/lib/cmake/pge behind"
  fi
fi
step "all checks passed"

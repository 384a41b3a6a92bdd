#!/usr/bin/env bash
# scripts/build-box2d3.sh CHECKOUT [--build-dir DIR] [--pge-build DIR] [--no-pge]
#
# Builds Box2D v3 from a checkout you already have (nothing is downloaded: clone
# https://github.com/erincatto/box2d yourself) and builds `pge` with it as the peer "box2d3", so
# that `pge compare` puts Box2D v3 beside PGE, Box2D 2.4.1 and Chipmunk:
#
#   scripts/build-box2d3.sh ~/src/box2d
#   build/cli/pge compare fixtures/scenes/peers/peers-gas-1000.json --peers box2d3
#
# Box2D is configured Release, without its samples, unit tests, benchmarks and heavy validation
# (BOX2D_VALIDATE, on by default in a top-level build, checks the whole world every step), and
# built as a static library in DIR (default: CHECKOUT/build-pge). PGE's build directory (default:
# $PGE_BUILD_DIR, else build/) is then configured with PGE_BOX2D3_INCLUDE_DIR and
# PGE_BOX2D3_LIBRARY pointing at it (other options of that build are kept) and `pge` rebuilt.
# The adapter (peers/src/box2d3_sim.cpp) is written against the v3.2 C API (b2Pos positions,
# b2MotionLocks); an older v3 checkout (3.0, 3.1) does not compile with it.
#
# Options:
#   --build-dir DIR  where Box2D is built (default CHECKOUT/build-pge)
#   --pge-build DIR  PGE's build directory (default $PGE_BUILD_DIR or build)
#   --no-pge         build Box2D only, and print the two CMake options to give PGE
#   -h, --help       this text
#
# Exit codes: 0 built; 2 bad command line or CHECKOUT is not a Box2D v3 checkout; otherwise the
# code of the CMake step that failed.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; }
checkout="" build_dir="" pge_build=${PGE_BUILD_DIR:-build} pge=1
while [[ $# -gt 0 ]]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --build-dir) [[ $# -ge 2 ]] || { echo "build-box2d3: --build-dir needs a directory" >&2; exit 2; }; build_dir=$2; shift 2 ;;
    --pge-build) [[ $# -ge 2 ]] || { echo "build-box2d3: --pge-build needs a directory" >&2; exit 2; }; pge_build=$2; shift 2 ;;
    --no-pge) pge=0; shift ;;
    -*) echo "build-box2d3: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) [[ -z $checkout ]] || { echo "build-box2d3: one checkout only (see --help)" >&2; exit 2; }; checkout=$1; shift ;;
  esac
done
[[ -n $checkout ]] || { echo "build-box2d3: give the Box2D v3 checkout (see --help)" >&2; exit 2; }
checkout=$(cd "$checkout" 2>/dev/null && pwd) || { echo "build-box2d3: no directory $1" >&2; exit 2; }
if [[ ! -f $checkout/include/box2d/box2d.h || ! -f $checkout/src/physics_world.c ]]; then
  echo "build-box2d3: $checkout is not a Box2D v3 checkout (no include/box2d/box2d.h and src/physics_world.c)" >&2
  exit 2
fi
build_dir=${build_dir:-$checkout/build-pge}

echo "build-box2d3: configuring Box2D in $build_dir"
mkdir -p "$build_dir"
cmake -S "$checkout" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=OFF \
  -DBOX2D_SAMPLES=OFF -DBOX2D_UNIT_TESTS=OFF -DBOX2D_BENCHMARKS=OFF -DBOX2D_DOCS=OFF -DBOX2D_VALIDATE=OFF \
  > "$build_dir/pge-configure.log" 2>&1 || { cat "$build_dir/pge-configure.log" >&2; exit 1; }
cmake --build "$build_dir" -j "$(nproc)" --target box2d
library=$(find "$build_dir" -name 'libbox2d.a' -print -quit)
[[ -n $library ]] || { echo "build-box2d3: no libbox2d.a under $build_dir after the build" >&2; exit 1; }
options=(-DPGE_BOX2D3_INCLUDE_DIR="$checkout/include" -DPGE_BOX2D3_LIBRARY="$library")
if [[ $pge -eq 0 ]]; then
  echo "build-box2d3: built $library; configure PGE with: ${options[*]}"
  exit 0
fi
echo "build-box2d3: configuring PGE in $pge_build with the box2d3 peer"
if [[ -f $pge_build/CMakeCache.txt ]]; then
  cmake -S . -B "$pge_build" "${options[@]}" > /dev/null
else
  cmake -S . -B "$pge_build" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${options[@]}" > /dev/null
fi
cmake --build "$pge_build" -j "$(nproc)" --target pge
echo "build-box2d3: done; $pge_build/cli/pge compare SCENE now runs box2d3 too (pge compare --help)"

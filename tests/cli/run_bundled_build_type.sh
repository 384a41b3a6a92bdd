#!/usr/bin/env bash
# scripts/run-bundled.sh configures the build directory with the type it already has, and with
# RelWithDebInfo only when it has none (a new directory, or a cache without a type): before
# 242a14d it always passed RelWithDebInfo, so `scripts/measure.sh --no-build` with a Release
# PGE_BUILD_DIR rebuilt it as RelWithDebInfo inside the main job's timing.
# `cmake` is a stand-in on PATH that records its arguments; its build step fails on purpose
# (exit 3) so that the script stops there, before `pge report`.
# Usage: run_bundled_build_type.sh SOURCE_DIR
set -eu
src=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/bin"
cat >"$tmp/bin/cmake" <<'FAKE'
#!/usr/bin/env bash
echo "$*" >>"$PGE_TEST_CMAKE_LOG"
[[ $1 == --build ]] && exit 3
exit 0
FAKE
chmod +x "$tmp/bin/cmake"
# The type configure was given, for a build directory whose cache says $1 (none: no cache).
configured_type() {
  local dir=$tmp/build-$RANDOM
  mkdir -p "$dir"
  case $1 in
    none) ;;
    empty) printf 'CMAKE_BUILD_TYPE:STRING=\n' >"$dir/CMakeCache.txt" ;;
    *) printf 'FOO:BOOL=ON\nCMAKE_BUILD_TYPE:STRING=%s\n' "$1" >"$dir/CMakeCache.txt" ;;
  esac
  : >"$tmp/log"
  local code=0
  PATH="$tmp/bin:$PATH" PGE_TEST_CMAKE_LOG="$tmp/log" PGE_BUILD_DIR="$dir" \
    "$src/scripts/run-bundled.sh" --no-deps --no-screenshot >/dev/null 2>&1 || code=$?
  [[ $code -eq 3 ]] || { echo "FAIL: run-bundled.sh exited $code, expected the stand-in build's 3" >&2; exit 1; }
  sed -n 's/^-S .* -DCMAKE_BUILD_TYPE=\([^ ]*\).*/\1/p' "$tmp/log"
}
check() {
  local got
  got=$(configured_type "$1")
  [[ $got == "$2" ]] || { echo "FAIL: a build directory with type '$1' was configured as '$got', expected '$2'"; exit 1; }
  echo "ok: '$1' -> $2"
}
check none RelWithDebInfo
check empty RelWithDebInfo
check Release Release
check Debug Debug
check RelWithDebInfo RelWithDebInfo

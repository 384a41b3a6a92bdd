#!/usr/bin/env bash
# Seeds the libFuzzer corpora from the fixtures (fuzz/README.md):
#   OUT/reader  every fixtures/**/*.json as it is (good and bad scenes alike) but fixtures/known-failures/
#   OUT/engine  every fixture scene that reads, encoded into fuzz_engine's byte format by
#               pge_fuzz_encode (built in the fuzz build directory)
# Existing files in OUT are kept: libFuzzer adds what it finds to the same directories.
set -euo pipefail

usage() {
  cat <<'USAGE'
Usage: scripts/fuzz-corpus.sh [--build-dir DIR] [--out DIR]
  --build-dir DIR  fuzz build directory holding fuzz/pge_fuzz_encode (default: build-fuzz)
  --out DIR        corpus root; writes DIR/reader and DIR/engine (default: out/fuzz/corpus)
USAGE
}

root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-fuzz"
out="$root/out/fuzz/corpus"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) [[ $# -ge 2 ]] || { echo "fuzz-corpus.sh: --build-dir needs a value" >&2; exit 2; }
                 build=$(cd "$2" 2>/dev/null && pwd) || { echo "fuzz-corpus.sh: no such directory: $2" >&2; exit 2; }
                 shift 2 ;;
    --out) [[ $# -ge 2 ]] || { echo "fuzz-corpus.sh: --out needs a value" >&2; exit 2; }
           out=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "fuzz-corpus.sh: unknown argument: $1 (see --help)" >&2; exit 2 ;;
  esac
done

encoder="$build/fuzz/pge_fuzz_encode"
if [[ ! -x "$encoder" ]]; then
  echo "fuzz-corpus.sh: $encoder not found; build it first:" >&2
  echo "  cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DPGE_LIBFUZZER=ON -DPGE_BUILD_TESTS=OFF" >&2
  echo "  cmake --build build-fuzz --target pge_fuzz_encode" >&2
  exit 2
fi

mkdir -p "$out/reader" "$out/engine"
# Not fixtures/known-failures/: what the engine still fails (docs/rotation.md) would stop every
# campaign at its first input (libFuzzer runs the seeds first and ends at the first finding).
mapfile -t scenes < <(find "$root/fixtures" -name '*.json' -not -path '*/known-failures/*' | sort)
for f in "${scenes[@]}"; do
  # Named after the path below fixtures/, so that scenes/x.json and bad/x.json do not collide.
  rel=${f#"$root/fixtures/"}
  cp "$f" "$out/reader/${rel//\//_}"
done
echo "${#scenes[@]} reader seeds in $out/reader"
# Bad fixtures fail to read and are reported and skipped by the encoder; that is expected.
"$encoder" "$out/engine" "${scenes[@]}" 2>/dev/null

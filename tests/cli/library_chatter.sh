#!/usr/bin/env bash
# Nothing a library prints reaches stdout (issue 22): CGAL's modular gcd writes "UNLUCKY PRIME !!"
# to std::cout, and `pge check --quiet --json /dev/stdout` gave JSON with that line in front.
# The scene (unlucky-prime.json) makes the oracle square-free factorise a contact polynomial
# whose gcd with its derivative is wrong modulo CGAL's first prime: the small disc, 2 m/s
# towards the big one and decelerating at 2 m/s^2, grazes it at t = 1, so the distance minus the
# radii (33554429.5) is (t - 1)^2 and the contact polynomial, doubled and made primitive, is
# (t - 1)^2 ((t - 1)^2 + 67108859); modulo 67108859 it is (t - 1)^4.
# Usage: library_chatter.sh PGE SCENE
set -u
pge=$1; scene=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
"$pge" check "$scene" --quiet --json /dev/stdout > "$dir/out" 2> "$dir/err" || fail "pge check exited with $?"
grep -q "UNLUCKY PRIME !!" "$dir/out" && fail "CGAL's chatter is on stdout: $(head -c 200 "$dir/out")"
grep -q "UNLUCKY PRIME !!" "$dir/err" ||
  fail "CGAL no longer reports an unlucky prime on this scene (the test needs another); stderr: $(cat "$dir/err")"
python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$dir/out" || fail "stdout is not the JSON alone"
# The other way round: sending std::cout to stderr sent --help and --version there too, so
# `pge --help | less` showed nothing. They belong on stdout.
for args in "--help" "run --help" "--version"; do
  # shellcheck disable=SC2086
  "$pge" $args > "$dir/out" 2> "$dir/err" || fail "pge $args exited with $?"
  [[ -s $dir/out && ! -s $dir/err ]] || fail "pge $args: stdout $(wc -c < "$dir/out") bytes, stderr $(wc -c < "$dir/err") bytes"
done
echo "ok: CGAL's UNLUCKY PRIME on stderr, stdout the JSON alone; --help and --version on stdout"

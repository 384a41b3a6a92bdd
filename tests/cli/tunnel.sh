#!/usr/bin/env bash
# Tunnelling is no silent success (issue 22): fast lets the ball lying on a floor fall through it
# (fixtures/scenes/rest/resting-on-floor.json, 0 events); `pge run` names the bodies on one stderr
# line, lists them in its JSON summary and exits 11, robust exits 0; `pge compare` counts the
# fast row's ball as tunnelled and the robust row's not.
# Usage: tunnel.sh PGE EXPECT_ERROR SCENE
set -u
pge=$1; expect_error=$2; scene=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "tunnel.sh: $*" >&2; exit 1; }

"$expect_error" 11 'resting-on-floor.json' 'body "ball" passed through fixed body "floor"' -- \
  "$pge" run "$scene" --solver fast --json "$tmp/fast.json" || fail "pge run --solver fast"
python3 - "$tmp/fast.json" <<'PY' || fail "the JSON summary does not list the tunnel"
import json, sys
t = json.load(open(sys.argv[1]))[0]["tunnels"]
assert len(t) == 1 and t[0]["body"] == "ball" and t[0]["fixed"] == "floor", t
PY
"$pge" run "$scene" --quiet || fail "robust: exit $?, expected 0"

"$pge" compare "$scene" --solvers fast,robust --json "$tmp/rows.json" >/dev/null 2>"$tmp/err.txt" ||
  fail "compare: exit $?; $(cat "$tmp/err.txt")"
python3 - "$tmp/rows.json" <<'PY' || fail "compare's tunnelled column"
import json, sys
rows = {r["label"]: r for r in json.load(open(sys.argv[1]))}
assert rows["pge fast/double"]["tunnelled"] == 1, rows["pge fast/double"]
assert rows["pge robust/double"]["tunnelled"] == 0, rows["pge robust/double"]
PY
echo "tunnel.sh: ok"

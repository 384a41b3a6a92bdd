#!/usr/bin/env bash
# JSON nested 100,000 deep (issue 22): closed, `pge run` and `pge check` crashed (SIGSEGV in
# nlohmann's serializer, describing the value for a message); unclosed, the reader took 206 s and
# printed a "one-line" message of 300 KB. Both must fail at once (the test's CTest TIMEOUT guards
# against a hang; no time is asserted) with exit 3 and one short line naming the file, line and
# column of the first bracket past the 64-level limit. Also: a 100,000-byte key in an expect
# block made a 100 KB message; it is cut to 80 bytes like every quoted value.
# Usage: deep_json.sh PGE EXPECT_ERROR_SCRIPT
set -u
pge=$1; expect_error=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
brackets() { head -c "$2" /dev/zero | tr '\0' "$1"; }
{ brackets '[' 100000; brackets ']' 100000; } > "$dir/closed.json"
brackets '[' 100000 > "$dir/unclosed.json"
# In a body: the message names it too.
{ printf '{"format": "pge-scene/1",\n "bodies": [{"id": "deep", "circle": {"radius": '; brackets '{' 100000; } \
  > "$dir/in-body.json"
for command in run check; do
  for file in closed unclosed in-body; do
    path=$dir/$file.json
    where="$path:1:65:"
    needles=()
    [[ $file == in-body ]] && { where="$path:2:"; needles=('body "deep" (bodies[0])'); }
    "$expect_error" 3 "$where" "${needles[@]}" "nested more than 64 levels deep" -- "$pge" "$command" "$path" ||
      fail "pge $command $file.json"
    message=$("$pge" "$command" "$path" 2>&1 >/dev/null)
    [[ ${#message} -le 500 ]] || fail "pge $command $file.json: a message of ${#message} bytes"
  done
done
# A 100,000-byte key in an expect block (read by `pge check`, not the reader) is cut the same way.
{ printf '{"format": "pge-scene/1", "bodies": [], "expect": {"'; head -c 100000 /dev/zero | tr '\0' k; printf '": 1}}'; } \
  > "$dir/expect-key.json"
"$expect_error" 3 "unknown key \"kkkk" "k...\"" -- "$pge" check "$dir/expect-key.json" || fail "pge check expect-key.json"
message=$("$pge" check "$dir/expect-key.json" 2>&1 >/dev/null)
[[ ${#message} -le 500 ]] || fail "pge check expect-key.json: a message of ${#message} bytes"
echo "ok: 100,000 levels deep, closed, unclosed and in a body, and a huge expect key: exit 3, one short line"

# Sourced by the pge compare tests: installed_peers OUT ERR prints each peer that has its 6 rows
# (a setting per rate and iteration count) in the table OUT, and fails (through the script's own
# fail) when a peer has rows but not 6, or rows though ERR says it is not installed.
installed_peers() {
  for peer in box2d chipmunk; do
    rows=$(grep -c "^| $peer | $peer " "$1")
    if grep -q "$peer is not installed" "$2"; then
      [ "$rows" -eq 0 ] || fail "$peer skipped but has rows"
    else
      [ "$rows" -eq 6 ] || fail "expected 6 $peer rows, got $rows"
      echo "$peer"
    fi
  done
}

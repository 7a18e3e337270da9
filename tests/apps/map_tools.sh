#!/bin/sh
# The map file through the apps: dpcr-sim saves one, dpcr-map checks, shows and exports it,
# dpcr-sim and dpcr-replay start a second session from it and save again; a corrupt, truncated or
# wrong-profile file gives one error line and a non-zero exit.
# Usage: map_tools.sh DPCR_SIM DPCR_REPLAY DPCR_MAP
set -eu
SIM=$1; REPLAY=$2; MAP=$3
T=$(mktemp -d "${TMPDIR:-/tmp}/dpcr_map_tools_XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$SIM" --world apartment --minutes 2 --out "$T/a" --save-map "$T/maps/a.dpcr" --emit-device "$T/dev" 2> "$T/sim.log" || fail "dpcr-sim --save-map"
grep -q "map saved to $T/maps/a.dpcr" "$T/sim.log" || fail "dpcr-sim did not report the save"
[ ! -e "$T/maps/a.dpcr.tmp" ] || fail "temp file left behind"

"$MAP" check "$T/maps/a.dpcr" > "$T/check.out" 2>&1 || fail "dpcr-map check refused a saved map"
[ ! -s "$T/check.out" ] || fail "dpcr-map check printed something"
"$MAP" info "$T/maps/a.dpcr" > "$T/info.out" || fail "dpcr-map info"
grep -q "profile vacuum" "$T/info.out" || fail "info: no profile"
grep -q "^check:    ok" "$T/info.out" || fail "info: no CRC status"
grep -q "^graph: " "$T/info.out" || fail "info: no graph counts"
"$MAP" export "$T/maps/a.dpcr" --out "$T/export" 2> /dev/null || fail "dpcr-map export"
for f in map.pgm map.yaml map.png; do [ -s "$T/export/$f" ] || fail "export: no $f"; done
cmp -s "$T/export/map.pgm" "$T/a/map.pgm" || fail "exported PGM differs from the run's"

"$SIM" --world apartment --minutes 2 --seed 2 --out "$T/b" --load-map "$T/maps/a.dpcr" --save-map "$T/maps/b.dpcr" 2> "$T/sim2.log" ||
  fail "dpcr-sim --load-map"
"$MAP" check "$T/maps/b.dpcr" || fail "second session's map"
# Its accuracy is measured from its first fix (before it the pose is a guess): start-aligned at
# the guess, LocErr_ave read metres.
if grep -q '"relocalisations": [1-9]' "$T/b/metrics.json"; then
  grep -q '"from_s":' "$T/b/metrics.json" || fail "second session: accuracy not measured from the fix"
  loc=$(grep -m1 '"loc_err_ave_m":' "$T/b/metrics.json" | tr -dc '0-9.')
  awk -v l="$loc" 'BEGIN { exit !(l < 0.5) }' || fail "second session: LocErr_ave $loc m from its fix"
fi
"$REPLAY" --uart "$T/dev/lidar.uart" --candump "$T/dev/wheels.log" --out "$T/c" --load-map "$T/maps/b.dpcr" \
  --save-map "$T/maps/c.dpcr" 2> /dev/null || fail "dpcr-replay --load-map"
"$MAP" check "$T/maps/c.dpcr" || fail "replay session's map"
# Localise-only at an unknown start (no --start-pose): the robot finds itself, the map is unchanged.
"$REPLAY" --uart "$T/dev/lidar.uart" --candump "$T/dev/wheels.log" --out "$T/d" --load-map "$T/maps/a.dpcr" \
  --localise-only --save-map "$T/maps/d.dpcr" 2> /dev/null || fail "dpcr-replay --localise-only"
cmp -s "$T/maps/a.dpcr" "$T/maps/d.dpcr" || fail "localise-only changed the map"
grep -q '"relocalisations": [1-9]' "$T/d/metrics.json" || fail "localise-only: the start was not found"
if "$SIM" --world apartment --minutes 0.1 --out "$T/x" --localise-only 2> /dev/null; then fail "--localise-only without a map"; fi

# Bad files: one line on stderr, exit 1, and dpcr-map check says no without a word.
cp "$T/maps/a.dpcr" "$T/maps/flipped.dpcr"
printf '\377' | dd of="$T/maps/flipped.dpcr" bs=1 seek=700 conv=notrunc 2> /dev/null
head -c 500 "$T/maps/a.dpcr" > "$T/maps/cut.dpcr"
printf 'not a map' > "$T/maps/text.dpcr"
for bad in flipped:CRC-32 cut:truncated text:magic; do
  name=${bad%%:*}; word=${bad#*:}
  if "$SIM" --world apartment --minutes 0.1 --out "$T/x" --load-map "$T/maps/$name.dpcr" 2> "$T/err.log"; then fail "$name loaded"; fi
  [ "$(wc -l < "$T/err.log")" -eq 1 ] || fail "$name: not one error line: $(cat "$T/err.log")"
  grep -q "$word" "$T/err.log" || fail "$name: error does not say $word: $(cat "$T/err.log")"
  if "$MAP" check "$T/maps/$name.dpcr" > "$T/check.out" 2>&1; then fail "dpcr-map check accepted $name"; fi
  [ ! -s "$T/check.out" ] || fail "dpcr-map check printed something for $name"
done
if "$REPLAY" --uart "$T/dev/lidar.uart" --candump "$T/dev/wheels.log" --profile building --out "$T/y" \
  --load-map "$T/maps/a.dpcr" 2> "$T/err.log"; then fail "a vacuum map loaded into the building profile"; fi
[ "$(wc -l < "$T/err.log")" -eq 1 ] && grep -q "another profile" "$T/err.log" || fail "wrong profile: $(cat "$T/err.log")"
echo "map tools: save, check, info, export, second sessions and bad files as expected"

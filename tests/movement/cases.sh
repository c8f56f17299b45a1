#!/usr/bin/env bash
# The case table of mesh movement (docs/movement.md, issue 12): every motion of the table run in
# one step from the original mesh, at P3, by the spring mover and by the
# baselines `--method idw` and `--method rbf`; prints
# a Markdown table (certified, inverted cells, worst-cell ratio, max angle, first-layer drift,
# move time). Usage: bash tests/movement/cases.sh [OUT_DIR]   (about 2 minutes, release build)
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:-target/movement-cases}"
mkdir -p "$out"
cargo build --release --quiet -p xtask
xtask=target/release/xtask
m=fixtures/motions

# case | snapshot key | motion arguments | label
rows=(
  "fixtures/movement/30p30n-far50.toml|far50|--motion $m/30p30n-rotate90.toml|30P30N, +90° then (−10, 10)"
  "fixtures/movement/30p30n-far50.toml|far50|--motion $m/30p30n-rotate-90.toml|30P30N, −90° then (10, −10)"
  "fixtures/movement/30p30n-far50.toml|far50|--motion $m/30p30n-rotate180.toml|30P30N, 180°"
  "fixtures/movement/30p30n-far50.toml|far50|--motion $m/30p30n-flap10.toml|30P30N, flap +10°"
  "fixtures/movement/30p30n-far50.toml|far50|--motion $m/30p30n-flap-10.toml|30P30N, flap −10°"
  "fixtures/movement/30p30n-far50.toml|far50|--motion $m/30p30n-slat10.toml|30P30N, slat 10° towards the main element"
  "naca0012|naca|--motion $m/naca0012-grow.toml|NACA0012, ×1.5 and 5 chords left"
  "naca0012|naca|--motion $m/naca0012-8bumps.toml|NACA0012, 8 bumps of 1 % chord"
  "naca0012|naca|--rotate -10 --about 0.25,0|NACA0012 R20, pitch 10°"
  "naca0012|naca|--rotate -30 --about 0.25,0|NACA0012 R20, pitch 30°"
  "naca0012|naca|--rotate -60 --about 0.25,0|NACA0012 R20, pitch 60°"
  "naca0012|naca|--rotate -90 --about 0.25,0|NACA0012 R20, pitch 90°"
  "fixtures/movement/naca0012-far5.toml|far5|--rotate -10 --about 0.25,0|NACA0012 R5, pitch 10°"
  "fixtures/movement/naca0012-far5.toml|far5|--rotate -30 --about 0.25,0|NACA0012 R5, pitch 30°"
  "fixtures/movement/naca0012-far5.toml|far5|--rotate -60 --about 0.25,0|NACA0012 R5, pitch 60°"
  "fixtures/movement/naca0012-far5.toml|far5|--rotate -90 --about 0.25,0|NACA0012 R5, pitch 90°"
)

echo "| motion | mover | P3 certified | inverted | worst-cell ratio | max angle before → after | first-layer height / angle drift | Newton steps | move time |"
echo "|---|---|---|---|---|---|---|---|---|"
for row in "${rows[@]}"; do
  IFS='|' read -r case key args label <<< "$row"
  snap="$out/$key.bin"
  [ -f "$snap" ] || "$xtask" mesh "$case" --order 3 --snapshot "$snap" --quiet > /dev/null
  for mover in default idw rbf; do
    case "$mover" in
      idw | rbf) flag="--method $mover" ;;
      *) flag="" ;;
    esac
    report="$out/${key}-$(echo "$label" | tr -c 'A-Za-z0-9' '_')-$mover.json"
    rm -f "$report"
    # exit 2 (a mesh made but invalid) still writes the report: its row says what failed
    # shellcheck disable=SC2086
    "$xtask" move "$case" --snapshot "$snap" $args $flag --order 3 \
        --out "$out/moved.msh" --report "$report" --quiet > /dev/null 2> "$out/err.txt" || true
    if [ -f "$report" ]; then
      python3 - "$report" "$label" "$mover" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); m = r["movement"]; q = r["quality"]
fl = m.get("first_layer") or [0, 0]
newton = ((m.get("springs") or {}).get("newton") or {}).get("iterations", "–")
valid = "yes" if q["certified"] and q["invalid_cells"] == 0 else f"NO ({q['invalid_cells']} invalid)"
print(f"| {sys.argv[2]} | {sys.argv[3]} | {valid} | {m['inverted_linear_cells']} "
      f"| {m['worst_cell_ratio']:.3f} | {m['before']['max_angle_deg']:.1f}° → {m['after']['max_angle_deg']:.1f}° "
      f"| {fl[0]:.1e} / {fl[1]:.2f}° | {newton} | {r['timings_s']['move']:.2f} s |")
PY
    else
      echo "| $label | $mover | fails: $(head -c 200 "$out/err.txt" | tr '\n' ' ') | | | | | | |"
    fi
  done
done

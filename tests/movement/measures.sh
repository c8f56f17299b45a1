#!/usr/bin/env bash
# The four measures of issue 43, cell by cell at P3 (tests/movement/measures.py, Gmsh's minSJ and
# minSICN): every motion below moved by the spring mover and by the baselines IDW and thin-plate
# RBF, from the same saved layered mesh; with the move's and the mesh's wall times and peak
# memory. Prints a Markdown table. Usage: bash tests/movement/measures.sh [OUT_DIR]   (a few
# minutes, release build; needs the checkers' venv of tests/python/install.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:-target/movement-measures}"
mkdir -p "$out"
cargo build --release --quiet -p curvemesh-cli
bin=target/release/curvemesh
py=.venv-checkers/bin/python
m=fixtures/motions

# case | key | motion arguments | label
rows=(
  "naca0012|naca|--rotate -90 --about 0.25,0|NACA0012 R20, pitch 90°"
  "fixtures/movement/naca0012-far5.toml|far5|--rotate -90 --about 0.25,0|NACA0012 R5, pitch 90°"
  "naca0012|naca|--rotate 180 --about 0.25,0|NACA0012 R20, exactly 180°"
  "30p30n|30p30n|--motion $m/30p30n-flap10.toml|30P30N flap +10°"
  "30p30n|30p30n|--motion $m/30p30n-slat10.toml|30P30N slat 10°"
  "30p30n|30p30n|--motion $m/30p30n-slat-flap10.toml|30P30N slat + flap"
  "fixtures/movement/30p30n-far50.toml|far50|--motion $m/30p30n-rotate180-mid.toml|30P30N R50, exactly 180° about (0.5, 0)"
  "fixtures/movement/naca0012-far5.toml|far5|--rotate -30 --about 0.25,0|NACA0012 R5, pitch 30°"
  "fixtures/movement/naca0012-far5.toml|far5|--rotate -60 --about 0.25,0|NACA0012 R5, pitch 60°"
  "naca0012|naca|--rotate -60 --about 0.25,0|NACA0012 R20, pitch 60°"
  "naca0012|naca|--motion $m/naca0012-8bumps.toml|NACA0012, 8 bumps of 1 % chord"
  "30p30n|30p30n|--motion $m/30p30n-flap-10.toml|30P30N flap −10°"
  "fixtures/movement/30p30n-far50.toml|far50|--motion $m/30p30n-rotate90.toml|30P30N R50, 90° then (−10, 10)"
  "two-element|two-element|--motion $m/two-element.toml|two-element, flap 5° and a bump"
)

# Runs a command quietly: its wall time in seconds and its peak memory (resident set) in MB.
timed() {
  python3 - "$@" <<'PY'
import resource, subprocess, sys, time
t = time.perf_counter()
subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
print(f"{time.perf_counter() - t:.2f} {kb / 1024:.0f}")
PY
}

echo "| motion (P3) | mover | lin | sj | sicn | edge | inverted | move | mesh | move memory | mesh memory |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for row in "${rows[@]}"; do
  IFS='|' read -r case key args label <<< "$row"
  read -r mesh_time mesh_mb < <(timed "$bin" mesh "$case" --order 3 --out "$out/$key.msh" \
      --snapshot "$out/$key.bin" --quiet)
  for mover in springs idw "rbf --kernel thin-plate"; do
    # shellcheck disable=SC2086
    read -r move_time move_mb < <(timed "$bin" move "$case" --snapshot "$out/$key.bin" $args \
        --method $mover --order 3 --out "$out/moved.msh" --report "$out/moved.json" --quiet)
    "$py" tests/movement/measures.py "$out/$key.msh" "$out/moved.msh" | python3 -c "
import json, sys
r = json.loads(sys.stdin.read())
print('| $label | ${mover%% *} | ' + ' | '.join(f'{r[k]:.3f}' for k in ['lin', 'sj', 'sicn', 'edge'])
      + f\" | {r['inverted']} | $move_time s | $mesh_time s | $move_mb MB | $mesh_mb MB |\")"
  done
done

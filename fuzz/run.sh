#!/usr/bin/env bash
# Runs every fuzz target (cargo fuzz, libFuzzer) for a bounded time each. Not part of CI.
#
#   bash fuzz/run.sh            # 60 s per target
#   bash fuzz/run.sh 600        # 10 min per target
#   bash fuzz/run.sh 60 msh     # one target
#
# Needs cargo-fuzz (`cargo install cargo-fuzz`). It wants a nightly compiler; on a stable
# toolchain RUSTC_BOOTSTRAP=1 unlocks the flags it uses. Corpora grow in
# <crate>/fuzz/corpus/<target> (seeded from fixtures/), crashes land in
# <crate>/fuzz/artifacts/<target>; turn each into a named regression test in the crate's
# own tests and fix it. Exit status: 0 when no target crashed.
set -euo pipefail
seconds="${1:-60}"
only="${2:-}"
root="$(cd "$(dirname "$0")/.." && pwd)"
export RUSTC_BOOTSTRAP=1
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target/fuzz}"

# crate folder, target, seed files
targets=(
  "crates/geom-curve airfoil_dat fixtures/geometry/*.dat fixtures/geometry/30p30n/*.dat crates/geom-curve/tests/data/*.dat"
  "crates/mesh-io msh crates/mesh-io/tests/data/*.msh"
  "crates/mesh-io stl crates/mesh-io/tests/data/*.stl"
  "crates/mesh-io snapshot crates/mesh-io/tests/data/*.snap"
  "crates/curvemesh case_toml fixtures/cases/*.toml"
  "crates/curvemesh motion_toml fixtures/motions/*.toml"
  "crates/tet-fill fill_points"
)
failed=()
for entry in "${targets[@]}"; do
  read -r dir target seeds <<<"$entry"
  [[ -n "$only" && "$only" != "$target" ]] && continue
  corpus="$root/$dir/fuzz/corpus/$target"
  mkdir -p "$corpus"
  (cd "$root" && for f in $seeds; do [[ -f "$f" ]] && cp -n "$f" "$corpus/" || true; done)
  echo "== $dir: $target for ${seconds}s"
  if ! (cd "$root/$dir/fuzz" && cargo fuzz run -O "$target" "$corpus" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536); then
    failed+=("$target")
  fi
done
if ((${#failed[@]})); then
  echo "crashes in: ${failed[*]} (see <crate>/fuzz/artifacts/)" >&2
  exit 1
fi
echo "no crashes"

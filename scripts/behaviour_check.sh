#!/usr/bin/env bash
# Runs every scenario in scenarios/ with a base build and with this checkout's build and
# compares telemetry and summaries (examples/compare_runs.rs says what counts as the same).
# For changes that must not change behaviour (refactors).
#
#   scripts/behaviour_check.sh REV        # base: the commit REV, built in a worktree
#   scripts/behaviour_check.sh --bin PATH # base: an already built wingman binary
#
# Plots and saved frames are turned off (they do not feed back into the run). Outputs go to
# target/behaviour/{base,new}/<scenario>/.
set -euo pipefail
cd "$(dirname "$0")/.."
export NODEVICE_SELECT=1

case "${1:-}" in
  --bin) base_bin=$(realpath "$2") ;;
  "" | -h | --help) sed -n '2,10p' "$0"; exit 2 ;;
  *)
    tree=target/behaviour/base-tree
    rm -rf "$tree"; git worktree prune
    git worktree add --detach "$tree" "$1" >/dev/null
    (cd "$tree" && cargo build --release --quiet --bin wingman --target-dir ../base-target)
    base_bin=$(realpath target/behaviour/base-target/release/wingman)
    git worktree remove --force "$tree"
    ;;
esac
cargo build --release --quiet --bin wingman --example compare_runs

run_all() { # BINARY OUT_DIR
  for scenario in scenarios/*.toml; do
    name=$(basename "$scenario" .toml)
    "$1" run "$scenario" --out "$2/$name" --quiet \
      --set output.plots=false --set output.frames_every=0 || echo "$name: exit $?"
  done
}
rm -rf target/behaviour/base target/behaviour/new
run_all "$base_bin" target/behaviour/base
run_all target/release/wingman target/behaviour/new
target/release/examples/compare_runs target/behaviour/base target/behaviour/new

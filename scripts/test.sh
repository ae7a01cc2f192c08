#!/usr/bin/env bash
# Runs the whole test suite, GPU tests included, on any machine: a real GPU where there
# is one, Mesa's software Vulkan (lavapipe) elsewhere. On Debian it installs lavapipe and
# Xvfb (for the viewer's test) when they are missing (as root, or through sudo).
set -euo pipefail
cd "$(dirname "$0")/.."

source scripts/gpu_setup.sh

if [ -z "${ATMOS_SKIP_GPU_TESTS:-}" ]; then
  ensure_lavapipe "or set ATMOS_SKIP_GPU_TESTS=1"
  # The viewer's test opens its window on a virtual X server (xvfb-run).
  if ! command -v xvfb-run >/dev/null; then
    install_packages "a virtual X server for the viewer test" "xvfb xauth" \
      "or set ATMOS_SKIP_GPU_TESTS=1"
  fi
fi
use_lavapipe_without_gpu
give_runtime_dir

log=$(mktemp)
# Each test that skips at run time appends `binary::test: reason` here
# (crates/app/tests/common/skip.rs).
skipped=$(mktemp)
trap 'rm -f "$log" "$skipped"' EXIT
export ATMOS_SKIPPED_TESTS="$skipped"
set +e
cargo test --workspace "$@" 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
set -e
# The skipped tests, once each with their first reason, then one closing line for the
# whole suite: a skipped test ends as passed for cargo, so it is counted out of those.
awk -F': ' '!seen[$1]++ { print "skipped: " $0 }' "$skipped"
skips=$(awk -F': ' '!seen[$1]++' "$skipped" | wc -l)
awk -v skips="$skips" '
  /^test result:/ { for (i = 1; i <= NF; i++) { if ($(i+1) ~ /^passed/) p += $i; if ($(i+1) ~ /^failed/) f += $i } }
  END { printf "tests: %d passed, %d failed, %d skipped\n", p - skips, f, skips }' "$log"
exit "$status"

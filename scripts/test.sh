#!/usr/bin/env bash
# Runs the whole test suite, GPU tests included, on any machine: a real GPU where there
# is one, Mesa's software Vulkan (lavapipe) elsewhere. On Debian it installs lavapipe and
# Xvfb (for the viewer's test) when they are missing (as root, or through sudo).
set -euo pipefail
cd "$(dirname "$0")/.."

# Installs the Debian `packages` for `what` (as root, or through sudo); with neither, says
# that `missing` is missing and stops.
install_for_tests() {
  local what=$1 missing=$2 packages=$3 sudo
  if [ "$(id -u)" = 0 ]; then sudo=""; elif command -v sudo >/dev/null; then sudo="sudo"; else
    echo "$missing is missing: install $packages (Debian), or set ATMOS_SKIP_GPU_TESTS=1" >&2
    exit 1
  fi
  echo "Installing $what: $packages" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $packages >/dev/null
}

lavapipe=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
if [ ! -f "$lavapipe" ] && [ -z "${ATMOS_SKIP_GPU_TESTS:-}" ]; then
  install_for_tests "software Vulkan for the GPU tests" "Software Vulkan" "mesa-vulkan-drivers libvulkan1"
fi
# The viewer's test opens its window on a virtual X server (xvfb-run).
if ! command -v xvfb-run >/dev/null && [ -z "${ATMOS_SKIP_GPU_TESTS:-}" ]; then
  install_for_tests "a virtual X server for the viewer test" "Xvfb" "xvfb xauth"
fi
# Without a real GPU, fail loudly if lavapipe is missing rather than fall back to GL.
if [ -f "$lavapipe" ] && ! ls /usr/share/vulkan/icd.d/ | grep -qv lvp_icd; then
  export WGPU_BACKEND="${WGPU_BACKEND:-vulkan}"
  export VK_ICD_FILENAMES="${VK_ICD_FILENAMES:-$lavapipe}"
fi
# lavapipe asks for a runtime directory; give it a private one rather than print errors.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  export XDG_RUNTIME_DIR="${TMPDIR:-/tmp}/atmos-runtime-$(id -u)"
  mkdir -p -m 700 "$XDG_RUNTIME_DIR"
fi

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

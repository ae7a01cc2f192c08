#!/usr/bin/env bash
# The README's first command: renders the default scene to sky.png on any machine, on a
# real GPU where there is one and on Mesa's software Vulkan (lavapipe) elsewhere, which
# it installs on Debian when it is missing (as root, or through sudo).
#
#   scripts/render.sh [FLAGS of atmos render]
#
# Flags are added to the default scene's (`--model bruneton`, `--width 640`); `--scene`
# and `--out` replace the scene file and sky.png (in the current folder). It prints what
# went wrong, if anything, and the line saying what was written.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/gpu_setup.sh"

# Without lavapipe a real GPU may still do, and atmos says what is missing if not.
ensure_lavapipe || true
use_lavapipe_without_gpu
give_runtime_dir

scene=(--scene "$root/assets/scenes/default.toml")
out=(--out sky.png)
for arg in "$@"; do
  case $arg in
    --scene | --scene=*) scene=() ;;
    --out | --out=*) out=() ;;
  esac
done

if [ ! -x "${CARGO_TARGET_DIR:-$root/target}/release/atmos" ]; then
  echo "Building atmos (the first build takes a few minutes)" >&2
fi
exec cargo run --manifest-path "$root/Cargo.toml" --release --quiet -p atmos -- \
  render "${scene[@]}" "$@" "${out[@]}"

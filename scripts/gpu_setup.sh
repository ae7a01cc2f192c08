# The GPU set-up that scripts/render.sh and scripts/test.sh share; sourced, not run.
# On Debian it installs Mesa's software Vulkan (lavapipe) when it is missing, runs on
# lavapipe where no real GPU is present, and gives lavapipe a runtime directory so that
# it prints nothing.

lavapipe_icd=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json

# install_packages WHAT PACKAGES [ELSE]: installs the Debian PACKAGES for WHAT (as root,
# or through sudo). Without apt-get, or without root and sudo, says what to install (and
# ELSE, another way out) and returns 1.
install_packages() {
  local what=$1 packages=$2 alternative=${3:+, $3} sudo=""
  if ! command -v apt-get >/dev/null; then
    echo "$what is missing: install $packages (Debian names)$alternative" >&2
    return 1
  fi
  if [ "$(id -u)" != 0 ]; then
    if ! command -v sudo >/dev/null; then
      echo "$what is missing: as root, apt-get install $packages$alternative" >&2
      return 1
    fi
    sudo=sudo
  fi
  echo "Installing $what: $packages" >&2
  # apt's own chatter (debconf's notes among it) is shown only when the install fails.
  local log status=0
  log=$(mktemp)
  { $sudo apt-get update -qq &&
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
      $packages; } >"$log" 2>&1 || status=$?
  if [ "$status" != 0 ]; then
    cat "$log" >&2
    echo "installing $packages failed" >&2
  fi
  rm -f "$log"
  return "$status"
}

# Whether this machine has a real GPU: a render node (Mesa, AMD, Intel, NVIDIA), NVIDIA's
# own device files, or WSL's GPU.
has_real_gpu() {
  compgen -G '/dev/dri/renderD*' >/dev/null || [ -e /dev/nvidia0 ] || [ -e /dev/dxg ]
}

# ensure_lavapipe [ELSE]: installs lavapipe on Linux when it is missing (see
# install_packages for ELSE); returns 1 when it stays missing.
ensure_lavapipe() {
  if [ "$(uname -s)" != Linux ] || [ -f "$lavapipe_icd" ]; then
    return 0
  fi
  install_packages "Mesa's software Vulkan (lavapipe)" "mesa-vulkan-drivers libvulkan1" "${1:-}"
}

# Without a real GPU, runs on lavapipe alone: the Vulkan loader then does not try the
# drivers of absent hardware, and wgpu does not try GL. Variables already set are kept.
use_lavapipe_without_gpu() {
  if [ -f "$lavapipe_icd" ] && ! has_real_gpu; then
    export WGPU_BACKEND="${WGPU_BACKEND:-vulkan}"
    export VK_ICD_FILENAMES="${VK_ICD_FILENAMES:-$lavapipe_icd}"
  fi
}

# Mesa's Vulkan device-selection layer looks for a Wayland display in XDG_RUNTIME_DIR and
# prints an error when it is unset or no directory; a private one keeps it quiet.
give_runtime_dir() {
  if [ -n "${XDG_RUNTIME_DIR:-}" ] && [ -d "$XDG_RUNTIME_DIR" ]; then
    return 0
  fi
  local dir="${TMPDIR:-/tmp}/atmos-runtime-$(id -u)"
  if ! mkdir -p -m 700 "$dir" 2>/dev/null || [ ! -O "$dir" ]; then
    dir=$(mktemp -d)
  fi
  export XDG_RUNTIME_DIR="$dir"
}

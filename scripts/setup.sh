#!/usr/bin/env bash
# Set up humanoidgen on a fresh Debian/Ubuntu machine: the Debian packages MuJoCo needs to render offscreen
# through EGL (Mesa's software renderer when there is no GPU) and libseccomp (the plan worker's syscall
# filter), then the Python package and its test tools.
set -euo pipefail
cd "$(dirname "$0")/.."

DEB_PACKAGES=(libegl1 libgl1-mesa-dri libseccomp2)
missing=()
for p in "${DEB_PACKAGES[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  if command -v apt-get >/dev/null 2>&1; then
    SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    echo "Installing Debian packages: ${missing[*]}"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
  else
    echo "Please install the equivalents of: ${missing[*]} (EGL and Mesa's DRI drivers) with your package manager." >&2
  fi
fi

PYTHON="${PYTHON:-python3}"
# Policy learning needs torch + torchvision (+ diffusers, gymnasium): from PyPI that is the CUDA build, about
# 5.6 GB. HGEN_TORCH_INDEX=https://download.pytorch.org/whl/cpu installs the CPU build (about 1.1 GB) of both
# from that index first (one index for both keeps them a matching pair); HGEN_NO_POLICY=1 skips them.
# The ray extra is for `--ray` (collection and benchmarks on a Ray cluster) and its tests.
EXTRAS="dev,policy,ray"
if [ "${HGEN_NO_POLICY:-0}" = "1" ]; then
  EXTRAS="dev,ray"
elif [ -n "${HGEN_TORCH_INDEX:-}" ]; then
  "$PYTHON" -m pip install --disable-pip-version-check -q torch torchvision --index-url "$HGEN_TORCH_INDEX"
fi
"$PYTHON" -m pip install --disable-pip-version-check -q -e ".[$EXTRAS]"
# LeRobot (training LeRobot's policies on our exports, evaluating them in our tasks) in its own environment,
# .venv-lerobot: it pins an older torch. HGEN_NO_LEROBOT=1 (or HGEN_NO_POLICY=1) skips it and its test.
if [ "${HGEN_NO_POLICY:-0}" != "1" ] && [ "${HGEN_NO_LEROBOT:-0}" != "1" ]; then
  PYTHON="$PYTHON" bash scripts/setup_lerobot.sh
fi
echo "humanoidgen is installed. Try: hgen render --out scene.png"

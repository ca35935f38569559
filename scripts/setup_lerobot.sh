#!/usr/bin/env bash
# The LeRobot road's own environment: .venv-lerobot holds humanoidgen with LeRobot 0.4.4 (the newest the index
# serves). LeRobot pins torch<2.11 and diffusers<0.36, older than what the main environment resolves to, so it
# is kept apart rather than forcing the main environment back (docs/guides/lerobot.md says why). In it:
#   .venv-lerobot/bin/lerobot-train ...           train LeRobot's diffusion or ACT on `hgen dataset export --lerobot`
#   .venv-lerobot/bin/hgen policy eval CKPT ...   evaluate the checkpoint in our tasks
# The test tests/test_lerobot_road.py runs there through this environment's python. HGEN_LEROBOT_VENV moves it.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV="${HGEN_LEROBOT_VENV:-.venv-lerobot}"
PYTHON="${PYTHON:-python3}"
if [ ! -x "$VENV/bin/python" ]; then
  "$PYTHON" -m venv "$VENV"
fi
# The same torch index choice as scripts/setup.sh (HGEN_TORCH_INDEX: a CPU-only build from that index).
if [ -n "${HGEN_TORCH_INDEX:-}" ]; then
  "$VENV/bin/pip" install --disable-pip-version-check -q "torch<2.11" "torchvision<0.26" --index-url "$HGEN_TORCH_INDEX"
fi
"$VENV/bin/pip" install --disable-pip-version-check -q -e ".[policy,lerobot]"
echo "LeRobot's environment is ready: $VENV/bin/lerobot-train, $VENV/bin/hgen"

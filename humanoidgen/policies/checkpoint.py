"""Checkpoint files. Two kinds:

    RUN/checkpoints/epoch_0100.pt   what inference needs: policy name, config, the task and the recording
                                    settings it was trained on, the EMA weights (normalizer included)
    RUN/latest.pt                   everything to resume training: also the raw weights, the EMA state,
                                    optimizer, learning-rate schedule, loss history and RNG state

Both are written to a temporary name and renamed, so an interrupt never leaves half a file."""

from __future__ import annotations

import os
from pathlib import Path

import torch

FORMAT = "humanoidgen-policy"
VERSION = 1
LATEST = "latest.pt"


class CheckpointError(ValueError):
    pass


def checkpoint_dir(run: Path) -> Path:
    return Path(run) / "checkpoints"


def epoch_path(run: Path, epoch: int) -> Path:
    return checkpoint_dir(run) / f"epoch_{epoch:04d}.pt"


def save(path: Path, payload: dict) -> None:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    torch.save({"format": FORMAT, "version": VERSION, **payload}, tmp)
    os.replace(tmp, path)


def read(path: Path) -> dict:
    path = Path(path)
    if not path.is_file():
        raise CheckpointError(f"no checkpoint at {path}")
    try:
        ckpt = torch.load(path, map_location="cpu", weights_only=True)
    except Exception as exc:  # noqa: BLE001 - a file torch cannot read is not a checkpoint of ours
        raise CheckpointError(f"{path} is not a readable checkpoint ({type(exc).__name__})") from None
    if not isinstance(ckpt, dict) or ckpt.get("format") != FORMAT:
        raise CheckpointError(f"{path} is not a humanoidgen policy checkpoint")
    if ckpt.get("version") != VERSION:
        raise CheckpointError(f"{path} has checkpoint version {ckpt.get('version')}, this code reads {VERSION}")
    return ckpt


def run_checkpoints(run: Path) -> list[Path]:
    """A run's kept checkpoints, oldest first; a checkpoint file itself is a run of one."""
    run = Path(run)
    if run.is_file():
        return [run]
    found = sorted(checkpoint_dir(run).glob("epoch_*.pt"))
    if not found:
        raise CheckpointError(f"{run} has no checkpoints (checkpoints/epoch_*.pt); train with: hgen policy train "
                              f"--out {run}")
    return found


def load_policy(path: Path, device: str = "cpu"):
    """(policy in eval mode with its EMA weights, the checkpoint's meta)."""
    from humanoidgen.policies.registry import policy_type

    ckpt = read(path)
    ptype = policy_type(ckpt["policy"])
    cfg = ptype.config_cls.model_validate(ckpt["config"])
    model = ptype.model_cls()(cfg)
    model.load_state_dict(ckpt["weights"])
    return model.to(device).eval(), ckpt["meta"]

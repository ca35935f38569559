"""A LeRobot-trained policy acting in this project's tasks, so the LeRobot road ends in a success rate too.

`lerobot-train` on an export (`hgen dataset export --lerobot`) writes checkpoints as
`<output_dir>/checkpoints/<step>/pretrained_model/` (config.json, model.safetensors, the processors, and
train_config.json, which names the dataset). `LeRobotPolicy` loads one with LeRobot's own factory and its
saved pre/post-processors (normalisation lives there since LeRobot 0.4) and answers what evaluation's
`rollout` asks of a policy: a batch from the observation history, one action per prediction.

What the environment observes comes from the export the policy was trained on: its `meta/humanoidgen.json`
(the task, the control rate and the recorder's settings: cameras, image size, action rate) and the
checkpoint's input features (which cameras and states the policy reads). Images are given as LeRobot's own
evaluation gives them (channels first, float in [0, 1]), padded to the exported (even) size as the export pads
them. LeRobot is imported only here and only when a LeRobot checkpoint is evaluated (it lives in its own
environment: scripts/setup_lerobot.sh)."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch

from humanoidgen.episodes.lerobot_export import SOURCE_META
from humanoidgen.policies.rollout import EvalError

STATE_KEY = "observation.state"
EE_POSE_KEY = "observation.ee_pose"
IMAGE_PREFIX = "observation.images."


@dataclass(frozen=True)
class _Timing:
    """What `rollout` reads of a policy's config: LeRobot policies keep their own observation queue."""

    n_obs_steps: int = 1


def is_lerobot_checkpoint(path: Path) -> bool:
    """A LeRobot `pretrained_model` folder (or a folder holding one): a config.json with a policy `type`."""
    return checkpoint_folder(path) is not None


def checkpoint_folder(path: Path) -> Path | None:
    path = Path(path)
    for p in (path, path / "pretrained_model"):
        cfg = p / "config.json"
        if cfg.is_file():
            try:
                if "type" in json.loads(cfg.read_text()):
                    return p
            except (OSError, ValueError):
                return None
    return None


def dataset_of(folder: Path, dataset: Path | None = None) -> Path:
    """The export the checkpoint was trained on: `dataset`, else train_config.json's `dataset.root`."""
    if dataset is None:
        train_cfg = folder / "train_config.json"
        if train_cfg.is_file():
            root = (json.loads(train_cfg.read_text()).get("dataset") or {}).get("root")
            dataset = Path(root) if root else None
    if dataset is None:
        raise EvalError(f"{folder} does not name the dataset it was trained on (no dataset.root in its "
                        f"train_config.json); give it with --data EXPORT")
    if not (Path(dataset) / SOURCE_META).is_file():
        raise EvalError(f"{dataset} is not an export of `hgen dataset export --lerobot` ({SOURCE_META} missing): "
                        f"the task and the cameras a LeRobot policy saw are read from it")
    return Path(dataset)


def source_meta(dataset: Path) -> dict:
    """The export's {task, control_hz, recorder, action_names}."""
    return json.loads((Path(dataset) / SOURCE_META).read_text())


class LeRobotPolicy:
    """One LeRobot checkpoint, driven as evaluation drives this project's own policies."""

    obs_keys: tuple[str, ...] = ()

    def __init__(self, folder: Path, device: str = "cpu") -> None:
        try:
            from lerobot.configs.policies import PreTrainedConfig
            from lerobot.policies.factory import get_policy_class, make_pre_post_processors
        except ImportError as exc:
            raise EvalError(f"{folder} is a LeRobot checkpoint, and LeRobot is not installed here ({exc}); run "
                            f"the evaluation in LeRobot's environment: scripts/setup_lerobot.sh, then "
                            f".venv-lerobot/bin/hgen policy eval ...") from exc
        pcfg = PreTrainedConfig.from_pretrained(str(folder))
        pcfg.device = device
        self.policy = get_policy_class(pcfg.type).from_pretrained(str(folder), config=pcfg)
        self.policy.to(device).eval()
        self.pre, self.post = make_pre_post_processors(
            pcfg, pretrained_path=str(folder), preprocessor_overrides={"device_processor": {"device": device}})
        self.name = f"lerobot-{pcfg.type}"
        self.cfg = _Timing()
        self.device = device
        self.features = {k: tuple(f.shape) for k, f in pcfg.input_features.items()}
        self.cameras = tuple(k.removeprefix(IMAGE_PREFIX) for k in self.features if k.startswith(IMAGE_PREFIX))
        unknown = [k for k in self.features if k not in (STATE_KEY, EE_POSE_KEY) and not k.startswith(IMAGE_PREFIX)]
        if unknown:
            raise EvalError(f"{folder} reads {', '.join(unknown)}, which the environment does not observe "
                            f"(it gives {STATE_KEY}, {EE_POSE_KEY} and {IMAGE_PREFIX}<camera>)")
        self._seed: int | None = None

    def start_episode(self, obs) -> None:
        """Forget the last episode's queued observations and actions."""
        self.policy.reset()
        self._seed = None

    def observation_batch(self, history, device: str) -> dict[str, torch.Tensor]:
        """The newest observation named and shaped as the export holds it, as a batch of one."""
        obs = history[-1]
        batch: dict[str, torch.Tensor] = {}
        if STATE_KEY in self.features:
            batch[STATE_KEY] = torch.as_tensor(obs["joint_pos"], dtype=torch.float32)[None]
        if EE_POSE_KEY in self.features:
            batch[EE_POSE_KEY] = torch.as_tensor(obs["ee_pose"], dtype=torch.float32)[None]
        for cam in self.cameras:
            _, h, w = self.features[IMAGE_PREFIX + cam]
            img = obs[f"rgb/{cam}"]
            if img.shape[:2] != (h, w):  # the export pads odd sizes to even ones by repeating the edge
                if img.shape[0] > h or img.shape[1] > w:
                    raise EvalError(f"camera {cam} renders {img.shape[1]}x{img.shape[0]}, larger than the "
                                    f"{w}x{h} the policy was trained on")
                img = np.pad(img, ((0, h - img.shape[0]), (0, w - img.shape[1]), (0, 0)), mode="edge")
            batch[IMAGE_PREFIX + cam] = torch.from_numpy(np.ascontiguousarray(img)).permute(2, 0, 1)[None].float() / 255
        return batch

    def predict_action(self, batch: dict[str, torch.Tensor], generator: torch.Generator | None = None
                       ) -> dict[str, torch.Tensor]:
        """The next action ({"action": [1, 1, D]}). LeRobot samples from torch's global generator: it is seeded
        once per episode from `generator`, so reruns of an evaluation meet the same noise."""
        if self._seed is None:
            self._seed = int(generator.initial_seed()) if generator is not None else 0
            torch.manual_seed(self._seed)
        with torch.inference_mode():
            action = self.post(self.policy.select_action(self.pre(batch)))
        return {"action": action.reshape(1, 1, -1).float().cpu()}

    def action_range(self, dataset: Path):
        """The demonstrations' action range, from the export's statistics (the random baseline draws in it)."""
        from humanoidgen.policies.baselines import ActionRange

        stats = json.loads((Path(dataset) / "meta" / "stats.json").read_text())["action"]
        return ActionRange.of(np.asarray(stats["min"], float), np.asarray(stats["max"], float),
                              f"demonstrations ({dataset})")

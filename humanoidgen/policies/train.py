"""Training any policy on a zarr export: min-max normalization fitted on the data, AdamW with a cosine
schedule after warm-up, EMA weights, a tqdm bar (loss, epoch, ETA), kept checkpoints every
`checkpoint_every` epochs and a resumable `latest.pt` every `save_every` epochs and on Ctrl-C.

    train("dp3", Path("data/close_drawer.zarr"), Path("runs/cd_dp3"), {"train": {"epochs": 200}})
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch

from humanoidgen.policies import checkpoint as ck
from humanoidgen.policies.config import PolicyConfig
from humanoidgen.policies.data import DataError, Demos, read_demos, sequence_index
from humanoidgen.policies.hands import hand_features
from humanoidgen.policies.registry import policy_type


@dataclass
class TrainResult:
    run: Path
    epochs: int  # epochs done in total (a resumed run counts the earlier ones)
    losses: list[float]  # mean training loss per epoch, all epochs
    seconds: float  # this invocation's training time
    steps_per_epoch: int
    checkpoints: list[Path] = field(default_factory=list)
    interrupted: bool = False
    new_epochs: int = 0  # epochs this invocation trained

    @property
    def seconds_per_epoch(self) -> float:
        return self.seconds / max(self.new_epochs, 1)


def resolve_device(device: str) -> str:
    if device == "auto":
        return "cuda" if torch.cuda.is_available() else "cpu"
    if device.startswith("cuda") and not torch.cuda.is_available():
        raise ValueError("--device cuda: no CUDA device is available here (use --device cpu or auto)")
    if device != "cpu" and not device.startswith("cuda"):
        raise ValueError(f"--device must be auto, cpu or cuda[:n], got {device!r}")
    return device


def policy_inputs(model, demos: Demos) -> dict[str, torch.Tensor]:
    """The data as the model's inputs, in memory: images resized once, point clouds cut to num_points."""
    cfg = model.cfg
    out = {"state": torch.as_tensor(demos.arrays["state"], dtype=torch.float32),
           "action": torch.as_tensor(demos.arrays["action"], dtype=torch.float32)}
    if "point_cloud" in model.obs_keys:
        pc = demos.arrays["point_cloud"]
        if pc.ndim != 3 or pc.shape[-1] < 3:
            raise DataError(f"{demos.path}: data/point_cloud has shape {pc.shape}, not (T, N, 3)")
        if pc.shape[1] < cfg.num_points:
            raise DataError(f"{demos.path}: its clouds have {pc.shape[1]} points, fewer than num_points="
                            f"{cfg.num_points}")
        out["point_cloud"] = torch.as_tensor(np.ascontiguousarray(pc[:, : cfg.num_points, :3]), dtype=torch.float32)
    if "hands" in model.obs_keys:
        try:
            out["hands"] = torch.as_tensor(hand_features(demos.arrays["hands"]))
        except ValueError as e:
            raise DataError(f"{demos.path}: data/ee_pose: {e}") from None
    if "img" in model.obs_keys:
        from humanoidgen.policies.dp.model import resize_images

        img = demos.arrays["img"]
        if len(img.shape) != 4 or img.shape[-1] != 3:
            raise DataError(f"{demos.path}: data/img has shape {img.shape}, not (T, H, W, 3)")
        out["img"] = resize_images(img, cfg.image_size, stop=demos.n_frames)
    return out


def run_meta(demos: Demos, task: str | None) -> dict:
    """What evaluation needs to rebuild the environment the data came from."""
    attrs = demos.attrs
    data_task = attrs.get("task")
    if data_task is None and task is None:
        raise DataError(f"{demos.path} does not say which task it holds (exported before the task was written "
                        "to it); give --task or export it again")
    if data_task is not None and task is not None and data_task != task:
        raise DataError(f"{demos.path} holds task {data_task!r}, not {task!r}")
    meta = {"task": data_task or task, "control_hz": float(attrs.get("control_hz", 50.0)),
            "recorder": dict(attrs.get("recorder") or {"every": 5}), "camera": attrs.get("camera", "head"),
            "data": str(Path(demos.path).resolve()), "episodes": demos.n_episodes, "frames": demos.n_frames}
    if attrs.get("perturbation"):  # trained on demonstrations re-recorded under an arm offset (DART)
        meta["perturbation"] = dict(attrs["perturbation"])
    return meta


def _batch(inputs: dict, rows: torch.Tensor, cfg, device: str) -> dict:
    """The training batch of sequences `rows` (each a horizon of frame indices): the observations of their first
    n_obs_steps frames, the actions of all."""
    return {k: v[rows[:, : cfg.n_obs_steps] if k != "action" else rows].to(device) for k, v in inputs.items()}


def _seconds_per_step(model, inputs: dict, index: torch.Tensor, cfg, device: str) -> float:
    """One training step's forward and backward pass timed on a batch of this run (no optimizer step; the random
    state and gradients put back), so that a run says before its first step what it will take here: the paper's
    recipe on a 2-core CPU measured about 7 s a step at batch 64, which a user should hear before days of it."""
    batch = _batch(inputs, index[: cfg.train.batch_size], cfg, device)
    rng = torch.get_rng_state()
    cuda_rng = torch.cuda.get_rng_state_all() if str(device).startswith("cuda") else None
    model.train()
    t0 = time.perf_counter()
    model.compute_loss(batch).backward()
    if cuda_rng is not None:
        torch.cuda.synchronize()
    seconds = time.perf_counter() - t0
    model.zero_grad(set_to_none=True)
    torch.set_rng_state(rng)
    if cuda_rng is not None:
        torch.cuda.set_rng_state_all(cuda_rng)
    return seconds


def train(policy: str, data: Path, out: Path, overrides: dict | None = None, device: str = "auto",
          resume: bool = False, task: str | None = None, progress: bool = True,
          on_start: Callable[[int, float], None] | None = None) -> TrainResult:
    from diffusers.optimization import get_scheduler
    from tqdm import tqdm

    from humanoidgen.policies.ema import EmaWeights

    ptype = policy_type(policy)
    device = resolve_device(device)
    out = Path(out)
    latest = out / ck.LATEST
    state = None
    if latest.exists():
        if not resume:
            raise ck.CheckpointError(f"{out} already holds a training run; continue it with --resume or choose "
                                     "another --out")
        state = ck.read(latest)
        cfg = _resumed_config(ptype, state, overrides, latest)
    else:
        if resume:
            raise ck.CheckpointError(f"nothing to resume: no {latest}")
        cfg = ptype.config(overrides)
    demos = read_demos(data, _keys(ptype, cfg), cfg.train.episodes, why=ptype.needs)
    meta = run_meta(demos, task)
    if policy == "dp" and cfg.camera != meta["camera"]:
        cfg = cfg.model_copy(update={"camera": meta["camera"]})  # the images are the export's camera's
    if state is not None and state["meta"]["task"] != meta["task"]:
        raise ck.CheckpointError(f"{latest} was trained on {state['meta']['task']!r}, this data is "
                                 f"{meta['task']!r}")
    torch.manual_seed(cfg.train.seed)
    model = ptype.model_cls()(cfg)
    inputs = policy_inputs(model, demos)
    index = torch.as_tensor(sequence_index(demos.episode_ends, cfg.horizon, cfg.n_obs_steps, cfg.n_action_steps))
    fit = {k: v.numpy() for k, v in inputs.items() if k in model.normalizer.keys}
    if cfg.action_frame == "relative":  # the range of what the U-Net denoises: every sample's actions, framed
        fit["target"] = fit["action"]
        fit["action"] = model.framed(inputs["action"][index], inputs["state"][index[:, : cfg.n_obs_steps]]).numpy()
    model.normalizer.fit(fit)
    model.to(device)
    ema = EmaWeights(model, cfg.train)
    tc = cfg.train
    steps_per_epoch = max(1, math.ceil(len(index) / tc.batch_size))
    opt = torch.optim.AdamW(model.parameters(), lr=tc.lr, betas=tc.betas, weight_decay=tc.weight_decay)
    sched = get_scheduler("cosine", opt, num_warmup_steps=tc.lr_warmup_steps,
                          num_training_steps=tc.epochs * steps_per_epoch)
    losses: list[float] = []
    first = 0
    if state is not None:
        model.load_state_dict(state["model"])
        ema.load_state_dict(state["ema"])
        opt.load_state_dict(state["optimizer"])
        sched.load_state_dict(state["lr_scheduler"])
        torch.set_rng_state(state["torch_rng"])
        losses, first = list(state["losses"]), int(state["epoch"])
    result = TrainResult(out, first, losses, 0.0, steps_per_epoch)
    out.mkdir(parents=True, exist_ok=True)
    (out / "config.json").write_text(cfg.model_dump_json(indent=2))

    def payload(epoch: int, full: bool) -> dict:
        p = {"policy": policy, "config": cfg.model_dump(mode="json"), "meta": {**meta, "epoch": epoch},
             "weights": ema.model.state_dict()}
        if full:
            p.update(model=model.state_dict(), ema=ema.state_dict(), optimizer=opt.state_dict(),
                     lr_scheduler=sched.state_dict(), torch_rng=torch.get_rng_state(), losses=losses, epoch=epoch)
        return p

    if on_start is not None:  # the data and settings are good: the CLI says the recipe and what the run will cost
        on_start((tc.epochs - first) * steps_per_epoch, _seconds_per_step(model, inputs, index, cfg, device))
    bar = tqdm(total=(tc.epochs - first) * steps_per_epoch, unit="step", desc=f"train {policy}",
               disable=not progress, dynamic_ncols=True)
    t0 = time.perf_counter()
    epoch = first
    try:
        for epoch in range(first, tc.epochs):
            model.train()
            order = index[torch.as_tensor(np.random.default_rng((tc.seed, epoch)).permutation(len(index)))]
            total = 0.0
            for b in range(steps_per_epoch):
                rows = order[b * tc.batch_size: (b + 1) * tc.batch_size]
                batch = _batch(inputs, rows, cfg, device)
                loss = model.compute_loss(batch)
                opt.zero_grad(set_to_none=True)
                loss.backward()
                opt.step()
                sched.step()
                ema.update(model)
                total += loss.item()
                bar.update(1)
                bar.set_postfix_str(f"epoch {epoch + 1}/{tc.epochs} loss {loss.item():.4f}")
            losses.append(total / steps_per_epoch)
            done = epoch + 1
            if done % tc.checkpoint_every == 0 or done == tc.epochs:
                ck.save(ck.epoch_path(out, done), payload(done, full=False))
                result.checkpoints.append(ck.epoch_path(out, done))
            if done % tc.save_every == 0 or done == tc.epochs:
                ck.save(latest, payload(done, full=True))
            result.epochs = done
    except KeyboardInterrupt:
        # The epoch in flight is dropped from the count (its updates are kept): resuming redoes it.
        ck.save(latest, payload(result.epochs, full=True))
        result.interrupted = True
    finally:
        bar.close()
    result.seconds = time.perf_counter() - t0
    result.new_epochs = result.epochs - first
    return result


def _keys(ptype, cfg: PolicyConfig) -> tuple[str, ...]:
    return ptype.model_cls().inputs_for(cfg)


def _resumed_config(ptype, state: dict, overrides: dict | None, latest: Path) -> PolicyConfig:
    """The saved run's config; overrides (merged over it, so a run trained with a recipe resumes with only
    --epochs) may only extend its epochs."""
    from humanoidgen.policies.recipes import merge

    if state.get("policy") != ptype.name:
        raise ck.CheckpointError(f"{latest} is a {state.get('policy')} run, not {ptype.name}")
    saved = ptype.config_cls.model_validate(state["config"])
    if not overrides:
        return saved
    wanted = ptype.config_cls.model_validate(merge(saved.model_dump(), overrides))
    epochs = wanted.train.epochs
    if wanted.model_copy(update={"train": wanted.train.model_copy(update={"epochs": saved.train.epochs})}) != saved:
        raise ck.CheckpointError(f"{latest} was trained with other settings; resume it with its own (only "
                                 "--epochs may change) or start a new --out")
    return saved.model_copy(update={"train": saved.train.model_copy(update={"epochs": epochs})})

"""Demonstrations re-recorded under a drifting arm error, labelled with the plan's own targets (DART, Laskey et al.,
"DART: Noise Injection for Robust Imitation Learning", CoRL 2017).

A policy trained on perfect executions has never seen the hand a centimetre off its path, so the first error it
makes puts it where its data says nothing, and closed-loop errors compound: close_drawer's DP3 failed in its own
training scenes as often as in new ones (docs/results/policies.md). Here each kept episode's recorded actions are
replayed in the task's gym environment (the policy's env, a simulation the plan never ran in) with a slowly
drifting offset added to one arm's joint targets. The observations are recorded from that perturbed run, and each
frame is labelled with the target the plan gave (the action as recorded): "from here, the plan's target", which
teaches the way back. A replay that no longer passes the task's predicates (judged in the same env, as the
evaluation judges a policy) is drawn again, up to `tries` times; then the episode is left out.

The offset per joint is an Ornstein-Uhlenbeck walk at the data's action rate: stationary standard deviation
`sigma` (rad), correlation time `tau_s`, started from its stationary law (a policy's error is of this kind, a few
hundredths of a radian, steady over a move: bench/replay_tolerance.py). The new store records what the env
observes (joint_pos, ee_pose, point_cloud, and qpos for `hgen dataset replay`; no images: the cameras' pictures
are not re-rendered) and says in its meta.json where it came from and how it was perturbed."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Literal

import numpy as np

from humanoidgen.episodes.dataset import DatasetError, EpisodeStore
from humanoidgen.sim.action import ARM_SLICE

# The last target held this long more (unrecorded): a drawer still sliding shut may yet pass. bench/replay_tolerance.py
# settles its replays by the same count.
SETTLE_ACTIONS = 20
RECORDED = ("joint_pos", "ee_pose", "point_cloud")


@dataclass(frozen=True)
class Perturbation:
    """How the replays are perturbed: `sigma` rad (stationary standard deviation per joint of `side`'s arm),
    `tau_s` seconds of correlation, `draws` perturbed replays per source episode, `tries` draws for each before
    it is left out, `seed` for the draws (each drawn from (seed, the scene's seed, draw, try))."""

    sigma: float
    side: Literal["left", "right", "both"] = "left"
    tau_s: float = 1.0
    draws: int = 1
    tries: int = 3
    seed: int = 0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.sigma) and self.sigma >= 0):
            raise ValueError(f"sigma must be a finite number >= 0 (rad), not {self.sigma!r}")
        if not (math.isfinite(self.tau_s) and self.tau_s > 0):
            raise ValueError(f"tau_s must be a positive number of seconds, not {self.tau_s!r}")
        if self.side not in ("left", "right", "both"):
            raise ValueError(f"side must be left, right or both, not {self.side!r}")
        if self.draws < 1 or self.tries < 1:
            raise ValueError("draws and tries must be at least 1")

    def joints(self) -> list[int]:
        """The action indices the offset moves."""
        sides = ("left", "right") if self.side == "both" else (self.side,)
        return [j for s in sides for j in range(ARM_SLICE[s].start, ARM_SLICE[s].stop)]

    def offsets(self, steps: int, rate_hz: float, rng: np.random.Generator) -> np.ndarray:
        """(steps, joints) the Ornstein-Uhlenbeck walk: x0 ~ N(0, sigma), x' = a x + sqrt(1 - a^2) sigma e."""
        n = len(self.joints())
        a = math.exp(-1.0 / (self.tau_s * rate_hz))
        out = np.empty((steps, n))
        x = rng.normal(0.0, self.sigma, n)
        for t in range(steps):
            out[t] = x
            x = a * x + math.sqrt(1.0 - a * a) * self.sigma * rng.normal(0.0, 1.0, n)
        return out


@dataclass
class PerturbStats:
    source_episodes: int = 0
    kept: int = 0
    left_out: int = 0
    tries: int = 0


def perturbed_replay(env, actions: np.ndarray, seed: int, offsets: np.ndarray, joints: list[int],
                     dressing: dict | None = None) -> tuple[bool, dict[str, np.ndarray], str]:
    """Replay `actions` in `env` (a HumanoidTaskEnv) for scene `seed` (in the room and look `dressing`, as the
    source episode's record gives it; None: the env's own), executing each with `offsets` added on `joints`; the
    frames it observed labelled with the actions as given. Returns (passed, arrays, the task's last words). The
    whole sequence is run (a success midway is kept: the predicates remember it), then the last target held
    SETTLE_ACTIONS more, unrecorded."""
    from humanoidgen.policies.rollout import final_detail

    obs, info = env.reset(seed=seed, options={"dressing": dressing})
    ok = bool(info.get("success"))
    frames: dict[str, list[np.ndarray]] = {k: [] for k in RECORDED if k in obs}
    executed = actions.copy()
    executed[:, joints] += offsets
    qpos = []  # the configurations seen, so that `hgen dataset replay` can draw the episode
    for t in range(len(actions)):
        for k in frames:
            frames[k].append(obs[k])
        qpos.append(env.sim.data.qpos.copy())
        obs, _, _, _, info = env.step(executed[t])
        ok = ok or bool(info.get("success"))
    for _ in range(SETTLE_ACTIONS):
        if ok:
            break
        obs, _, _, _, info = env.step(executed[-1])
        ok = ok or bool(info.get("success"))
    arrays = {k: np.stack(v) for k, v in frames.items()}
    arrays["action"] = np.asarray(actions, dtype=np.float32)
    arrays["qpos"] = np.stack(qpos)
    return ok, arrays, final_detail(info)


@dataclass(frozen=True)
class _Job:
    """One perturbed replay to draw: everything a worker process needs, nothing it shares."""

    actions: np.ndarray
    seed: int
    source_episode: int
    draw: int
    how: Perturbation
    rate_hz: float
    dressing: dict | None = None  # the source episode's room and look (a randomized collection's record)


def _draw(job: _Job, env) -> list[tuple[dict, dict[str, np.ndarray] | None, str]]:
    """Up to `how.tries` replays of one (episode, draw): the index records and arrays to write, in order."""
    how = job.how
    out = []
    for attempt in range(how.tries):
        rng = np.random.default_rng([how.seed, job.seed, job.draw, attempt])
        ok, arrays, words = perturbed_replay(env, job.actions, job.seed,
                                             how.offsets(len(job.actions), job.rate_hz, rng), how.joints(),
                                             job.dressing)
        record = {"seed": job.seed, "success": ok, "source_episode": job.source_episode, "draw": job.draw,
                  "try": attempt, "error": "" if ok else words}
        if job.dressing is not None:
            record["dressing"] = job.dressing  # as collection records it: `hgen dataset replay` draws this room
        out.append((record, arrays if ok else None, words))
        if ok:
            break
    return out


_WORKER_ENV = None  # one env per worker process, made by _init_worker


def _init_worker(task: str, config) -> None:
    global _WORKER_ENV
    _WORKER_ENV = _make_env(task, config)


def _draw_in_worker(job: _Job):
    return _draw(job, _WORKER_ENV)


def _make_env(task: str, config):
    from humanoidgen.envs.task_env import HumanoidTaskEnv

    return HumanoidTaskEnv(task, config=config)


def perturb_store(source: Path, out: Path, how: Perturbation, episodes: int | None = None,
                  progress: Callable[[str], None] | None = None, resume: bool = False,
                  workers: int = 1, cloud_near_hands: float | None = None) -> PerturbStats:
    """Write to `out` a store of `how.draws` perturbed replays of each of the first `episodes` (all: None) kept
    episodes of the store at `source`. Each attempt is an index line (a left-out draw too, with the task's words).
    With `resume`, an interrupted run goes on: draws already kept or given up are not replayed again (the same
    source and perturbation are required, except that `how.draws` may grow: a finished store gains draws).
    `workers` > 1 replays in that many processes (each with its own env); the store is written here, in the order
    a single process would write it, so the result does not depend on it. `cloud_near_hands`: the share of each
    recorded cloud's points drawn near the hands (`sim.cloud_focus`; None: the source's setting)."""
    from humanoidgen.envs.config import TaskEnvConfig

    if workers < 1:
        raise ValueError("workers must be at least 1")
    src = EpisodeStore(Path(source))
    meta = src.meta()
    kept = src.kept()[:episodes] if episodes else src.kept()
    if not kept:
        raise DatasetError(f"{source} has no kept episodes to perturb")
    recorder = dict(meta.get("recorder") or {})
    dst = EpisodeStore(Path(out))
    if cloud_near_hands is None and resume and (Path(out) / "meta.json").exists():  # as the store was begun
        cloud_near_hands = (dst.meta().get("recorder") or {}).get("point_cloud_near_hands")
    if cloud_near_hands is not None:
        recorder["point_cloud_near_hands"] = float(cloud_near_hands)
    rate_hz = float(meta.get("control_hz", 50.0)) / int(recorder.get("every", 1))
    cfg = TaskEnvConfig.from_recorder(recorder, meta.get("control_hz", 50.0), cameras=(), depth=False,
                                      point_cloud=bool(recorder.get("point_cloud", True)))
    new_meta = {k: v for k, v in meta.items() if k != "format_version"}
    new_meta["recorder"] = {**recorder, "cameras": [], "depth": False}
    new_meta["cameras"] = []
    new_meta["perturbation"] = {**asdict(how), "source": str(Path(source).resolve()), "method": "DART: "
                                "observations from the perturbed replay, actions as the plan gave them"}
    dst.create(new_meta, resume=resume)
    if resume:
        # More draws extend a finished store (its draws are kept, the new ones appended); anything else must match.
        before = dst.meta().get("perturbation") or {}
        same = {k: v for k, v in new_meta["perturbation"].items() if k != "draws"}
        near = (dst.meta().get("recorder") or {}).get("point_cloud_near_hands", 0.0)
        if near != recorder.get("point_cloud_near_hands", 0.0):
            raise DatasetError(f"{out} was recorded with point_cloud_near_hands {near}; resume it with the same "
                               "--cloud-near-hands or choose another --out")
        if {k: before.get(k) for k in same} != same or int(before.get("draws", 0)) > how.draws:
            raise DatasetError(f"{out} was perturbed otherwise ({before}); resume it with the same settings (or "
                               "more --draws) or choose another --out")
        if int(before.get("draws", 0)) < how.draws:
            dst.update_meta(perturbation=new_meta["perturbation"])
    finished = {(a.get("source_episode"), a.get("draw")) for a in dst.attempts()
                if a.get("success") or a.get("try") == how.tries - 1}
    stats = PerturbStats(source_episodes=len(kept), kept=len(dst.kept()))  # a resumed run counts what it has
    stats.left_out = len(finished) - len({(a.get("source_episode"), a.get("draw")) for a in dst.kept()})
    position = {int(rec["episode"]): k for k, rec in enumerate(kept)}  # for the results, which come by record

    def jobs():
        for k, rec in enumerate(kept):
            actions = np.asarray(src.load(rec["episode"], ("action",))["action"], dtype=np.float64)
            for d in range(how.draws):
                if (int(rec["episode"]), d) in finished:
                    if progress is not None:
                        progress(f"episode {k + 1}/{len(kept)} draw {d + 1}: done before")
                    continue
                yield _Job(actions, int(rec["seed"]), int(rec["episode"]), d, how, rate_hz, rec.get("dressing"))

    def write(results) -> None:
        for attempts in results:
            for record, arrays, _ in attempts:
                dst.add(record, arrays)
                stats.tries += 1
            record, _, words = attempts[-1]
            if record["success"]:
                stats.kept += 1
            else:
                stats.left_out += 1
            if progress is not None:
                progress(f"episode {position[record['source_episode']] + 1}/{len(kept)} draw {record['draw'] + 1}: "
                         + ("kept" if record["success"] else f"left out after {how.tries} tries ({words})"))

    if workers == 1:
        env = _make_env(meta["task"], cfg)
        try:
            write(_draw(job, env) for job in jobs())
        finally:
            env.close()
        return stats
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    # spawn: a fresh interpreter per worker (no forked MuJoCo or torch state); map keeps the jobs' order
    pool = ProcessPoolExecutor(workers, mp_context=mp.get_context("spawn"), initializer=_init_worker,
                               initargs=(meta["task"], cfg))
    try:
        write(pool.map(_draw_in_worker, jobs(), chunksize=1))
    finally:  # interrupted: the draws not begun are dropped (--resume replays them), not run to the end first
        pool.shutdown(wait=True, cancel_futures=True)
    return stats


def describe(stats: PerturbStats, how: Perturbation) -> str:
    arms = "both arms" if how.side == "both" else f"the {how.side} arm"
    return (f"{stats.kept} perturbed episodes kept of {stats.source_episodes * how.draws} wanted "
            f"({stats.left_out} left out after {how.tries} tries each; {stats.tries} replays; sigma {how.sigma:g} rad "
            f"on {arms}, tau {how.tau_s:g} s)")


def read_perturbation(store: EpisodeStore) -> dict | None:
    """The perturbation a store was made with (None: recorded as planned)."""
    return store.meta().get("perturbation")

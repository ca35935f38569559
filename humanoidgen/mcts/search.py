"""MCTS over LLM continuations (paper: "Enhancing Reasoning with MCTS", appendix "MCTS-Based LLM Reasoning").

One iteration: select a path by discounted UCB until a node's "expand here" branch wins; restore that
node's snapshot; ask the LLM to continue from it (prompt.py); run the answer step by step, truncating at the
first failed step and combining ok steps into units (stcr.py); a unit equal to an existing child's follows that
child, others become new nodes; backpropagate the intrinsic reward. Stops at task success or after N
expansions. With K executors, K expansions run at once (one thread per executor); in-flight selections count
as zero-reward visits (virtual loss) so they spread over the tree."""

from __future__ import annotations

import queue
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from humanoidgen.generation.extract import plan_text
from humanoidgen.generation.scene_image import CAPTION
from humanoidgen.llm import LLMClient
from humanoidgen.llm.images import sha256, with_image
from humanoidgen.mcts.executor import Executor, outcome_text
from humanoidgen.mcts.prompt import expansion_prompt
from humanoidgen.mcts.stcr import Unit, closes_intent, intrinsic_reward, segment
from humanoidgen.mcts.tree import Node, Tree


@dataclass
class MCTSConfig:
    expansions: int = 8  # expansions in this run (a continued tree keeps its earlier ones)
    gamma: float = 0.99
    minimal_guidance: bool = False  # hide cube operation annotations in the prompt
    short_description: bool = False  # the short task description (block/pyramid stacking tasks)
    verify: bool = True  # re-run the found plan from a fresh reset
    images: bool = False  # every expansion prompt carries the annotated picture of the scene at the start


@dataclass
class MCTSResult:
    task: str
    seed: int | None
    tree: Tree
    success: bool
    plan: list[tuple[str, str]] | None = None
    verified: bool | None = None  # the plan re-ran to success from a fresh reset (None: not checked)
    expansions_run: int = 0
    log: list[dict] = field(default_factory=list)

    @property
    def tokens(self) -> int:
        return sum(int(e.get("tokens") or 0) for e in self.tree.meta.get("expansions", []))

    def plan_text(self) -> str:
        if self.plan is None:
            raise ValueError(f"no successful plan for {self.task}")
        n = len(self.tree.meta.get("expansions", []))
        return plan_text(self.plan, f"Plan for task {self.task}, found by MCTS (`hgen generate script --mcts`) "
                                    f"after {n} expansion(s), {len(self.tree.nodes)} node(s).")


class MCTS:
    def __init__(self, spec_data: dict, client: LLMClient, executors: list[Executor], seed: int | None = None,
                 config: MCTSConfig | None = None, tree: Tree | None = None) -> None:
        from humanoidgen.generation.script_gen import step_names

        self.spec_data, self.client, self.seed = spec_data, client, seed
        self.executors = executors
        self.config = config or MCTSConfig()
        self.names = step_names()
        self.tree = tree
        self._lock = threading.Lock()
        self._png: bytes | None = None  # the scene's picture (config.images), rendered once per search

    # -- setup ------------------------------------------------------------------------------------------
    def _prepare(self) -> None:
        """Reset every executor to the task's scene; a new tree gets a root with the set-up snapshot."""
        infos = [ex.reset(self.spec_data, self.seed) for ex in self.executors]
        if self.config.images and self._png is None:
            from humanoidgen.generation.scene_image import scene_png
            from humanoidgen.tasks.registry import parse_task

            self._png = scene_png(parse_task(self.spec_data, "<search>"), self.seed)
        if self.tree is None:
            ex = self.executors[0]
            verdict = ex.judge()
            self.tree = Tree(gamma=self.config.gamma, meta={
                "task": self.spec_data["name"], "description": self.spec_data.get("description", ""),
                "seed": self.seed, "spec": self.spec_data, "scene": infos[0]["scene"],
                "hands": infos[0]["hands"], "expansions": []})
            root = self.tree.add(None, None, ex.snapshot(), events=verdict["events"], checks=verdict["checks"])
            root.status = verdict.get("status", [])

    # -- the loop ---------------------------------------------------------------------------------------
    def run(self) -> MCTSResult:
        self._prepare()
        tree = self.tree
        free: queue.Queue[Executor] = queue.Queue()
        for ex in self.executors:
            free.put(ex)
        started, base = 0, len(tree.meta["expansions"])
        with ThreadPoolExecutor(max_workers=len(self.executors)) as pool:
            futures: set = set()
            while True:
                while (len(futures) < len(self.executors) and started < self.config.expansions
                       and tree.solution() is None):
                    with self._lock:
                        path = tree.select()
                        tree.begin(path)
                        k = base + started  # the expansion's id in the log
                    futures.add(pool.submit(self._job, path, k, free))
                    started += 1
                if not futures:
                    break
                done, futures = wait(futures, return_when=FIRST_COMPLETED)
                for f in done:
                    f.result()  # an LLM error ends the search, as in script generation
        sol = tree.solution()
        result = MCTSResult(tree.meta["task"], self.seed, tree, sol is not None, expansions_run=started,
                            log=tree.meta["expansions"])
        if sol is not None:
            result.plan = tree.plan(sol)
            if self.config.verify:
                result.verified = self.verify(result.plan)
                tree.meta["verified"] = result.verified
        return result

    def _job(self, path: list[int], k: int, free: queue.Queue) -> None:
        ex = free.get()
        try:
            self._expand(path, k, ex)
        except BaseException:
            with self._lock:  # release the virtual loss so a saved tree is consistent
                self.tree.backprop(path, 0.0)
            raise
        finally:
            free.put(ex)

    # -- one expansion ----------------------------------------------------------------------------------
    def _expand(self, path: list[int], k: int, ex: Executor) -> None:
        tree, cfg = self.tree, self.config
        with self._lock:
            node = tree.nodes[path[-1]]
            prompt = expansion_prompt(tree, node, self.names, cfg.minimal_guidance, cfg.short_description)
        t_restore = time.perf_counter()
        ex.restore(node.snapshot)
        restore_seconds = time.perf_counter() - t_restore
        t0 = time.perf_counter()
        reply = self.client.chat([{"role": "user", "content": with_image(prompt, self._png, CAPTION)}])
        tokens = int(reply.usage.total or 0)
        entry: dict[str, Any] = {"id": k, "node": node.id, "path": path, "prompt": prompt, "response": reply.text,
                                 "tokens": tokens, "llm_seconds": round(time.perf_counter() - t0, 3),
                                 "cached": reply.cached, "new_nodes": []}
        if self._png is not None:
            entry["image"] = sha256(self._png)
        t_run = time.perf_counter()
        steps = segment(reply.text)
        cur, pending, failure, snap = node, [], None, node.snapshot
        for title, code in steps:
            out = ex.run_step(code)
            if not out.ok:  # Truncate: the rest of the answer is discarded
                failure = {"title": title, "code": code, "error": outcome_text(out), "expansion": k}
                break
            snap = ex.snapshot()
            pending.append((title, code))
            if closes_intent(code):  # Combine: the unit is complete
                cur, snap = self._attach(cur, pending, snap, ex, k, tokens, entry)
                pending = []
        if pending:
            cur, snap = self._attach(cur, pending, snap, ex, k, tokens, entry)
        if not steps:
            failure = {"title": "(no code)", "code": "", "expansion": k,
                       "error": "the answer had no ```python blocks; write each step in its own block"}
        if failure is not None and failure["code"]:
            ex.restore(cur.snapshot)  # judge the state the valid prefix reached, not the failed step's
        verdict = ex.judge()
        with self._lock:
            cur.checks = verdict["checks"]
            cur.status = verdict.get("status", [])
            success = failure is None and bool(cur.checks) and all(c["ok"] for c in cur.checks)
            if failure is not None:
                cur.failures.append(failure)
            reward = 1.0 if success else intrinsic_reward(cur.events[len(node.events):], node.checks, cur.checks)
            tree.backprop(path, reward)
            cur.success = success
            # Expansion time without the LLM: restoring the node, running and judging the new steps.
            entry.update(end_node=cur.id, failure=failure, reward=reward, success=success,
                         run_seconds=round(restore_seconds + time.perf_counter() - t_run, 3))
            tree.meta["expansions"].append(entry)

    def _attach(self, cur: Node, steps: list[tuple[str, str]], snap: dict, ex: Executor, k: int, tokens: int,
                entry: dict) -> tuple[Node, dict]:
        """Move down one unit: follow an existing child with the same code (restoring its exact state), or
        add a node that keeps the state reached (Resume)."""
        unit = Unit(list(steps))
        with self._lock:
            child = self.tree.child_with_key(cur, unit.key)
            if child is None:
                child = self.tree.add(cur.id, unit, snap, events=list(snap.get("events", [])), tokens=tokens,
                                      expansion=k)
                entry["new_nodes"].append(child.id)
                return child, snap
        ex.restore(child.snapshot)
        return child, child.snapshot

    # -- checking the result ----------------------------------------------------------------------------
    def verify(self, plan: list[tuple[str, str]]) -> bool:
        """Re-run the plan from a fresh reset with the same seed (no snapshots involved)."""
        ex = self.executors[0]
        ex.reset(self.spec_data, self.seed)
        for _, code in plan:
            if not ex.run_step(code).ok:
                return False
        checks = ex.judge()["checks"]
        return bool(checks) and all(c["ok"] for c in checks)


def write_outputs(result: MCTSResult, out: Path | None, log_path: Path | None = None,
                  picture: Path | None = None) -> dict[str, Path]:
    """The plan at `out` (if found), the tree log (default: next to it, .tree.json) and its picture
    (.tree.png). Returns what was written."""
    from humanoidgen.mcts.render import draw_tree

    written: dict[str, Path] = {}
    base = Path(out) if out is not None else Path(log_path) if log_path is not None else None
    if base is None:
        return written
    log_path = Path(log_path) if log_path is not None else base.with_suffix(".tree.json")
    picture = Path(picture) if picture is not None else base.with_suffix(".tree.png")
    if result.success and out is not None:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        Path(out).write_text(result.plan_text())
        written["plan"] = Path(out)
    result.tree.save(log_path)
    written["log"] = log_path
    draw_tree(result.tree, picture)
    written["picture"] = picture
    return written

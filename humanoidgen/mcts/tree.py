"""The search tree: nodes (a unit of code each, with the state it leads to), discounted-UCB selection with
the special "expand here" branch at every node, virtual loss for parallel expansions, and JSON round trips."""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from humanoidgen.mcts.stcr import Unit

EXPAND = -1  # the special branch (the empty set of the paper): stop descending, expand this node


def discounted(rewards: list[float], gamma: float, running: int = 0) -> tuple[float, float]:
    """(W_gamma, N_gamma) of an edge. Rewards are in backprop order; `running` in-flight selections count as
    the newest visits with reward 0 (virtual loss), so parallel searches spread out."""
    rs = list(rewards) + [0.0] * running
    n = len(rs)
    w = sum(gamma ** (n - t) * r for t, r in enumerate(rs, 1))
    return w, sum(gamma ** t for t in range(n))


def ducb(w: float, n: float, total: float) -> float:
    """Q_DUCB = W/N + sqrt(2 ln(total) / N); an unvisited edge (N = 0) goes first."""
    if n <= 0:
        return math.inf
    return w / n + math.sqrt(2 * math.log(max(total, 1.0)) / n)


@dataclass
class Node:
    id: int
    parent: int | None
    unit: Unit | None  # None at the root
    snapshot: dict | None  # the state after this node's unit (Resume)
    events: list[str] = field(default_factory=list)  # planner events from the start up to this state
    checks: list[dict] = field(default_factory=list)  # success conditions at this state (when judged)
    status: list[dict] = field(default_factory=list)  # object poses / openness at this state (when judged)
    children: list[int] = field(default_factory=list)
    rewards: list[float] = field(default_factory=list)  # edge parent -> this node, in backprop order
    expand_rewards: list[float] = field(default_factory=list)  # the "expand here" branch of this node
    running: int = 0  # in-flight selections through the edge into this node
    expand_running: int = 0
    failures: list[dict] = field(default_factory=list)  # {"title", "code", "error", "expansion"} tried here
    tokens: int = 0  # tokens of the expansion that created the node
    expansion: int | None = None  # which expansion created it
    success: bool = False

    def to_dict(self, snapshots: bool = True) -> dict:
        d = asdict(self)
        d["unit"] = self.unit.to_dict() if self.unit else None
        d["running"] = d["expand_running"] = 0  # in-flight work does not survive a save
        if not snapshots:
            d["snapshot"] = None
        return d

    @classmethod
    def from_dict(cls, d: dict) -> Node:
        d = dict(d)
        d["unit"] = Unit.from_dict(d["unit"]) if d.get("unit") else None
        return cls(**d)


@dataclass
class Tree:
    nodes: list[Node] = field(default_factory=list)
    gamma: float = 0.99
    meta: dict[str, Any] = field(default_factory=dict)  # task, seed, scene description, expansions log

    @property
    def root(self) -> Node:
        return self.nodes[0]

    def add(self, parent: int | None, unit: Unit | None, snapshot: dict | None, **kw: Any) -> Node:
        node = Node(len(self.nodes), parent, unit, snapshot, **kw)
        self.nodes.append(node)
        if parent is not None:
            self.nodes[parent].children.append(node.id)
        return node

    def child_with_key(self, node: Node, key: str) -> Node | None:
        return next((self.nodes[c] for c in node.children if self.nodes[c].unit.key == key), None)

    def path(self, node: Node) -> list[Node]:
        out = [node]
        while out[-1].parent is not None:
            out.append(self.nodes[out[-1].parent])
        return out[::-1]

    def scores(self, node: Node) -> list[tuple[int, float]]:
        """(branch, Q_DUCB) for every child of `node` and its EXPAND branch, children first."""
        stats = [(c, *discounted(self.nodes[c].rewards, self.gamma, self.nodes[c].running)) for c in node.children]
        stats.append((EXPAND, *discounted(node.expand_rewards, self.gamma, node.expand_running)))
        total = sum(n for _, _, n in stats)
        return [(b, ducb(w, n, total)) for b, w, n in stats]

    def select(self) -> list[int]:
        """Descend from the root by the DUCB policy until the EXPAND branch wins; the path of node ids.
        Ties go to the first branch (existing children before EXPAND)."""
        node, path = self.root, [self.root.id]
        while True:
            best, _ = max(self.scores(node), key=lambda s: s[1])
            if best == EXPAND:
                return path
            node = self.nodes[best]
            path.append(node.id)

    def begin(self, path: list[int]) -> None:
        """Count the selection as in flight along its path (virtual loss) until `backprop`."""
        for i in path[1:]:
            self.nodes[i].running += 1
        self.nodes[path[-1]].expand_running += 1

    def backprop(self, path: list[int], reward: float) -> None:
        for i in path[1:]:
            self.nodes[i].running = max(0, self.nodes[i].running - 1)
            self.nodes[i].rewards.append(reward)
        last = self.nodes[path[-1]]
        last.expand_running = max(0, last.expand_running - 1)
        last.expand_rewards.append(reward)

    def plan(self, node: Node) -> list[tuple[str, str]]:
        """The steps from the root to `node`, in order (the executed code of that node)."""
        return [s for n in self.path(node) if n.unit for s in n.unit.steps]

    def solution(self) -> Node | None:
        return next((n for n in self.nodes if n.success), None)

    # -- persistence ------------------------------------------------------------------------------------
    def to_dict(self, snapshots: bool = True) -> dict:
        return {"gamma": self.gamma, "meta": self.meta, "nodes": [n.to_dict(snapshots) for n in self.nodes]}

    @classmethod
    def from_dict(cls, d: dict) -> Tree:
        return cls([Node.from_dict(n) for n in d["nodes"]], d.get("gamma", 0.99), d.get("meta", {}))

    def save(self, path: Path, snapshots: bool = True) -> None:
        """JSON with every node's snapshot, so a loaded tree can be searched further. Redacted: the expansions
        log holds prompts and answers, which may quote an API key."""
        from humanoidgen.llm.redact import redact

        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(redact(self.to_dict(snapshots))))

    @classmethod
    def load(cls, path: Path) -> Tree:
        return cls.from_dict(json.loads(Path(path).read_text()))

"""A picture of the search tree: nodes coloured by role (on the successful path, ended a failed branch,
expanded, other), labelled with short unit titles; failed branches carry their error."""

from __future__ import annotations

import re
from pathlib import Path

from humanoidgen.mcts.tree import Node, Tree

COLORS = {"success": "#4caf50", "failed": "#e57373", "expanded": "#64b5f6", "other": "#cfd8dc",
          "root": "#ffd54f"}


def _short(text: str, n: int = 26) -> str:
    text = " ".join(text.split())
    return text if len(text) <= n else text[: n - 1] + "…"


def node_role(tree: Tree, node: Node, on_path: set[int]) -> str:
    if node.id in on_path:
        return "success"
    if node.parent is None:
        return "root"
    if node.failures:
        return "failed"
    return "expanded" if node.expand_rewards else "other"


def layout(tree: Tree) -> dict[int, tuple[float, float]]:
    """Leaves at consecutive x, parents centred over their children, depth downwards."""
    pos: dict[int, tuple[float, float]] = {}
    nxt = [0.0]

    def place(node: Node, depth: int) -> float:
        if not node.children:
            x = nxt[0]
            nxt[0] += 1.0
        else:
            xs = [place(tree.nodes[c], depth + 1) for c in node.children]
            x = (xs[0] + xs[-1]) / 2
        pos[node.id] = (x, -float(depth))
        return x

    place(tree.root, 0)
    return pos


def draw_tree(tree: Tree, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")  # files only; no display needed
    import matplotlib.pyplot as plt

    pos = layout(tree)
    sol = tree.solution()
    on_path = {n.id for n in tree.path(sol)} if sol else set()
    width = max(pos.values(), key=lambda p: p[0])[0] + 1
    depth = -min(p[1] for p in pos.values()) + 1
    fig, ax = plt.subplots(figsize=(max(4.0, 2.6 * width), max(3.0, 1.6 * depth)))
    for n in tree.nodes:
        if n.parent is not None:
            (x0, y0), (x1, y1) = pos[n.parent], pos[n.id]
            ax.plot([x0, x1], [y0, y1], color="#90a4ae", zorder=1)
    for n in tree.nodes:
        x, y = pos[n.id]
        role = node_role(tree, n, on_path)
        label = "root" if n.unit is None else f"#{n.id} {_short(n.unit.title)}"
        label += f"\nN={len(n.rewards)} R={sum(n.rewards):g}" if n.unit is not None else ""
        if n.failures:
            err = re.sub(r" \(line \d+ of the step\)", "", n.failures[-1]["error"])
            label += f"\n✗ {_short(err.split(': ', 1)[-1], 34)}"
        ax.text(x, y, label, ha="center", va="center", fontsize=7, zorder=2,
                bbox={"boxstyle": "round", "facecolor": COLORS[role], "edgecolor": "#455a64"})
    from matplotlib.patches import Patch

    ax.legend(handles=[Patch(facecolor=c, label=r) for r, c in COLORS.items()], loc="upper right", fontsize=7)
    ax.set_xlim(-0.7, width - 0.3)
    ax.set_ylim(-depth + 0.4, 0.6)
    ax.axis("off")
    ax.set_title(f"MCTS tree for {tree.meta.get('task', '?')}: {len(tree.nodes)} nodes, "
                 f"{len(tree.meta.get('expansions', []))} expansions, "
                 f"{'solved' if sol else 'not solved'}", fontsize=9)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path

"""MCTS-enhanced script generation (issue 7): STCR turns LLM answers into tree edges, a discounted-UCB tree
search expands nodes from exact simulator snapshots, optionally in parallel. See search.py."""

from humanoidgen.mcts.executor import Executor, FakeExecutor, Outcome, SandboxExecutor
from humanoidgen.mcts.run import MCTSEvalRow, evaluate_mcts, search_plan
from humanoidgen.mcts.search import MCTS, MCTSConfig, MCTSResult, write_outputs
from humanoidgen.mcts.stcr import Unit, combine, normalize_code, segment, truncate
from humanoidgen.mcts.tree import EXPAND, Node, Tree, discounted, ducb

__all__ = [
    "EXPAND", "MCTS", "MCTSConfig", "MCTSEvalRow", "MCTSResult", "Executor", "FakeExecutor", "Node", "Outcome",
    "SandboxExecutor", "Tree", "Unit", "combine", "discounted", "ducb", "evaluate_mcts", "normalize_code",
    "search_plan", "segment", "truncate", "write_outputs",
]

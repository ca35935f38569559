"""STCR (Segment-Truncate-Combine-Resume): turning an LLM answer into tree edges.

Segment: the answer's ```python blocks are the steps. Truncate: the search runs them in order and stops at
the first step whose outcome is not ok. Combine: consecutive ok steps are grouped into one *unit* that closes
at a step finishing an intent (a hand operation) or at the end of the valid prefix, so an edge of the tree is
a meaningful action ("pinch cube 1"), not a single move. Resume: nodes keep a snapshot (see search.py)."""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass, field

from humanoidgen.generation.extract import extract_steps

# A step calling one of these completes an intent (took hold of / let go of / pressed something).
INTENT_OPS = ("hand_grasp", "hand_pinch", "open_hand", "hand_press")
_OP_CALL = re.compile(r"\.(%s)\s*\(" % "|".join(INTENT_OPS))
_HELD = re.compile(r"^(grasped|pinched) \S+ \d+ with the \w+ hand$")
_STAYED = re.compile(r"^released \S+ \d+ and it stayed on (.+)$")


@dataclass
class Unit:
    """Consecutive steps with one intent; its normalized code is its identity when branches merge."""

    steps: list[tuple[str, str]] = field(default_factory=list)  # (title, code)

    @property
    def key(self) -> str:
        return "\n".join(normalize_code(c) for _, c in self.steps)

    @property
    def title(self) -> str:
        # The step that closes the unit names what it achieved; earlier steps are its preparation.
        return self.steps[-1][0] if self.steps else ""

    @property
    def code(self) -> str:
        return "\n".join(f"# step: {t}\n{c.rstrip()}" for t, c in self.steps)

    def to_dict(self) -> dict:
        return {"steps": [list(s) for s in self.steps]}

    @classmethod
    def from_dict(cls, d: dict) -> Unit:
        return cls([(t, c) for t, c in d["steps"]])


def segment(text: str) -> list[tuple[str, str]]:
    """Steps (title, code) of an answer: one per fenced python block."""
    return extract_steps(text)


def normalize_code(code: str) -> str:
    """Code without comments, blank lines or formatting differences (the AST's own rendering)."""
    try:
        return ast.unparse(ast.parse(code))
    except (SyntaxError, ValueError, MemoryError, RecursionError):  # still comparable: strip by hand
        lines = (re.sub(r"#.*$", "", ln).strip() for ln in code.splitlines())
        return "\n".join(re.sub(r"\s+", "", ln) for ln in lines if ln)


def closes_intent(code: str) -> bool:
    stripped = "\n".join(re.sub(r"#.*$", "", ln) for ln in code.splitlines())
    return bool(_OP_CALL.search(stripped))


def combine(steps: list[tuple[str, str]]) -> list[Unit]:
    """Group a valid prefix into units (each closes at an intent-completing step, the last at the end)."""
    units, pending = [], []
    for step in steps:
        pending.append(step)
        if closes_intent(step[1]):
            units.append(Unit(pending))
            pending = []
    if pending:
        units.append(Unit(pending))
    return units


def truncate(steps: list[tuple[str, str]], oks: list[bool]) -> list[tuple[str, str]]:
    """The steps before the first failed one (`oks` may be shorter than `steps`: steps not run)."""
    out = []
    for step, ok in zip(steps, oks):
        if not ok:
            break
        out.append(step)
    return out


def valuable_events(events: list[str]) -> list[str]:
    """The 'valuable moments' among planner events: took hold of an object, or let go of one and it stayed
    on something (not still moving, not on nothing)."""
    out = []
    for e in events:
        m = _STAYED.match(e)
        if _HELD.match(e) or (m and m.group(1) != "nothing"):
            out.append(e)
    return out


def checks_met(checks: list[dict]) -> int:
    return sum(bool(c.get("ok")) for c in checks)


def intrinsic_reward(new_events: list[str], checks_before: list[dict], checks_after: list[dict]) -> float:
    """1 if the branch produced a valuable moment or met one more success condition (e.g. an articulated
    part reached its goal openness), else 0."""
    return 1.0 if valuable_events(new_events) or checks_met(checks_after) > checks_met(checks_before) else 0.0

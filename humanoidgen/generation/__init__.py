"""LLM-driven generation: task scenes (specs) and demonstration scripts (plans), with validation, sandboxed
execution, repair/retry loops, attempt logs and evaluation. Prompt templates live in `humanoidgen/prompts/`."""

from humanoidgen.generation.evaluate import EvalRow, evaluate
from humanoidgen.generation.scene_gen import SceneGenerationError, generate_scene, validate_spec
from humanoidgen.generation.script_gen import AttemptLog, ScriptResult, StepLog, generate_script

__all__ = [
    "AttemptLog",
    "EvalRow",
    "SceneGenerationError",
    "ScriptResult",
    "StepLog",
    "evaluate",
    "generate_scene",
    "generate_script",
    "validate_spec",
]

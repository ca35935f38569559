"""Checks of `str.format` templates in plan code (part of the friendly first layer, `checker`).

A `str.format` replacement field is a tiny expression language of its own: `'{0.random.mtrand}'.format(np)`
reads attributes and `'{0[os]}'.format(mods)` indexes with string keys, neither of which the AST check of
`checker` can see, since they live inside a string. Here a template (the string literal a `.format` is called
on) is parsed the way `str.format` parses it, nested format specs included (`'{0:{1}}'`), and a field may only
name an argument (`{}`, `{0}`, `{name}`), optionally indexed with integers (`{0[1]}`), with any conversion
(`!r`) and format spec (`:.3f`).
"""

from __future__ import annotations

import _string  # the C helpers behind `string.Formatter` (field-name splitting)
from string import Formatter

# `str.format` itself refuses format specs nested more than two levels deep.
MAX_SPEC_NESTING = 2

_WHAT_IS_ALLOWED = ("format fields may only name an argument (`{}`, `{0}`, `{name}`), optionally with an integer "
                    "index (`{0[1]}`) and a format spec (`{0:.3f}`)")


def format_template_problems(template: str) -> list[str]:
    """Why the `str.format` template `template` is not allowed in plan code (empty list: it is fine)."""
    return _template_problems(template, 0)


def _template_problems(template: str, depth: int) -> list[str]:
    try:
        parsed = list(Formatter().parse(template))
    except ValueError as e:
        return [f"malformed format string ({e}); write it as an f-string instead"]
    problems: list[str] = []
    for _literal, field, spec, _conversion in parsed:
        if field is None:
            continue
        problem = _field_problem(field)
        if problem:
            problems.append(problem)
        if spec and "{" in spec:
            if depth >= MAX_SPEC_NESTING:
                problems.append("format spec nested too deeply")
            else:
                problems.extend(_template_problems(spec, depth + 1))
    return problems


def _field_problem(field: str) -> str | None:
    shown = "{" + field + "}"
    try:
        _first, rest = _string.formatter_field_name_split(field)
        parts = list(rest)
    except ValueError as e:
        return f"malformed format field `{shown}` ({e})"
    for is_attribute, key in parts:
        if is_attribute:
            return (f"format field `{shown}` reads the attribute `.{key}`; {_WHAT_IS_ALLOWED}. Compute the "
                    f"value first and format that, e.g. with an f-string: f\"{{x.{key}}}\"")
        if not isinstance(key, int):
            return (f"format field `{shown}` indexes with the non-integer key `[{key}]`; {_WHAT_IS_ALLOWED}. "
                    f"Look the value up first (`v = d['{key}']`) and format that, e.g. f\"{{v}}\"")
    return None

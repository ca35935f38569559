"""The size a family's tasks expect: the range of largest extents of the family's own models (a cup 9.5-11.5 cm
across its handle, a plate 18-24 cm, a drawer's cabinet 26-32 cm). An import with `--fit-family`, and every
model of the library, is scaled into it: the library's meshes come at the sizes their packages' scenes used
(LIBERO's bowls at 0.7 of the scanned ones), and a plan written for the family's models meets sizes it was
written for (a cup on a 14 cm saucer stands on its curved rim, a 5 cm tumbler is too short for a hand to wrap)."""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.imported.model_file import FIRST_IMPORTED_TYPE_ID


def family_size_range(family: str) -> tuple[float, float]:
    """(smallest, largest) largest bounding-box extent (m) of the family's own models (type_ids below 100)."""
    from humanoidgen.objects import library

    fam = library.family(family)
    sizes = [float(np.max(np.subtract(a.bbox_max, a.bbox_min))) for a in
             (fam.annotations(m.type_id) for m in fam.models() if m.type_id < FIRST_IMPORTED_TYPE_ID)]
    if not sizes:
        raise ValueError(f"family {family} has no models of its own to take a size range from")
    return min(sizes), max(sizes)


def largest_extent(family: str, type_id: int) -> float:
    """A model's largest bounding-box extent (m), closed."""
    from humanoidgen.objects import library

    a = library.annotations(family, type_id)
    return float(np.max(np.subtract(a.bbox_max, a.bbox_min)))


def fit_note(fitted: float, family: str, fit: tuple[float, float] | None) -> list[str]:
    """The import's note on a model scaled into its family's size range."""
    if fit is None or abs(fitted - 1.0) < 1e-9:
        return []
    return [f"scaled x{fitted:.3g} into the {family} family's size range ({fit[0]:.3g}-{fit[1]:.3g} m across)"]

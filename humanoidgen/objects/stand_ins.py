"""Which models may stand in for a task's object when each episode draws one (`--randomize-models`): the
family's imported models that offer what its tasks need (`imported/usable.py`) and are about the size of the
model the task was written with."""

from __future__ import annotations

from humanoidgen.objects import library
from humanoidgen.objects.family import ObjectModel
from humanoidgen.objects.imported.sizing import largest_extent
from humanoidgen.objects.imported.usable import unusable_reason

# A model drawn to stand in for a task's object is at most this many times larger or smaller (largest extent)
# than the model the task was written with: the task placed other things by that size (two 3 cm cubes in a cup,
# not two 8 cm cartons). Library models are already in their family's size range (imported/sizing.py).
STAND_IN_RATIO = 1.4


def drawable_models(family_name: str, like: int | None = None) -> list[ObjectModel]:
    """The models a task's episode may draw for an object of this family (`--randomize-models`): its imported
    ones (type_id 100 and up) that offer what the family's tasks need (`imported/usable.py`); with `like` (the
    type_id the task was written with), those within STAND_IN_RATIO of its size."""
    fam = library.family(family_name)
    imported = fam.imported() if hasattr(fam, "imported") else []
    usable = {m.info.type_id for m in imported if unusable_reason(m) is None}
    out = [m for m in fam.models() if m.type_id in usable]
    if like is None:
        return out
    ref = largest_extent(family_name, like)
    return [m for m in out
            if 1.0 / STAND_IN_RATIO <= largest_extent(family_name, m.type_id) / ref <= STAND_IN_RATIO]

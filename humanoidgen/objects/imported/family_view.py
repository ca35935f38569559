"""A family with its imported models: the family's own models (type_id < 100) and those of the model folders
(model_file.py), each built and annotated by whichever it is. The library hands every family out this way."""

from __future__ import annotations

import mujoco

from humanoidgen.objects.family import ObjectFamily, ObjectModel
from humanoidgen.objects.imported.build import build_imported
from humanoidgen.objects.imported.model_file import ImportedModel, imported_models
from humanoidgen.objects.schema import ObjectAnnotations


class WithImported:
    """`base` (an ObjectFamily) plus the imported models of its name."""

    def __init__(self, base: ObjectFamily):
        self.base = base
        self.name = base.name
        self.articulated = base.articulated

    @property
    def static(self) -> bool:
        return bool(getattr(self.base, "static", False))

    def imported(self) -> list[ImportedModel]:
        return imported_models(self.name)

    def _imported(self, type_id: int) -> ImportedModel | None:
        for m in self.imported():
            if m.info.type_id == type_id:
                return m
        return None

    def models(self) -> list[ObjectModel]:
        own = self.base.models()
        return own + [ObjectModel(self.name, m.info.type_id, m.info.description,
                                  {"name": m.info.name, "folder": str(m.folder)}) for m in self.imported()]

    def build(self, spec: mujoco.MjSpec, body: mujoco.MjsBody, type_id: int) -> None:
        m = self._imported(type_id)
        if m is None:
            self.base.build(spec, body, type_id)
        else:
            build_imported(spec, body, m)

    def annotations(self, type_id: int) -> ObjectAnnotations:
        m = self._imported(type_id)
        return self.base.annotations(type_id) if m is None else m.annotations

    def geometry(self, type_id: int):  # the rigid families' primitive geometry (own models only)
        return self.base.geometry(type_id)

    def __getattr__(self, item):  # anything else a family offers (its data, helpers) is the base's
        return getattr(self.base, item)

"""_formats.py - the result formats a run writes per phase and the trajectory exports, as the
libraries register them (lv_result_format_info in lv_io.h, lv_export_format_info in
lv_export.h). Nothing is re-typed here: a format added to a table appears in `formats()`, and
in `Run.execute(formats=...)`, without a change to the package.

    import lvsim
    list(lvsim.formats("results"))          # ["mat", "csv"]
    lvsim.formats()["oem"].file             # "<stage>.oem"
"""
from . import _lib

KINDS = ("results", "exports")


class Format:
    """A registered format: `name` (the word of `--format`, `--outputs`, Run.execute), `kind`
    ("results": a phase's file; "exports": from a results folder), `file` (a result format's
    extension ".mat"; what an export writes, "mission.czml"), `description` (one line)."""

    __slots__ = ("name", "kind", "file", "description")

    def __init__(self, kind, name, file, description):
        self.kind, self.name, self.file, self.description = kind, name, file, description

    def __repr__(self):
        return f"Format({self.name!r}, {self.kind}, {self.file!r})"


def formats(kind=None):
    """The registered formats by name, in the libraries' order (results first): {"mat":
    Format, ...}; `kind` "results" or "exports" keeps those only."""
    if kind is not None and kind not in KINDS:
        raise ValueError(f"kind {kind!r}: 'results' or 'exports'")
    out = {}
    if kind in (None, "results"):
        for name, file, desc in _lib.RESULT_FORMATS:
            out[name] = Format("results", name, file, desc)
    if kind in (None, "exports"):
        for name, file, desc in _lib.format_table(_lib.post().lv_export_format_info):
            out[name] = Format("exports", name, file, desc)
    return out

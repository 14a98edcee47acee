"""_laws.py - the steering and throttle laws, as the library registers them (lv_guidance.h,
lv_laws_get): each law's keys with their units, ranges, defaults and descriptions. Nothing
about a law is written here: a law added to the library appears in `laws()` (and in a
mission's parameters as "<phase>.guidance.<key>") without a change to the package.

    import lvsim
    gt = lvsim.laws()["gravity_turn"]
    gt.key("kick").unit, gt.key("kick").required      # "rad", True
    [k.name for k in gt.keys]                          # rise_time, kick, kick_time, heading
"""
import math
from ctypes import byref, c_size_t

from . import _lib
from ._lib import lib, text
from .errors import check

KINDS = ("steering", "throttle")
FORMS = ("none", "named", "keys", "nested", "word")
TYPES = ("number", "table", "choice")
KEY_ANGLE, KEY_OPTIONAL, KEY_DOF3 = 1, 2, 4


class LawKey:
    """A key of a law: `name`, `type` ("number", "table", "choice"), `unit` (SI; "1" when
    dimensionless, "" for a table or a choice), `lo`, `hi`, `lo_open`, `hi_open` (the values allowed), `default` (SI; NaN
    when required or absent), `required`, `optional` (absent: no run parameter), `angle`
    (also taken in degrees as NAME_deg), `dof3_only`, `frames` (the frames it applies in, or
    None: all), `instead_of` (the table that replaces it), `needs` (the key it applies with),
    `choices` (a choice's words), `description`."""

    __slots__ = ("name", "type", "unit", "lo", "hi", "lo_open", "hi_open", "default",
                 "required", "optional", "angle", "dof3_only", "frames", "instead_of", "needs",
                 "choices", "description")

    def __init__(self, k, frame_words):
        self.name = text(k.name)
        self.type = TYPES[k.type]
        self.unit = text(k.unit) or ""
        self.lo, self.hi = k.lo, k.hi
        self.lo_open, self.hi_open = bool(k.lo_open), bool(k.hi_open)
        self.angle = bool(k.flags & KEY_ANGLE)
        self.optional = bool(k.flags & KEY_OPTIONAL)
        self.dof3_only = bool(k.flags & KEY_DOF3)
        self.choices = []
        if k.choices:
            i = 0
            while k.choices[i]:
                self.choices.append(text(k.choices[i]))
                i += 1
        self.instead_of = text(k.instead_of) if k.instead_of else None
        self.needs = text(k.needs) if k.needs else None
        self.required = self.type == "number" and math.isnan(k.dflt) and not self.optional
        if self.type == "choice":
            self.default = self.choices[int(k.dflt)]
        elif self.type == "table":
            self.default = None
        else:
            self.default = k.dflt
        self.frames = ([w for i, w in enumerate(frame_words) if k.frames & (1 << i)]
                       if k.frames else None)
        self.description = text(k.description) or ""

    def holds(self, value):
        """True when number `value` (SI) is one this key takes."""
        return (self.type == "number" and math.isfinite(value)
                and (value > self.lo if self.lo_open else value >= self.lo)
                and (value < self.hi if self.hi_open else value <= self.hi))

    def __repr__(self):
        return f"LawKey({self.name!r}, {self.unit!r}, {self.type})"


class Law:
    """A steering or throttle law: `name` (what a mission file writes), `kind` ("steering",
    "throttle"), `form` (how a file writes it: "named" `guidance: {law: NAME}`, "keys"
    `throttle: {KEY: ..}`, "nested" `throttle: {NAME: {..}}`, "word" `throttle: NAME`,
    "none": no `guidance:`), `description`, `needs_aero` (why it needs `aero:`, or None),
    `keys` (list of LawKey, in file order)."""

    __slots__ = ("name", "kind", "form", "description", "needs_aero", "keys")

    def __init__(self, info):
        self.name = text(info.name)
        self.kind = KINDS[info.kind]
        self.form = FORMS[info.form]
        self.description = text(info.description) or ""
        self.needs_aero = text(info.needs_aero) if info.needs_aero else None
        raw = [info.keys[i] for i in range(info.n_keys)]
        frame_words = next((LawKey(k, []).choices for k in raw if k.type == 2), [])
        self.keys = [LawKey(k, frame_words) for k in raw]

    def key(self, name):
        """The key `name` ("kick"; "kick_deg" finds kick); KeyError otherwise."""
        base = name[:-4] if name.endswith("_deg") else name
        for k in self.keys:
            if k.name == name or (k.angle and k.name == base):
                return k
        raise KeyError(f"law '{self.name}' has no key '{name}' (its keys: "
                       f"{', '.join(k.name for k in self.keys) or 'none'})")

    def __repr__(self):
        return f"Law({self.name!r}, {self.kind}, {len(self.keys)} keys)"


def laws(kind=None):
    """The registered laws by name, in the library's order: {"gravity_turn": Law, ...};
    `kind` "steering" or "throttle" keeps those only."""
    if kind is not None and kind not in KINDS:
        raise ValueError(f"kind {kind!r}: 'steering' or 'throttle'")
    out = {}
    for i in range(lib.lv_laws_count()):
        info = _lib.lv_law_info()
        err = _lib.lv_err()
        check(lib.lv_laws_get(i, byref(info), byref(err)), err)
        law = Law(info)
        if kind is None or law.kind == kind:
            out[law.name] = law
    return out


def common_keys(kind="steering"):
    """The keys every law of `kind` takes besides its own (steering: target_lat,
    target_lon), as LawKey."""
    if kind not in KINDS:
        raise ValueError(f"kind {kind!r}: 'steering' or 'throttle'")
    n = c_size_t(0)
    ptr = lib.lv_laws_common_keys(KINDS.index(kind), byref(n))
    return [LawKey(ptr[i], []) for i in range(n.value)]

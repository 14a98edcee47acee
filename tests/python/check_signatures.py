#!/usr/bin/python3
"""check_signatures.py - the Python package's ctypes prototypes against the public headers.

Usage: check_signatures.py INCLUDE_DIR   (PYTHONPATH holds the built package)

python/lvsim/_lib.py declares the return and argument types of every C function it calls
(ctypes cannot read headers). This test reads every `LV_API` declaration of include/lvsim/*.h,
maps its C types to ctypes and compares them with the prototypes the package set, function by
function: a header change that is not made in _lib.py too (an argument added, a type changed)
fails here instead of corrupting memory at run time. The structures' layouts are checked by
py_layout.c and test_python.py; this checks the functions.

Type rules (what ctypes must say for a C type): void -> None; int, lv_status and every enum
-> c_int; unsigned -> c_uint; double, size_t, long, uint64_t -> their ctypes; char * (const or
not) -> c_char_p; a pointer to a structure the package mirrors -> POINTER(that structure);
a pointer to an opaque handle or to void -> c_void_p; T ** -> POINTER(<rule for T *>); a
pointer to a number -> POINTER(its ctypes); a function pointer typedef -> the package's
CFUNCTYPE of the same name (checked by name only).
Exit 0 when every prototype matches; one line per mismatch otherwise.
"""
import ctypes
import glob
import os
import re
import sys

from lvsim import _lib

SCALARS = {"int": ctypes.c_int, "lv_status": ctypes.c_int, "unsigned": ctypes.c_uint,
           "unsigned int": ctypes.c_uint, "double": ctypes.c_double, "size_t": ctypes.c_size_t,
           "long": ctypes.c_long, "uint64_t": ctypes.c_uint64, "char": ctypes.c_char,
           "unsigned char": ctypes.c_ubyte, "lv_vref": ctypes.c_uint}


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def declarations(include_dir):
    """{name: (return type text, [argument type texts], header)} of every LV_API function."""
    out, enums, fnptrs = {}, set(), set()
    for path in sorted(glob.glob(os.path.join(include_dir, "lvsim", "*.h"))):
        text = strip_comments(open(path).read())
        text = re.sub(r"^\s*#.*?(?<!\\)$", " ", text, flags=re.M | re.S)  # directives
        enums.update(re.findall(r"typedef\s+enum\s+\w*\s*\{[^}]*\}\s*(\w+)\s*;", text))
        fnptrs.update(re.findall(r"typedef\s+[^;(]*\(\s*\*\s*(\w+)\s*\)\s*\(", text))
        for m in re.finditer(r"\bLV_API\b([^;{]*?)\b(\w+)\s*\(([^;{]*?)\)\s*;", text):
            ret, name, args = m.group(1), m.group(2), m.group(3)
            args = [a.strip() for a in split_args(args)]
            if args == ["void"]:
                args = []
            out[name] = (" ".join(ret.split()), [strip_name(a) for a in args],
                         os.path.basename(path))
    return out, enums, fnptrs


def split_args(s):
    depth, cur, out = 0, "", []
    for ch in s:
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        if ch == "," and depth == 0:
            out.append(cur)
            cur = ""
        else:
            cur += ch
    if cur.strip():
        out.append(cur)
    return out


def strip_name(arg):
    """The type of a parameter declaration ("const char *name" -> "const char *",
    "double x[3]" -> "double *")."""
    arg = " ".join(arg.split())
    arr = re.match(r"^(.*?)\s*\b\w+\s*\[[^\]]*\]$", arg)
    if arr:
        return arr.group(1) + " *"
    bare = re.sub(r"\bconst\b", "", arg).strip()
    if bare in SCALARS or "*" not in arg and len(bare.split()) == 1:
        return arg  # a type without a parameter name ("double", "lv_status")
    m = re.match(r"^(.*?[\s*])(\w+)$", arg)
    return m.group(1).strip() if m else arg


def expected(ctype, enums, fnptrs):
    """What ctypes must say for the C type text `ctype`: a comparable description."""
    t = re.sub(r"\bconst\b", "", ctype)
    t = " ".join(t.replace("*", " * ").split())
    stars = t.count("*")
    base = t.replace("*", "").strip()
    if base in enums:
        base = "int"
    if stars == 0:
        if base == "void":
            return "None"
        if base in SCALARS:
            return SCALARS[base].__name__
        if base in fnptrs:
            return "fn:" + base
        return "struct-by-value:" + base
    desc = None
    if base == "char":
        desc = "c_char_p"
        stars -= 1
    elif base in SCALARS:
        desc = "POINTER(%s)" % SCALARS[base].__name__
        stars -= 1
    elif base == "void":
        desc = "c_void_p"
        stars -= 1
    else:
        mirrored = getattr(_lib, base, None)
        if isinstance(mirrored, type) and issubclass(mirrored, ctypes.Structure):
            desc = "POINTER(%s)" % base
        else:
            desc = "c_void_p"  # an opaque handle (lv_mission *, lv_run *)
        stars -= 1
    for _ in range(stars):
        desc = "POINTER(%s)" % desc
    return desc


def actual(t):
    """ctypes' type as the same kind of description."""
    if t is None:
        return "None"
    if t is ctypes.c_char_p:
        return "c_char_p"
    if t is ctypes.c_void_p:
        return "c_void_p"
    if isinstance(t, type) and issubclass(t, ctypes._Pointer):
        return "POINTER(%s)" % actual(t._type_)
    if isinstance(t, type) and issubclass(t, ctypes._CFuncPtr):
        return "fn"
    if isinstance(t, type) and issubclass(t, ctypes.Structure):
        return t.__name__
    for name in ("c_int", "c_uint", "c_double", "c_size_t", "c_long", "c_uint64", "c_char",
                 "c_ubyte"):
        if t is getattr(ctypes, name):
            return ctypes.__dict__[name].__name__
    return repr(t)


def same(exp, act):
    if exp.startswith("fn:"):
        return act == "fn"
    return exp == act


def compare(decls, enums, fnptrs):
    """(mismatch lines, prototypes checked)."""
    libs = [("liblvsim", _lib.lib), ("liblvsim_post", _lib.post())]
    bad, n = [], 0
    for lname, dll in libs:
        for name, f in sorted(vars(dll).items()):
            if not isinstance(f, ctypes._CFuncPtr) or f.argtypes is None:
                continue
            n += 1
            if name not in decls:
                bad.append(f"{name}: declared in python/lvsim/_lib.py ({lname}) but in no "
                           "public header")
                continue
            ret, args, header = decls[name]
            if not same(expected(ret, enums, fnptrs), actual(f.restype)):
                bad.append(f"{name} ({header}): returns {ret!r} = "
                           f"{expected(ret, enums, fnptrs)}, _lib.py says {actual(f.restype)}")
            if len(args) != len(f.argtypes):
                bad.append(f"{name} ({header}): {len(args)} arguments ({', '.join(args)}), "
                           f"_lib.py gives {len(f.argtypes)}")
                continue
            for i, (a, t) in enumerate(zip(args, f.argtypes)):
                if not same(expected(a, enums, fnptrs), actual(t)):
                    bad.append(f"{name} ({header}): argument {i + 1} {a!r} = "
                               f"{expected(a, enums, fnptrs)}, _lib.py says {actual(t)}")
    return bad, n


def main():
    decls, enums, fnptrs = declarations(sys.argv[1])
    # the check itself must see a wrong prototype: lv_run_set's value (double) as an int
    f = _lib.lib.lv_run_set
    saved = f.argtypes
    f.argtypes = [saved[0], saved[1], ctypes.c_int, saved[3]]
    wrong, _ = compare(decls, enums, fnptrs)
    f.argtypes = saved
    if not any(w.startswith("lv_run_set ") and "argument 3" in w for w in wrong):
        print("self-test: a wrong prototype of lv_run_set was not reported:", wrong)
        return 1
    bad, n = compare(decls, enums, fnptrs)
    for line in bad:
        print(line)
    print(f"{n} prototypes checked against {len(decls)} declarations: "
          f"{len(bad)} mismatch{'es' if len(bad) != 1 else ''}")
    if n < 50:
        print("too few prototypes found: is the package's _lib.py read at all?")
        return 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

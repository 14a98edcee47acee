#!/usr/bin/python3
"""check_manifest.py - an independent check of a results folder against its manifest.json.

Usage: check_manifest.py OUTDIR [--mission FILE] [--status ok|failed] [--name MISSION_NAME]
                          [--foreign NAME,NAME...] [--stream PATTERN,PATTERN...]

Checks, with Python's own hashlib and os.walk (nothing of lvsim):
  - manifest.json parses and lists exactly the regular files under OUTDIR (manifest.json
    itself aside): none missing, none extra (no .tmp file, no staging folder);
  - every listed file has the listed size and SHA-256;
  - summary.json names the same mission and status as the manifest, and every phase file
    it names is in the manifest (one run's files, not a mix of two);
  - with --mission: the manifest's mission SHA-256 is the file's; --status, --name: the
    manifest says so; --foreign: these files (the user's, kept by --force) are in OUTDIR and
    not in the manifest;
  - every file that carries lvsim's record of the digest computed as it was written
    (extended attribute user.lvsim.sha256: "<sha256> <bytes> <st_dev> <st_ino> <s>.<ns>",
    src/io/atomic.h) for its current identity has the digest hashlib computes; with
    --stream: every listed file whose name matches one of these fnmatch patterns carries
    such a record (it was written through lvsim's hashing stream and not read again for the
    manifest; skipped where the file system has no user extended attributes).
Exit 0 when every check passes; otherwise the failures, one a line, and exit 1.
"""
import errno
import fnmatch
import hashlib
import json
import os
import sys


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 16), b""):
            h.update(chunk)
    return h.hexdigest()


def record(path):
    """lvsim's digest record on path when it names the file as it is now, else None."""
    try:
        rec = os.getxattr(path, "user.lvsim.sha256", follow_symlinks=False).decode()
    except OSError:
        return None
    parts = rec.split(" ")
    st = os.lstat(path)
    if len(parts) != 5 or "." not in parts[4]:
        return None
    sec, nsec = parts[4].split(".")
    if (int(parts[1]), int(parts[2]), int(parts[3]), int(sec) * 10**9 + int(nsec)) != \
            (st.st_size, st.st_dev, st.st_ino, st.st_mtime_ns):
        return None
    return parts[0]


def xattrs_work(folder):
    probe = os.path.join(folder, ".check_manifest_xattr_probe")
    try:
        open(probe, "w").close()
        os.setxattr(probe, "user.probe", b"1")
        return True
    except OSError as e:
        if e.errno in (errno.ENOTSUP, errno.EOPNOTSUPP):
            return False
        raise
    finally:
        if os.path.exists(probe):
            os.remove(probe)


def main(argv):
    outdir = argv[1]
    opts = dict(zip(argv[2::2], argv[3::2]))
    fails = []
    with open(os.path.join(outdir, "manifest.json")) as f:
        man = json.load(f)
    listed = {e["name"]: e for e in man["files"]}
    found = set()
    for root, dirs, files in os.walk(outdir):
        for name in files:
            rel = os.path.relpath(os.path.join(root, name), outdir)
            if rel != "manifest.json":
                found.add(rel)
    foreign = set(opts["--foreign"].split(",")) if "--foreign" in opts else set()
    for name in sorted(foreign):
        if name in listed:
            fails.append("a user's file in the manifest: %s" % name)
        if name not in found:
            fails.append("a user's file is gone: %s" % name)
    for name in sorted(found - set(listed) - foreign):
        fails.append("not in the manifest: %s" % name)
    for name in sorted(set(listed) - found):
        fails.append("in the manifest, missing: %s" % name)
    for name in sorted(found & set(listed)):
        path = os.path.join(outdir, name)
        if os.path.getsize(path) != listed[name]["bytes"]:
            fails.append("%s: %d bytes, the manifest says %d" % (name, os.path.getsize(path),
                                                                 listed[name]["bytes"]))
        elif sha256(path) != listed[name]["sha256"]:
            fails.append("%s: SHA-256 differs from the manifest's" % name)
        rec = record(path)
        if rec is not None and rec != sha256(path):
            fails.append("%s: its record's SHA-256 differs from the file's" % name)
        if name.endswith(".tmp") or ".staging-" in name:
            fails.append("a temporary file in the results: %s" % name)
    if "summary.json" in listed:
        with open(os.path.join(outdir, "summary.json")) as f:
            summ = json.load(f)
        if man.get("mission", {}).get("name") not in (None, summ["mission"]):
            fails.append("manifest mission %r, summary mission %r" %
                         (man["mission"]["name"], summ["mission"]))
        if summ.get("status") != man.get("status"):
            fails.append("manifest status %r, summary status %r" %
                         (man.get("status"), summ.get("status")))
        for ph in summ["phases"]:
            for kind, name in ph.get("files", {}).items():
                if name not in listed:
                    fails.append("phase %s: its %s file %s is not in the manifest" %
                                 (ph["name"], kind, name))
    if "--stream" in opts and xattrs_work(os.path.dirname(os.path.abspath(outdir))):
        pats = opts["--stream"].split(",")
        for name in sorted(found & set(listed)):
            if any(fnmatch.fnmatch(name, p) for p in pats) and \
                    record(os.path.join(outdir, name)) is None:
                fails.append("%s: no digest record (not hashed as it was written)" % name)
    if "--mission" in opts and man["mission"]["sha256"] != sha256(opts["--mission"]):
        fails.append("manifest mission SHA-256 is not that of %s" % opts["--mission"])
    if "--status" in opts and man["status"] != opts["--status"]:
        fails.append("status %r, expected %r" % (man["status"], opts["--status"]))
    if "--name" in opts and man["mission"]["name"] != opts["--name"]:
        fails.append("mission %r, expected %r" % (man["mission"]["name"], opts["--name"]))
    for f in fails:
        print("check_manifest: %s: %s" % (outdir, f))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

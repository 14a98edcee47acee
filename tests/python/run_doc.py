#!/usr/bin/env python3
"""run_doc.py DOC.md - runs every ```python block of a Markdown file, in order, in one namespace
(as a reader would paste them into one session), from a temporary folder holding a link to
the source tree's examples/ (so the doc's paths "examples/..." work and nothing is written into
the sources). A block that raises fails the test, with the block's first line. Prints
"N passed, 0 failed" (blocks)."""
import os
import re
import sys
import tempfile
import traceback

doc = os.path.abspath(sys.argv[1])
root = os.path.dirname(os.path.dirname(doc))
with open(doc, encoding="utf-8") as f:
    blocks = re.findall(r"^```python\n(.*?)^```", f.read(), flags=re.S | re.M)
if not blocks:
    print(f"{doc}: no ```python block")
    sys.exit(1)
ns = {"__name__": "__doc__"}
with tempfile.TemporaryDirectory() as tmp:
    os.symlink(os.path.join(root, "examples"), os.path.join(tmp, "examples"))
    os.chdir(tmp)
    for i, code in enumerate(blocks, 1):
        try:
            exec(compile(code, f"{doc}:block {i}", "exec"), ns)
        except Exception:
            traceback.print_exc()
            print(f"block {i} of {len(blocks)} failed: {code.splitlines()[0]!r}")
            print(f"{i - 1} passed, 1 failed")
            sys.exit(1)
print(f"{len(blocks)} passed, 0 failed")

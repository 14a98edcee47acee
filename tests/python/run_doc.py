#!/usr/bin/env python3
"""run_doc.py SOURCE_DIR DOC.md... - runs every ```python block of each Markdown file, in
order, in one namespace per file (as a reader would paste them into one session), from a
temporary folder holding a link to the source tree's examples/ (so the docs' paths
"examples/..." work and nothing is written into the sources). A block that raises fails the
test, naming the file and the block's first line. Prints "N passed, M failed" (blocks)."""
import os
import re
import sys
import tempfile
import traceback

root = os.path.abspath(sys.argv[1])
passed = failed = 0
with tempfile.TemporaryDirectory() as tmp:
    os.symlink(os.path.join(root, "examples"), os.path.join(tmp, "examples"))
    os.chdir(tmp)
    for doc in sys.argv[2:]:
        doc = os.path.abspath(os.path.join(root, doc))
        with open(doc, encoding="utf-8") as f:
            blocks = re.findall(r"^```python\n(.*?)^```", f.read(), flags=re.S | re.M)
        if not blocks:
            print(f"{doc}: no ```python block")
            failed += 1
            continue
        ns = {"__name__": "__doc__"}
        for i, code in enumerate(blocks, 1):
            try:
                exec(compile(code, f"{doc}:block {i}", "exec"), ns)
                passed += 1
            except Exception:
                traceback.print_exc()
                print(f"{doc}: block {i} of {len(blocks)} failed: {code.splitlines()[0]!r}")
                failed += 1
                break  # the later blocks build on this one
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)

#!/usr/bin/python3
"""Regenerates the tables that tests measure in the documentation (docs/verification/*.md).

A document marks each generated block with

    <!-- tables from FILTER: begin -->
    ... (written by this script) ...
    <!-- tables: end -->

where FILTER is a GoogleTest filter (e.g. PeridynamicsQuadratureEnergy.BulkTensorErrorTable). The script runs
the test binary with that filter and copies the Markdown the test prints (table rows starting with '|',
their headings in bold and the blank lines between them) into the block. The prose around the blocks is
written by hand and reads the numbers; `--check` says whether a block is out of date.

Usage: scripts/make_doc_tables.py [--tests build/tests/perimorph_tests] [--check] [DOC ...]
(default: every docs/**/*.md with such a block). Exit 1 with --check when a block differs, or when a test fails.
"""

import argparse
import glob
import os
import re
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BLOCK = re.compile(r"(<!-- tables from (\S+): begin -->\n)(.*?)(<!-- tables: end -->)", re.S)


def printed_markdown(binary, test_filter):
    p = subprocess.run([binary, f"--gtest_filter={test_filter}"], capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    if p.returncode != 0 or "[  PASSED  ]" not in p.stdout:
        sys.exit(f"error: {binary} --gtest_filter={test_filter} failed (exit {p.returncode}); tables come from "
                 f"passing tests:\n{p.stdout[-3000:]}")
    keep = []
    for line in p.stdout.splitlines():
        if line.startswith("|") or line.startswith("**"):
            keep.append(line)
        elif not line.strip() and keep and keep[-1] != "":
            keep.append("")
    text = "\n".join(keep).strip()
    if not text:
        sys.exit(f"error: {test_filter} printed no Markdown table")
    return text + "\n"


def update(doc, binary, check):
    with open(doc) as f:
        text = f.read()
    blocks = BLOCK.findall(text)
    if not blocks:
        return None
    stale = []

    def render(m):
        new = printed_markdown(binary, m.group(2))
        if new.strip() != m.group(3).strip():
            stale.append(m.group(2))
        return m.group(1) + new + m.group(4)

    new_text = BLOCK.sub(render, text)
    rel = os.path.relpath(doc, REPO)
    if check:
        print(f"{rel}: " + (f"out of date: {', '.join(stale)}" if stale else "up to date"))
    elif new_text != text:
        with open(doc, "w") as f:
            f.write(new_text)
        print(f"wrote {rel} ({len(blocks)} blocks)")
    else:
        print(f"{rel}: unchanged")
    return not stale


def main():
    ap = argparse.ArgumentParser(description=__doc__.strip().split("\n")[0])
    ap.add_argument("docs", nargs="*")
    ap.add_argument("--tests", default=os.path.join(REPO, "build", "tests", "perimorph_tests"))
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    docs = args.docs or sorted(glob.glob(os.path.join(REPO, "docs", "**", "*.md"), recursive=True))
    results = [update(d, args.tests, args.check) for d in docs]
    return 1 if args.check and any(r is False for r in results) else 0


if __name__ == "__main__":
    sys.exit(main())

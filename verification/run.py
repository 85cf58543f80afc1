#!/usr/bin/python3
"""perimorph's verification suite: runs BENCHMARKS.md's cases B1–B8 (all, or those named), full or reduced,
and writes the summary table verification/README.md (full size) from every case's report.

    verification/run.py                      # every case, full size: verification/results/, README.md
    verification/run.py b2 b6                # named cases (by id or script name)
    verification/run.py --reduced            # every case at its reduced size (CI), under build/verification/
    verification/run.py --summary            # only rewrite README.md from the reports in results/

Runs are cached per binary (verification/.cache/, keyed by the binary's md5 and the case text), so a report
can be regenerated without running the program again. Exit status 1 when a criterion fails without a
measured reason ("fails: reason" does not count, FAIL does).
"""

import importlib
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pmverify.report import md_table  # noqa: E402
from pmverify.suite import CASES, RESULTS, make_context, parser, run_case  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def select(names):
    if not names:
        return CASES
    out = []
    for n in names:
        hits = [c for c in CASES if c == n or c.split("_")[0] == n.lower()]
        if not hits:
            raise SystemExit(f"error: no case {n!r}; the cases are {', '.join(CASES)} (or b1 ... b8)")
        out += hits
    return out


def summary(results=RESULTS, path=os.path.join(HERE, "README.md")):
    """verification/README.md: one row per criterion of every case report in `results`."""
    rows, cases = [], []
    for name in CASES:
        js = os.path.join(results, name + ".json")
        if not os.path.isfile(js):
            cases.append((name, None))
            continue
        with open(js) as f:
            rep = json.load(f)
        cases.append((name, rep))
        link = f"[{rep['case']}](results/{rep['report']})"
        for c in rep["criteria"]:
            status = c["status"] if c["status"] in ("PASS", "info") else f"**{c['status']}**"
            rows.append((link, c["id"], c["text"], c["ours"], c["bar"], c["thesis"], status))
    counts = {}
    for *_, s in rows:
        k = "PASS" if s == "PASS" else "info" if s == "info" else "FAIL" if s == "**FAIL**" else "fails: reason"
        counts[k] = counts.get(k, 0) + 1
    L = ["# Verification: BENCHMARKS.md B1–B8", "",
         "Written by `verification/run.py` from the case reports in [results/](results/) on "
         f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}. Each report names the command, the program "
         "binary (md5 and the commit it was built from) and every run; each case script holds only its "
         "parameters, criteria and figures, the rest is the shared library [pmverify/](pmverify/).", "",
         "Verdicts: PASS; **FAIL** (not met, unexplained); **fails: reason** (not met for a reason in the model, "
         "measured in the report: BENCHMARKS.md lets such a case stand and leaves the bar to its owner); info "
         "(no bar). Criteria C… are BENCHMARKS.md's; K… check the program against an independent computation "
         "of the same quantity.", "",
         "Totals: " + ", ".join(f"{v} {k}" for k, v in sorted(counts.items())) + ".", "",
         "| case | report | mode | program | figures |", "|---|---|---|---|---|"]
    for name, rep in cases:
        if rep is None:
            L.append(f"| {name} | not run | | | |")
            continue
        figs = ", ".join(f"[{f}](results/{f})" for f in rep.get("figures", []))
        L.append(f"| {rep['case']} {rep['title']} | [{rep['report']}](results/{rep['report']}) | {rep['mode']} | "
                 f"commit {rep['program']['commit']}, md5 {rep['program']['md5'][:12]} | {figs} |")
    L += ["", md_table(["case", "id", "criterion", "ours", "bar", "thesis", "result"], rows), "",
          "Reduced sizes run in CI: `ctest -L verification` (each case's script with `--reduced`); the full sizes "
          "with `verification/run.py`.", ""]
    with open(path, "w") as f:
        f.write("\n".join(L))
    print(f"wrote {os.path.relpath(path)}")


def main(argv):
    ap = parser(__doc__.strip().split("\n")[0])
    ap.add_argument("cases", nargs="*", help="b1 … b6 or script names (default: all)")
    ap.add_argument("--summary", action="store_true", help="only rewrite README.md from the existing reports")
    args = ap.parse_args(argv)
    if args.summary:
        summary()
        return 0
    ctx = make_context(args, ["verification/run.py"] + argv)
    failed = []
    for name in select(args.cases):
        module = importlib.import_module(name)
        rep = run_case(module, ctx)
        if rep.failed:
            failed.append(module.CASE_ID)
    if not args.reduced and os.path.abspath(ctx.results) == os.path.abspath(RESULTS):
        summary()
    if failed:
        print(f"criteria failed without a measured reason in: {', '.join(failed)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

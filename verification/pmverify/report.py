"""Criteria and reports.

A Criterion is one line of a benchmark's bar (BENCHMARKS.md) or one check of the program against an
independent computation: what is compared, our value, the bar, the thesis' figure and the verdict:

  PASS              the bar is met
  FAIL              the bar is not met and nothing measured explains it: a bug until shown otherwise
  fails: REASON     the bar is not met for a reason in the model, measured by the script (BENCHMARKS.md:
                    such a case is reported, it does not block); REASON must quote the measurement
  info              reported without a bar

A Report collects a case's criteria, text, tables and figures and writes RESULTS/NAME.md and NAME.json;
verification/run.py gathers the JSON of every case into verification/README.md.
"""

import dataclasses
import json
import math
import os
import time

import numpy as np

from .program import REPO


@dataclasses.dataclass
class Criterion:
    id: str          # C1, C2 ... (BENCHMARKS' bar), K1 ... (checks against independent computations)
    text: str        # what is compared, in words
    ours: str        # our value(s)
    bar: str         # the pass condition
    thesis: str      # what the thesis reports ("—" if nothing)
    passed: bool = None   # None: information only
    reason: str = None    # for a failure with a measured model reason
    detail: str = ""      # numbers behind the verdict

    @property
    def status(self):
        if self.passed is None:
            return "info"
        if self.passed:
            return "PASS"
        return f"fails: {self.reason}" if self.reason else "FAIL"

    @property
    def failed(self):
        """Unexplained failure (turns the exit status and CI red)."""
        return self.passed is False and not self.reason


def pyplot():
    """matplotlib.pyplot on the file-only Agg backend (the scripts run without a display)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def fmt(v, spec=".4g"):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "—"
    return format(v, spec)


def pct(v, spec=".3f"):
    return "—" if v is None or (isinstance(v, float) and math.isnan(v)) else format(100 * v, spec) + "%"


def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c).replace("|", "\\|") for c in r) + " |" for r in rows]
    return "\n".join(out)


def to_json(v):
    if isinstance(v, (np.floating, np.integer, np.bool_)):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    if isinstance(v, dict):
        return {str(k): to_json(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [to_json(x) for x in v]
    if isinstance(v, np.ndarray):
        return to_json(v.tolist())
    if dataclasses.is_dataclass(v):
        return to_json(dataclasses.asdict(v))
    return v


class Report:
    """One case's report. `name` is the file stem in the results folder (e.g. b2_plate_uniform)."""

    def __init__(self, ctx, case_id, name, title):
        self.ctx, self.case_id, self.name, self.title = ctx, case_id, name, title
        self.criteria = []
        self.blocks = []      # Markdown blocks after the criteria table
        self.intro = []       # Markdown blocks before it
        self.data = {}        # extra figures for the JSON
        self.figures = []     # (file name, caption)

    # ------------------------------------------------------------------ content
    def criterion(self, id, text, ours, bar, thesis="—", passed=None, reason=None, detail=""):
        c = Criterion(id, text, ours, bar, thesis, None if passed is None else bool(passed), reason, detail)
        self.criteria.append(c)
        return c

    def describe(self, *paragraphs):
        """Set-up text shown before the criteria."""
        self.intro += list(paragraphs)

    def add(self, *blocks):
        """Markdown blocks after the criteria."""
        self.blocks += list(blocks)

    def section(self, title, *blocks):
        self.blocks.append(f"## {title}")
        self.blocks += list(blocks)

    def table(self, header, rows):
        self.blocks.append(md_table(header, rows))

    def figure_path(self, stem):
        """Where a figure of this report goes (RESULTS/NAME_STEM.png, the folder made); add it with figure()."""
        os.makedirs(self.ctx.results, exist_ok=True)
        return os.path.join(self.ctx.results, f"{self.name}{'_' + stem if stem else ''}.png")

    def figure(self, path, caption):
        self.figures.append((os.path.basename(path), caption))

    def save_figure(self, fig, path, caption, dpi=80):
        """Saves a matplotlib figure to `path` (from figure_path), closes it and adds it with its caption."""
        fig.savefig(path, dpi=dpi)
        pyplot().close(fig)
        self.figure(path, caption)

    # ------------------------------------------------------------------ output
    @property
    def failed(self):
        return any(c.failed for c in self.criteria)

    def markdown(self):
        ctx = self.ctx
        L = [f"# {self.case_id} — {self.title}", "",
             f"Generated by `{ctx.command_line()}` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}"
             f" ({ctx.mode} size); program {ctx.program.describe()}. {ctx.run_summary()}", ""]
        L += _blocks(self.intro)
        L += ["## Criteria", "",
              md_table(["id", "criterion", "ours", "bar", "thesis", "result"],
                       [(c.id, c.text, c.ours, c.bar, c.thesis, _bold(c.status)) for c in self.criteria]), ""]
        details = [(c.id, c.detail) for c in self.criteria if c.detail]
        if details:
            L += ["Numbers behind the verdicts:", ""] + [f"- **{i}**: {d}" for i, d in details] + [""]
        L += _blocks(self.blocks)
        for fn, caption in self.figures:
            L += [f"![{caption}]({fn})", "", f"*{caption}*", ""]
        return "\n".join(L).rstrip() + "\n"

    def write(self):
        os.makedirs(self.ctx.results, exist_ok=True)
        md = os.path.join(self.ctx.results, self.name + ".md")
        with open(md, "w") as f:
            f.write(self.markdown())
        js = os.path.join(self.ctx.results, self.name + ".json")
        with open(js, "w") as f:
            json.dump(to_json({"case": self.case_id, "title": self.title, "report": self.name + ".md",
                               "mode": self.ctx.mode, "program": self.ctx.program.provenance(),
                               "command": self.ctx.command_line(), "runs": self.ctx.runs_json(),
                               "criteria": [dict(dataclasses.asdict(c), status=c.status) for c in self.criteria],
                               "figures": [fn for fn, _ in self.figures], "data": self.data}), f, indent=1)
        print(f"wrote {os.path.relpath(md, REPO) if md.startswith(REPO) else md}")
        for c in self.criteria:
            print(f"  {c.id:4s} {c.status[:100]:20s} {c.text[:90]}")
        return md


def _bold(status):
    return status if status in ("PASS", "info") else f"**{status}**"


def _blocks(blocks):
    out = []
    for b in blocks:
        out += [b, ""]
    return out

"""pmverify: the shared library of perimorph's verification suite (BENCHMARKS.md B1–B6).

Each case script (verification/bN_*.py) holds only its parameters, criteria and figures; everything else
lives here once:

  program    running `perimorph` on a case, with a cache keyed by the binary's hash and the case text
  template   case files made from an example's case.toml by setting keys (comments and layout kept)
  fields     the run's CSV and VTU read into numpy arrays, cells placed on their structured grid
  report     criteria (PASS / FAIL / "fails: reason" / info), Markdown + JSON reports, provenance
  suite      the command line of a case script and of verification/run.py (all or named cases)
  reference  the independent numpy physics the program is checked against (kernels, calibration,
             quadrature, α profiles, the cut rule, ...): written from THEORY.md, sharing no code with C++
"""

from .program import Program, RunSpec, RunResult  # noqa: F401
from .template import CaseTemplate  # noqa: F401
from .report import Criterion, Report, md_table, fmt, pct, pyplot  # noqa: F401
from .suite import Context, case_main  # noqa: F401

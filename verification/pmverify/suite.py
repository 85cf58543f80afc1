"""The command line shared by every case script and by verification/run.py.

A case script is a module verification/bN_name.py with

    CASE_ID = "B2"                       # BENCHMARKS.md's id
    NAME = "b2_plate_uniform"            # report file stem (results/NAME.md, .json, NAME_*.png)
    TITLE = "2D plate, uniform extension and shear (thesis §2.6.1, figs. 2.9–2.13)"
    def run(ctx) -> Report               # parameters, runs, criteria and figures of the case

    if __name__ == "__main__":
        sys.exit(case_main(sys.modules[__name__]))

`ctx.reduced` says which size to run: the full size (BENCHMARKS.md) writes verification/results/; the
reduced size (CI, a CTest with label `verification`) checks the criteria that apply at that size and
writes under build/verification/ unless --results says otherwise.
"""

import argparse
import os
import shlex
import sys
import time

from .program import REPO, Program, RunSpec, parse_info

CASES = ["b1_ghost_forces", "b2_plate_uniform", "b3_cracked_plate", "b4_cube_uniform", "b5_cracked_block",
         "b6_fracture_convergence", "b7_adaptive_fracture", "b8_damage_handover"]
RESULTS = os.path.join(REPO, "verification", "results")


class Context:
    def __init__(self, program, reduced, results, jobs, argv, time_limit=None):
        self.program, self.reduced, self.results, self.jobs, self.argv = program, reduced, results, jobs, argv
        self.time_limit = time_limit  # seconds per full-size run (--time-limit), for the cases that use it
        self.mode = "reduced" if reduced else "full"
        self.results_by_name = {}
        self.t0 = time.time()

    # ------------------------------------------------------------------ running
    def run(self, spec):
        r = self.program.run(spec)
        self.results_by_name[spec.name] = r
        return r

    def run_all(self, specs, jobs=None):
        rs = self.program.run_all(specs, self.jobs if jobs is None else jobs)
        for s, r in zip(specs, rs):
            self.results_by_name[s.name] = r
        return rs

    def info(self, name, case_text):
        """`perimorph info` of a case, parsed (program.parse_info); counted among the case's runs."""
        r = self.run(RunSpec(name + "_info", case_text, command="info", output=False)).check()
        return parse_info(r.stdout)

    # ------------------------------------------------------------------ provenance
    def command_line(self):
        return " ".join(shlex.quote(a) for a in self.argv)

    def run_summary(self):
        rs = list(self.results_by_name.values())
        if not rs:
            return ""
        fresh = [r for r in rs if not r.cached]
        wall, cpu = sum(r.wall_s for r in rs), sum(r.cpu_s for r in rs)
        loads = [x for r in rs for x in r.load]
        return (f"{len(rs)} program runs ({len(rs) - len(fresh)} from the cache of this binary), "
                f"{wall:.0f} s wall and {cpu:.0f} s CPU (user + sys) in all when they ran, "
                f"load average {min(loads):.2f}–{max(loads):.2f} on a {os.cpu_count()}-core machine.")

    def runs_json(self):
        return [{"name": n, "exit": r.returncode, "wall_s": r.wall_s, "cpu_s": r.cpu_s, "load": r.load,
                 "dir": r.dir} for n, r in self.results_by_name.items()]


def parser(description):
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--reduced", action="store_true", help="the reduced size (CI): criteria that apply at that size")
    ap.add_argument("--perimorph", default=None, help="the binary (default: $PERIMORPH or build/apps/perimorph)")
    ap.add_argument("--results", default=None,
                    help="where the reports go (default: verification/results/ full, build/verification/ reduced)")
    ap.add_argument("--cache", default=None,
                    help="run cache (default: $PERIMORPH_VERIFY_CACHE or verification/.cache/)")
    ap.add_argument("--time-limit", type=float, default=None,
                    help="seconds per program run of the full size: a run still going is stopped and reported as "
                         "such (cases that support it: B8)")
    ap.add_argument("--jobs", type=int, default=max(1, min(2, os.cpu_count() or 1)),
                    help="program runs at a time (each with OMP_NUM_THREADS=1 unless the case says otherwise)")
    return ap


def make_context(args, argv):
    program = Program(args.perimorph, args.cache)
    results = args.results or (os.path.join(REPO, "build", "verification") if args.reduced else RESULTS)
    return Context(program, args.reduced, os.path.abspath(results), args.jobs, argv, args.time_limit)


def run_case(module, ctx):
    """Runs one case module; returns its Report (written) or raises."""
    t0 = time.time()
    print(f"== {module.CASE_ID} {module.NAME} ({ctx.mode}) with {ctx.program.path}", flush=True)
    ctx.results_by_name = {}
    rep = module.run(ctx)
    rep.write()
    print(f"== {module.CASE_ID}: {'FAIL' if rep.failed else 'ok'} in {time.time() - t0:.0f} s", flush=True)
    return rep


def case_main(module):
    """Entry point of a case script; exit status 1 when a criterion fails without a measured reason."""
    doc = (module.__doc__ or module.NAME).strip().split("\n")[0]
    args = parser(doc).parse_args()
    rel = os.path.relpath(os.path.abspath(sys.argv[0]), REPO)
    ctx = make_context(args, ["verification/" + os.path.basename(rel)] + sys.argv[1:])
    rep = run_case(module, ctx)
    return 1 if rep.failed else 0

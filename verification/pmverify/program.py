"""Running `perimorph` on case files, with a cache keyed by the binary's hash.

A run is identified by the md5 of the binary, its name, the command, its arguments and the case text with
comment lines left out (a case header may be reworded without invalidating a run). The cache holds the
case file, everything the program wrote, its log and `result.json` (exit status, wall and CPU time, the
load of the machine). A finished run, failed or not, is never repeated for the same key: the program is
deterministic (bit-identical for any thread count), so a result is a property of the binary and the case.
Two processes asking for the same run wait for each other (a lock file), so a suite and a CTest can share
one cache.
"""

import concurrent.futures
import dataclasses
import fcntl
import glob
import hashlib
import json
import os
import re
import shutil
import subprocess
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_BINARY = os.path.join(REPO, "build", "apps", "perimorph")
DEFAULT_CACHE = os.path.join(REPO, "verification", ".cache")


def file_md5(path):
    h = hashlib.md5()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def strip_comments(text):
    """The case text without comment-only lines and trailing blanks: what the program reads."""
    lines = (ln.rstrip() for ln in text.splitlines())
    return "\n".join(ln for ln in lines if ln and not ln.lstrip().startswith("#"))


@dataclasses.dataclass
class RunSpec:
    """One program invocation: `perimorph COMMAND CASE [-o DIR] ARGS` on `case_text`.

    name: unique within a case script (a directory name); threads: OMP_NUM_THREADS (the results do not
    depend on it, the wall time does); output: pass `-o DIR` (run, ghost-forces); quiet: pass --quiet (run).
    """
    name: str
    case_text: str
    command: str = "run"
    args: tuple = ()
    threads: int = 1
    output: bool = True
    quiet: bool = True
    timeout: float = None
    checkpoint_every: int = 0  # run: --checkpoint-every N (not in the key: the results do not depend on it)

    def argv(self, case_path, out_dir):
        a = [self.command, case_path]
        if self.output and self.command in ("run", "ghost-forces"):
            a += ["-o", out_dir]
        if self.quiet and self.command == "run":
            a.append("--quiet")
        if self.checkpoint_every and self.command == "run":
            a += ["--checkpoint-every", str(self.checkpoint_every)]
        return a + [str(x) for x in self.args]

    def key(self, binary_md5):
        text = "\0".join([binary_md5, self.name, self.command, *map(str, self.args), strip_comments(self.case_text)])
        return hashlib.sha256(text.encode()).hexdigest()[:16]


@dataclasses.dataclass
class RunResult:
    spec: RunSpec
    dir: str
    returncode: int
    stdout: str
    stderr: str
    wall_s: float
    cpu_s: float
    load: tuple  # 1-minute load average before and after
    cached: bool

    @property
    def ok(self):
        return self.returncode == 0

    @property
    def case_path(self):
        return os.path.join(self.dir, "case.toml")

    @property
    def output(self):
        return self.stdout + self.stderr

    def message(self, lines=3):
        """The last lines the program printed (its error message when it failed)."""
        return " ".join(ln.strip() for ln in self.output.strip().splitlines()[-lines:])

    def check(self):
        """Raises RuntimeError naming the run and quoting the program when it failed; returns self."""
        if not self.ok:
            raise RuntimeError(f"perimorph {' '.join(self.spec.argv('CASE', 'DIR'))} ({self.spec.name}, {self.dir}) "
                               f"exited {self.returncode}: {self.message(6)}")
        return self

    def path(self, pattern):
        """The one file of the run matching the glob `pattern` (e.g. '*.pvd'); RuntimeError otherwise."""
        found = sorted(glob.glob(os.path.join(self.dir, pattern)))
        if len(found) != 1:
            raise RuntimeError(f"{self.dir}: {len(found)} files match {pattern!r} (need 1)")
        return found[0]

    def csv_path(self):
        """BASENAME.csv of a run (not BASENAME_failures.csv, _failed_bonds.csv nor _alpha.csv), or the ghost-forces CSV."""
        found = [p for p in sorted(glob.glob(os.path.join(self.dir, "*.csv")))
                 if not p.endswith(("_failures.csv", "_failed_bonds.csv", "_alpha.csv"))]
        if len(found) != 1:
            raise RuntimeError(f"{self.dir}: {len(found)} result CSV files (need 1)")
        return found[0]


class Program:
    """A perimorph binary: its path, md5 and the commit it reports (`perimorph --version`)."""

    def __init__(self, path=None, cache_dir=None):
        self.path = os.path.abspath(path or os.environ.get("PERIMORPH") or DEFAULT_BINARY)
        if not os.path.isfile(self.path):
            raise RuntimeError(f"no perimorph binary at {self.path}: build it (scripts/setup.sh) or pass --perimorph")
        self.md5 = file_md5(self.path)
        self.cache_dir = os.path.abspath(cache_dir or os.environ.get("PERIMORPH_VERIFY_CACHE") or DEFAULT_CACHE)
        p = subprocess.run([self.path, "--version"], capture_output=True, text=True)
        m = re.search(r"commit (\S+)\)", p.stdout)
        self.commit = m.group(1) if p.returncode == 0 and m else "unknown (the binary has no --version)"
        self.built = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime(os.path.getmtime(self.path)))

    def describe(self):
        return f"`{self.path}` (md5 {self.md5[:12]}, commit {self.commit}, built {self.built})"

    def provenance(self):
        return {"path": self.path, "md5": self.md5, "commit": self.commit, "built": self.built}

    # ------------------------------------------------------------------ running
    def run(self, spec, log=print):
        """Runs `spec` (or takes it from the cache); returns a RunResult. Never raises for a failed run:
        call RunResult.check() where a failure is an error."""
        d = os.path.join(self.cache_dir, self.md5[:12], f"{spec.name}-{spec.key(self.md5)}")
        os.makedirs(os.path.dirname(d), exist_ok=True)
        with open(d + ".lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            done = os.path.join(d, "result.json")
            if os.path.isfile(done):
                with open(done) as f:
                    rec = json.load(f)
                # A run that ended is the same whatever limit it ran under; one its time limit stopped
                # stands only for a spec with that limit.
                if rec["returncode"] != 124 or rec.get("timeout") == spec.timeout:
                    return RunResult(spec, d, rec["returncode"], rec["stdout"], rec["stderr"], rec["wall_s"],
                                     rec["cpu_s"], tuple(rec["load"]), True)
            # An interrupted run (its time limit, or the machine gone) that left a checkpoint of this case
            # continues from it (`run --restart`, bit for bit the uninterrupted run); otherwise it starts over.
            previous = rec if os.path.isfile(done) else None
            case_path = os.path.join(d, "case.toml")
            checkpoints = glob.glob(os.path.join(d, "*.checkpoint"))
            resume = (spec.command == "run" and len(checkpoints) == 1 and os.path.isfile(case_path)
                      and open(case_path).read() == spec.case_text)
            if not resume:
                previous = None
                if os.path.isdir(d):
                    shutil.rmtree(d)
                os.makedirs(d)
                with open(case_path, "w") as f:
                    f.write(spec.case_text)
            argv = [self.path] + spec.argv(case_path, d) + (["--restart", checkpoints[0]] if resume else [])
            if resume:
                log(f"  {spec.name}: continuing from its checkpoint {checkpoints[0]}")
            log(f"  {spec.name}: running {spec.command} ({spec.threads} thread{'s' if spec.threads > 1 else ''}) ...")
            result = self._execute(spec, argv, d)
            parts = (previous or {}).get("parts", [previous] if previous else [])
            if resume:
                # Times of the parts before: those that ended with a record (a machine that went away leaves
                # none; the CSV's wall_time column counts every part).
                result.wall_s += sum(p["wall_s"] for p in parts)
                result.cpu_s += sum(p["cpu_s"] for p in parts)
            log(f"  {spec.name}: {'done' if result.ok else 'FAILED (exit %d)' % result.returncode} in "
                f"{result.wall_s:.1f} s wall, {result.cpu_s:.1f} s CPU" + ("" if result.ok else f": {result.message()}"))
            with open(os.path.join(d, "run.log"), "a" if resume else "w") as f:
                f.write(" ".join(argv) + "\n" + result.stdout + result.stderr
                        + f"\n[exit {result.returncode}, wall {result.wall_s:.2f} s, CPU {result.cpu_s:.2f} s, "
                          f"load {result.load[0]:.2f} -> {result.load[1]:.2f}]\n")
            with open(done + ".tmp", "w") as f:
                json.dump({"argv": argv, "returncode": result.returncode, "stdout": result.stdout,
                           "stderr": result.stderr, "wall_s": result.wall_s, "cpu_s": result.cpu_s,
                           "load": list(result.load), "timeout": spec.timeout, "program": self.provenance(),
                           "parts": [{k: p[k] for k in ("wall_s", "cpu_s", "returncode")} for p in parts]
                           + [{"wall_s": result.wall_s - sum(p["wall_s"] for p in parts),
                               "cpu_s": result.cpu_s - sum(p["cpu_s"] for p in parts),
                               "returncode": result.returncode}],
                           "date": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())}, f, indent=1)
            os.replace(done + ".tmp", done)
            return result

    def _execute(self, spec, argv, d):
        env = dict(os.environ, OMP_NUM_THREADS=str(spec.threads))
        load0 = os.getloadavg()[0]
        t0 = time.time()
        with open(os.path.join(d, "stdout.txt"), "w+") as out, open(os.path.join(d, "stderr.txt"), "w+") as err:
            p = subprocess.Popen(argv, stdout=out, stderr=err, env=env, cwd=d)
            try:
                _, status, usage = _wait4(p, spec.timeout)
                code = os.waitstatus_to_exitcode(status)
            except subprocess.TimeoutExpired:
                # SIGTERM first: the run stops at its next solve, its files in step, with a checkpoint when
                # it stops between increments; SIGKILL if it has not within two minutes.
                p.terminate()
                try:
                    _, status, usage = _wait4(p, 120)
                except subprocess.TimeoutExpired:
                    p.kill()
                    _, status, usage = os.wait4(p.pid, 0)
                code = 124
            p.returncode = code
            wall = time.time() - t0
            out.seek(0)
            err.seek(0)
            stdout, stderr = out.read(), err.read()
        if code == 124 and spec.timeout:
            stderr += f"\n[stopped after {spec.timeout:.0f} s: the run's time limit]"
        return RunResult(spec, d, code, stdout, stderr, wall, usage.ru_utime + usage.ru_stime,
                         (load0, os.getloadavg()[0]), False)

    def run_all(self, specs, jobs=1, log=print):
        """Runs every spec, `jobs` at a time; results in the order of `specs`."""
        if jobs <= 1 or len(specs) <= 1:
            return [self.run(s, log) for s in specs]
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            return list(pool.map(lambda s: self.run(s, log), specs))

    # ------------------------------------------------------------------ program figures
    def info(self, name, case_text):
        """`perimorph info` of a case, parsed: c_hat, gc_factor (G_c per s_crit²), dofs, bonds, and the text."""
        r = self.run(RunSpec(name + "_info", case_text, command="info", output=False)).check()
        return parse_info(r.stdout)


def _wait4(p, timeout):
    """os.wait4 on a Popen child (its own CPU time), with an optional timeout."""
    if timeout is None:
        return os.wait4(p.pid, 0)
    end = time.time() + timeout
    while True:
        pid, status, usage = os.wait4(p.pid, os.WNOHANG)
        if pid:
            return pid, status, usage
        if time.time() > end:
            raise subprocess.TimeoutExpired(p.args, timeout)
        time.sleep(0.05)


def parse_info(text):
    """The figures of `perimorph info` that the scripts use (None where the case has none)."""
    out = {"text": text}
    for key, pattern, kind in (("c_hat", r"c_hat = ([0-9.eE+-]+)", float),
                               ("gc_factor", r"G_c = ([0-9.eE+-]+) \* s_crit", float),
                               ("dof_nodes", r"(\d+) dof nodes", int),
                               ("dofs", r"dof nodes, (\d+) dofs", int),
                               ("bonds", r"(\d+) bonds", int),
                               ("cell_pairs", r"(\d+) interacting cell pairs", int),
                               ("nu", r"nu = ([0-9.eE+-]+)", float),
                               ("lame", r"lambda = mu = ([0-9.eE+-]+)", float)):
        m = re.search(pattern, text)
        out[key] = kind(m.group(1)) if m else None
    return out

"""What the end-to-end tests share: named checks that print ok / FAIL and are counted,
and a case written into the work folder and run."""
import os
import subprocess
import sys


class Checks:
    def __init__(self, surge, work):
        self.surge, self.work, self.failures = surge, work, []

    def check(self, cond, what):
        print(("ok   " if cond else "FAIL ") + what, flush=True)
        if not cond:
            self.failures.append(what)

    def run(self, name, text, *extra):
        """Writes `text` as WORK/name.yaml, runs it into WORK/name; stops the test if it fails."""
        case = os.path.join(self.work, name + ".yaml")
        with open(case, "w") as f:
            f.write(text)
        out = os.path.join(self.work, name)
        r = subprocess.run([self.surge, "run", case, "--out", out, "--quiet", *extra], capture_output=True, text=True)
        self.check(r.returncode == 0, f"{name} runs (exit {r.returncode}: {r.stderr[-400:]})")
        if r.returncode != 0:
            sys.exit(1)
        return out

    def finish(self, what):
        if self.failures:
            print(f"{len(self.failures)} check(s) failed")
            sys.exit(1)
        print(f"all {what} checks passed")

"""Structure changes keep the bits: short runs of the demo, SPHERIC test 2 at 4 cm (both
boundaries), Archimedes (both boundaries), the slide tsunami at dp = 0.04 m and a DEM-only
column must write byte-identical gauges, particle files and checkpoints to those recorded
(tests/reference/same_bits.json: SHA-256 of each file) from the code before a change that
should not change results. A change that changes results on purpose records them anew:

    python3 tests/python/test_same_bits.py build/cpu-ci/src/surge/surge /tmp/bits cases --record

and says so in its commit. The runs are short (seconds each): they check bits, not physics.

The batched (SIMD) pair loop sums in another order than the scalar one: a build with it
compares against same_bits_simd.json (`--reference same_bits_simd.json`), a build without
it (SURGE_SIMD=OFF) against same_bits.json."""
import hashlib
import json
import os
import shutil
import subprocess
import sys

SURGE, WORK, CASES = sys.argv[1], sys.argv[2], sys.argv[3]
RECORD = "--record" in sys.argv[4:]
NAME = sys.argv[sys.argv.index("--reference") + 1] if "--reference" in sys.argv else "same_bits.json"
REFERENCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference", NAME)

# name: (case file, --set overrides); every run writes its outputs, a final checkpoint and gauges.
RUNS = {
    "demo": ("demo_dambreak.yaml", ["time.end=0.1"]),
    "spheric_dynamic": ("spheric_test2.yaml", ["dp=0.04", "time.end=0.1", "sph.boundary=dynamic"]),
    "spheric_mdbc": ("spheric_test2.yaml", ["dp=0.04", "time.end=0.1", "sph.boundary=mdbc"]),
    "archimedes_dynamic": ("archimedes.yaml", ["time.end=0.02", "time.output_every=0.01", "sph.boundary=dynamic"]),
    "archimedes_mdbc": ("archimedes.yaml", ["time.end=0.02", "time.output_every=0.01", "sph.boundary=mdbc",
                                            "dem.packs.0.fixed=false"]),
    "slide": ("slide_tsunami.yaml", ["dp=0.04", "time.end=0.02", "time.output_every=0.01"]),
    "column": ("column_collapse.yaml", ["time.end=0.05", "time.output_every=0.025"]),
}


def digests(out):
    """SHA-256 of the files that carry results: gauges, particle files, checkpoint."""
    d = {}
    for root, _, files in os.walk(out):
        for f in sorted(files):
            if f.endswith((".csv", ".vtp", ".bin")):
                path = os.path.join(root, f)
                d[os.path.relpath(path, out)] = hashlib.sha256(open(path, "rb").read()).hexdigest()
    return d


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
got = {}
for name, (case, sets) in RUNS.items():
    out = os.path.join(WORK, name)
    args = [SURGE, "run", os.path.join(CASES, case), "--out", out, "--quiet", "--threads", "2"]
    for s in sets:
        args += ["--set", s]
    r = subprocess.run(args, capture_output=True, text=True, env=dict(os.environ, OMP_WAIT_POLICY="PASSIVE"))
    if r.returncode != 0:
        print("FAIL %s: exit %d: %s" % (name, r.returncode, r.stderr[-300:]))
        sys.exit(1)
    got[name] = digests(out)
    print("ran  %s: %d files" % (name, len(got[name])))

if RECORD:
    os.makedirs(os.path.dirname(REFERENCE), exist_ok=True)
    with open(REFERENCE, "w") as f:
        json.dump(got, f, indent=1, sort_keys=True)
        f.write("\n")
    print("recorded", REFERENCE)
    sys.exit(0)

want = json.load(open(REFERENCE))
failures = 0
for name in RUNS:
    for path in sorted(set(want.get(name, {})) | set(got[name])):
        a, b = want.get(name, {}).get(path), got[name].get(path)
        if a != b:
            failures += 1
            print("FAIL %s/%s: %s" % (name, path, "missing" if b is None else "extra" if a is None else "differs"))
print("\n%d file(s) differ" % failures)
sys.exit(1 if failures else 0)

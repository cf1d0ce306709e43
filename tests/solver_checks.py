"""Shared by the 3D solver checks (check_weak_hardening, check_low_yield, check_cold_start,
check_heavy_sliding, check_transient_counts_3d, check_softening_curve,
check_softening_partial_slip): the pass/fail line, the contact of
bench/cases/tractcurve_plast.yaml as case text, writing a case, and a sweep's counts."""
import os
import re
import subprocess


class Checks:
    """check(what, ok, detail) prints one line per check; failures counts the failed ones."""

    def __init__(self):
        self.failures = 0

    def __call__(self, what, ok, detail=""):
        print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail else ''}")
        if not ok:
            self.failures += 1


def eurosprinter(title, cells):
    """The first lines of a case on the Eurosprinter contact of CONTACT's tractcurve_plast
    (a/b = 0.5, F_n = 106.7 kN, G = 82000 N/mm^2, nu = 0.28, mu = 0.33) on cells x cells."""
    return (f'title: "{title}"\n'
            "contact: {dimension: 3, normal_load: 106700.0, radius: [625.0, 1776.72]}\n"
            f"grid: {{cells: [{cells}, {cells}], extent: [1.1, 1.1]}}\n"
            "material: {shear_modulus: 82000.0, poisson_ratio: 0.28}\n"
            "friction: {mu: 0.33}\n")


def softening_sweep(title, cells, creepages):
    """A steady sweep over creepages of the Eurosprinter contact with softening (tau_c0 150
    N/mm^2, k_rel -0.01) at V = 10 m/s, scalars only."""
    return eurosprinter(title, cells) + f"""\
plasticity: {{tau_c0: 150.0, k_rel: -0.01}}
rolling: {{velocity: 10000.0, creepage: 0.0}}
simulation: {{mode: steady}}
output: {{fields: []}}
sweep:
  rolling.creepage: [{", ".join(repr(x) for x in creepages)}]
"""


def sweep_counts(binary, path, out, extra, timeout=300):
    """(points solved, failed, Newton iterations) of `rollsim sweep`, or None (printed why)."""
    try:
        p = subprocess.run([binary, "sweep", path, "-o", out, "--quiet"] + extra,
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        print(f"timed out after {timeout} s")
        return None
    m = re.search(r"(\d+) points solved, (\d+) failed, Newton iterations (\d+)", p.stdout)
    if p.returncode != 0 or not m:
        print(p.stdout, p.stderr)
        return None
    return int(m.group(1)), int(m.group(2)), int(m.group(3))


# Summary lines of `rollsim run` as regular expressions, by name, for run_counts.
SUMMARY = {
    "rtol": r"solver\.rtol auto = ([0-9.e+-]+)",
    "steps": r"IDA steps (\d+)",
    "newton": r"Newton iterations (\d+)",
    "jacobians": r"Jacobian evaluations (\d+)",
    "factorisations": r"factorisations (\d+)",
    "per_passage": r"([0-9.]+) steps per passage",
    "mu": r"F_x/\(mu F_n\) = ([0-9.e+-]+)",
}


def run_counts(binary, path, out, extra, keys, timeout=300):
    """`rollsim run PATH -o OUT EXTRA...`: the summary's numbers named by KEYS (SUMMARY), each
    None where the summary has no such line; None when the run failed (printed)."""
    p = subprocess.run([binary, "run", path, "-o", out] + extra, capture_output=True, text=True,
                       timeout=timeout)
    print(p.stdout, p.stderr)
    if p.returncode != 0:
        return None
    nums = {}
    for key in keys:
        m = re.search(SUMMARY[key], p.stdout)
        nums[key] = float(m.group(1)) if m else None
    return nums


def write_case(work, name, case):
    """Writes the case text CASE to WORK/NAME.yaml (WORK made if missing); its path."""
    os.makedirs(work, exist_ok=True)
    path = os.path.join(work, name + ".yaml")
    with open(path, "w") as f:
        f.write(case)
    return path


def plastic_and_elastic(check, binary, work, name, case, elastic_sets):
    """Writes CASE to WORK/NAME.yaml and sweeps it as it is and with ELASTIC_SETS (the elastic
    curve over the same points): (path, plastic .nc, elastic .nc, plastic counts, elastic
    counts), the counts as sweep_counts gives them, or None if either sweep did not run."""
    path = write_case(work, name, case)
    plastic_nc, elastic_nc = os.path.join(work, name + ".nc"), os.path.join(work, "elastic.nc")
    elastic = sweep_counts(binary, path, elastic_nc, elastic_sets)
    plastic = sweep_counts(binary, path, plastic_nc, [])
    check("the elastic sweep ran", elastic is not None)
    check("the plastic sweep ran", plastic is not None)
    if plastic is None or elastic is None:
        return None
    return path, plastic_nc, elastic_nc, plastic, elastic

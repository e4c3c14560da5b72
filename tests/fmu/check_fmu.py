#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""kanegen fmu, checked as an importer sees it (tests/fmu/tests.cmake registers each case):

  run MODEL FMI...   each version's FMU (model exchange and co-simulation) unzipped with zipfile, modelDescription.xml
                     checked against FMI's rules (fmi_rules.py), then driven by fmu_driver (our own importer:
                     model exchange by its own RK4, co-simulation by DoStep) and compared with kanegen
                     simulate's CSV to 1e-6
  sources MODEL FMI  the FMU against simulate as for run, then sources/ alone compiled with g++ and clang++ -Wall -Wextra -Wpedantic -Werror, each
                     binary giving the numbers of the FMU's own
  hostile            names with quotes, <, &, newlines: well-formed XML naming them exactly, code that compiles
  refused            bad options and bad models: a clear error, exit status 2, and no .fmu nor temporary file

Exit status 0 when every check passes; the first failure is printed."""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fmi_rules  # noqa: E402

TOLERANCE = 1e-6
FLAGS = ["-std=c++17", "-O1", "-fPIC", "-shared", "-fvisibility=hidden", "-Wall", "-Wextra", "-Wpedantic", "-Werror"]


# kanegen fmu builds the FMUs with the plain compiler even in a sanitized build (whose ctest sets
# KANEGEN_CXX to the sanitizing one): fmu_driver, like any importer, is not instrumented and could not
# load an instrumented binary. kanegen itself still runs sanitized. kanegen simulate, the reference,
# keeps KANEGEN_CXX: its runner links the build's runtime library, sanitized in such a build.
PLAIN = {k: v for k, v in os.environ.items() if k != "KANEGEN_CXX"}


def run(args, env=None):
    return subprocess.run(args, capture_output=True, text=True, env=PLAIN if env is None else env)


def must(args, what, env=None):
    r = run(args, env)
    if r.returncode != 0:
        sys.exit(f"FAIL: {what}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r


def export(a, model, fmi, out, *extra):
    must([a.kanegen, "fmu", model, "-o", out, "--fmi", str(fmi), "--quiet", *extra], f"kanegen fmu {model}")
    folder = out[:-4]
    shutil.rmtree(folder, ignore_errors=True)
    with zipfile.ZipFile(out) as z:
        bad = z.testzip()  # every entry's CRC-32 checked
        assert bad is None, f"{out}: entry {bad} is corrupt"
        z.extractall(folder)
    root = ET.parse(os.path.join(folder, "modelDescription.xml")).getroot()
    return folder, root, fmi_rules.check(root, fmi)


def binary_of(folder, root, fmi):
    ident = root.find("CoSimulation").get("modelIdentifier")
    platform = "linux64" if fmi == 2 else "x86_64-linux"
    path = os.path.join(folder, "binaries", platform, ident + ".so")
    assert os.path.exists(path), f"no binary {path}"
    return path


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in r] for r in rows[1:] if r]


def drive(a, binary, fmi, kind, root, variables, names, stop, work, sets=(), substeps=40, said=None):
    """fmu_driver on `binary`: the columns `names` (looked up in modelDescription.xml) every 0.01 s,
    model exchange by RK4 with `substeps` steps an interval; `said` gets the driver's summary line."""
    by_name = {v.name: v for v in variables}
    token = root.get("guid" if fmi == 2 else "instantiationToken")
    states = sum(1 for v in variables if v.derivative is not None)
    plan = os.path.join(work, f"plan_{fmi}_{kind}.txt")
    with open(plan, "w") as f:
        f.write(f"token {token}\nstates {states}\nstop {stop}\ninterval 0.01\nsubsteps {substeps}\n")
        for name, value in sets:
            f.write(f"set {by_name[name].vr} {value!r}\n")
        for n in names:
            f.write(f"out {by_name[n].vr}\n")
    out = os.path.join(work, f"driver_{fmi}_{kind}_{os.path.basename(binary)}.csv")
    r = must([a.driver, binary, str(fmi), kind, plan, out], f"fmu_driver {kind} FMI {fmi}")
    if said is not None:
        said.append(r.stdout.strip())
    return read_csv(out)[1]


def largest_difference(reference, names, rows):
    """max |difference| over the rows and the columns `names` (reference: the simulate CSV)."""
    head, ref = reference
    assert len(ref) == len(rows), f"{len(ref)} rows in the reference, {len(rows)} from the FMU"
    worst = (0.0, "", 0.0)
    for r, row in zip(ref, rows):
        assert abs(r[0] - row[0]) < 1e-12, "times differ"
        for j, n in enumerate(names):
            d = abs(r[head.index(n)] - row[j + 1])
            if not d <= worst[0]:
                worst = (d, n, r[0])
    return worst


TIGHT = ["--rtol", "1e-10", "--atol", "1e-12"]


def simulated(a, model, work):
    """kanegen simulate's CSV of 1 s, the reference."""
    sim = os.path.join(work, "simulate.csv")
    must([a.kanegen, "simulate", model, "--t-end", "1", "--dt", "0.01", *TIGHT, "-o", sim, "--quiet"], "simulate", os.environ)
    return read_csv(sim)


def against_simulate(a, reference, binary, fmi, root, variables, work):
    """Model exchange and co-simulation of `binary`, every column of `reference` compared."""
    names = [n for n in reference[0][1:] if n in {v.name for v in variables}]
    assert len(names) == len(reference[0]) - 1, "every simulate column is an FMU variable"
    for kind in ("me", "cs"):
        rows = drive(a, binary, fmi, kind, root, variables, names, 1.0, work)
        d, n, t = largest_difference(reference, names, rows)
        print(f"FMI {fmi} {kind}: largest difference from kanegen simulate {d:.3g} ({n} at t={t})")
        assert d <= TOLERANCE, f"FMI {fmi} {kind} differs from simulate by {d} in {n} at t={t}"
    if any(v.initial == "approx" for v in variables):  # closed loops: coarse steps drift, events project
        said = []
        rows = drive(a, binary, fmi, "me", root, variables, names, 1.0, work, substeps=4, said=said)
        d, n, t = largest_difference(reference, names, rows)
        events, moved = (int(x) for x in said[0].replace(",", "").split()[2::3])
        print(f"FMI {fmi} me, h = 2.5e-3: {said[0]}; largest difference {d:.3g} ({n} at t={t})")
        assert events > 0 and moved == events, f"the loops' drift raised no step event ({said[0]})"
        assert d <= 1e-3, f"with step events, FMI {fmi} me differs from simulate by {d} in {n} at t={t}"


def case_run(a, model, versions):
    work = os.path.join(a.work, "run")
    os.makedirs(work, exist_ok=True)
    reference = simulated(a, model, work)
    for fmi in versions:
        folder, root, variables = export(a, model, fmi, os.path.join(work, f"model{fmi}.fmu"), *TIGHT)
        against_simulate(a, reference, binary_of(folder, root, fmi), fmi, root, variables, work)


def compile_sources(folder, compiler, out):
    sources = os.path.join(folder, "sources")
    files = []
    for base, _, names in os.walk(sources):
        files += [os.path.join(base, n) for n in names if n.endswith(".cpp")]
    must([compiler, *FLAGS, "-I" + sources, *sorted(files), "-o", out], f"{compiler} on sources/")


def case_sources(a, model, fmi):
    """The FMU's own binary against simulate, then sources/ alone built by each compiler: the same numbers."""
    work = os.path.join(a.work, "sources")
    os.makedirs(work, exist_ok=True)
    folder, root, variables = export(a, model, fmi, os.path.join(work, "model.fmu"), *TIGHT)
    against_simulate(a, simulated(a, model, work), binary_of(folder, root, fmi), fmi, root, variables, work)
    names = [v.name for v in variables if v.causality in ("output", "local") and v.derivative is None][:12]
    own = drive(a, binary_of(folder, root, fmi), fmi, "cs", root, variables, names, 0.2, work)
    for compiler in ("g++", "clang++"):
        if shutil.which(compiler) is None:
            sys.exit(f"FAIL: {compiler} not found (scripts/install-deps.sh installs it)")
        binary = os.path.join(work, f"{compiler}.so")
        compile_sources(folder, compiler, binary)
        rows = drive(a, binary, fmi, "cs", root, variables, names, 0.2, work)
        worst = max(abs(x - y) for r, s in zip(own, rows) for x, y in zip(r, s))
        print(f"{compiler}: sources/ compiled with -Werror; largest difference from the FMU's binary {worst:.3g}")
        assert worst <= 1e-9, f"the binary {compiler} built from sources/ differs by {worst}"


HOSTILE_URDF = """<?xml version="1.0"?>
<robot name="quoted">
  <link name="base"/>
  <link name="arm &amp; &lt;hand&gt;"><inertial><mass value="1"/><origin xyz="0 0 -0.5"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="{name}" type="continuous"><parent link="base"/><child link="arm &amp; &lt;hand&gt;"/>
    <axis xyz="0 1 0"/></joint>
</robot>
"""


def case_hostile(a):
    """Names that XML and C would read as markup or code: the XML is well-formed and names them byte for
    byte, the sources compile with -Werror and the FMU runs; a newline in a name is refused by the loader."""
    work = os.path.join(a.work, "hostile")
    os.makedirs(work, exist_ok=True)
    shipped = os.path.join(a.source, "tests", "data", "models", "hostile_names.urdf")
    written = os.path.join(work, "quoted.urdf")
    joint = "a\"b' <c> & d;]]> --> \\ ??/ */"
    escaped = joint.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")
    with open(written, "w") as f:
        f.write(HOSTILE_URDF.format(name=escaped))
    for urdf, fmi in ((shipped, 2), (written, 3)):
        folder, root, variables = export(a, urdf, fmi, os.path.join(work, f"h{fmi}.fmu"))
        joints = [j.get("name") for j in ET.parse(urdf).getroot().iter("joint")]
        names = {v.name for v in variables}
        for j in joints:  # each joint's coordinate, speed and input, exactly as the URDF spells them
            for n in (j, j + "_dot", "der(" + j + ")", j + "_tau"):
                assert n in names, f"{n!r} is not a variable of the FMU of {urdf}"
        outputs = [v.name for v in variables if v.causality in ("output", "local")][:6]
        drive(a, binary_of(folder, root, fmi), fmi, "cs", root, variables, outputs, 0.05, work)
    compile_sources(folder, "g++", os.path.join(work, "hostile_gxx.so"))
    print("hostile names: well-formed XML naming them exactly, sources compiled with -Werror, FMUs run")
    with open(os.path.join(work, "newline.urdf"), "w") as f:
        f.write(HOSTILE_URDF.format(name="a&#10;b"))
    refused(a, [os.path.join(work, "newline.urdf"), "-o", os.path.join(work, "newline.fmu")],
            "control character", work)


def refused(a, args, said, work, status=2):
    """kanegen fmu refuses with exit status `status` (2; CLI11's 105 for a value its check refuses) and a
    message holding `said`; no .fmu nor temporary file is left."""
    before = set(os.listdir(work))
    r = run([a.kanegen, "fmu", *args, "--quiet"])
    assert r.returncode == status, f"kanegen fmu {args}: exit {r.returncode}, wanted {status}\n{r.stderr}"
    assert said in r.stderr, f"kanegen fmu {args}: the message does not say {said!r}: {r.stderr}"
    left = set(os.listdir(work)) - before
    assert not left, f"kanegen fmu {args} left {left}"
    print(f"refused: {r.stderr.strip().splitlines()[-1][:160]}")


def case_refused(a):
    work = os.path.join(a.work, "refused")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    model = os.path.join(a.source, "models", "simple_pendulum.json")
    out = os.path.join(work, "p.fmu")
    refused(a, [model, "-o", os.path.join(work, "p.zip")], "ends in .fmu", work)
    refused(a, [model, "-o", out, "--integrator", "bdf"], "integrates with rk4, dopri5, implicit, radau (bdf: it needs SUNDIALS", work)
    refused(a, [model, "-o", "/proc/kanegen-none/p.fmu"], "cannot write in /proc/kanegen-none", work)
    refused(a, [model, "-o", out, "--fmi", "4"], "--fmi", work, status=105)
    # An output named as a coordinate: FMI asks for unique variable names.
    with open(model) as f:
        text = f.read()
    duplicate = os.path.join(work, "duplicate.json")
    with open(duplicate, "w") as f:
        f.write(text.replace('"name": "angle"', '"name": "pivot"'))
    refused(a, [duplicate, "-o", out], "the FMU's variable 'pivot'", work)
    bad = os.path.join(a.source, "tests", "data", "bad_models", "duplicate_joint.json")
    refused(a, [bad, "-o", out], "duplicate_joint.json", work)
    # A failed export leaves an existing FMU as it was.
    with open(out, "w") as f:
        f.write("previous")
    refused(a, [bad, "-o", out], "duplicate_joint.json", work)
    with open(out) as f:
        assert f.read() == "previous", "a failed export changed the existing .fmu"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--kanegen", required=True)
    p.add_argument("--driver", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("case", choices=["run", "sources", "hostile", "refused"])
    p.add_argument("model", nargs="?")
    p.add_argument("fmi", nargs="*", type=int)
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    try:
        if a.case == "run":
            case_run(a, os.path.join(a.source, "models", a.model), a.fmi)
        elif a.case == "sources":
            case_sources(a, os.path.join(a.source, "models", a.model), a.fmi[0])
        elif a.case == "hostile":
            case_hostile(a)
        else:
            case_refused(a)
    except AssertionError as e:
        sys.exit(f"FAIL: {e}")
    print("ok")


if __name__ == "__main__":
    main()

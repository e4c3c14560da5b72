# SPDX-License-Identifier: GPL-2.0-or-later
"""The structure FMI asks of modelDescription.xml, written from the standards' text (FMI 2.0.x section
2.2.7 "Definition of Model Variables" with its table of causality, variability and initial, and 2.2.8
"Definition of the Model Structure"; FMI 3.0 sections 2.4.7 and 2.4.8), not from kanegen's writer: each
check raises AssertionError with what is wrong."""

# Allowed (causality, variability) pairs and, for each, the allowed values of initial and its default
# (None: initial must not be given). FMI 2.0 table in 2.2.7; FMI 3.0 keeps it (2.4.7.4) and adds
# structuralParameter, which kanegen does not use.
_A = ({"exact"}, "exact")
_B = ({"approx", "calculated"}, "calculated")
_C = ({"exact", "approx", "calculated"}, "calculated")
_NONE = (set(), None)
ALLOWED = {
    ("parameter", "fixed"): _A, ("parameter", "tunable"): _A,
    ("calculatedParameter", "fixed"): _B, ("calculatedParameter", "tunable"): _B,
    ("input", "discrete"): _NONE, ("input", "continuous"): _NONE,
    ("output", "constant"): _A, ("output", "discrete"): _C, ("output", "continuous"): _C,
    ("local", "constant"): _A, ("local", "fixed"): _B, ("local", "tunable"): _B,
    ("local", "discrete"): _C, ("local", "continuous"): _C,
    ("independent", "continuous"): _NONE,
}


class Var:
    def __init__(self, name, vr, causality, variability, initial, start, derivative, index):
        self.name, self.vr, self.causality, self.variability = name, vr, causality, variability
        self.initial, self.start, self.derivative, self.index = initial, start, derivative, index


def _check_variable(v, fmi):
    key = (v.causality, v.variability)
    assert key in ALLOWED, f"{v.name}: causality {v.causality} with variability {v.variability} is not allowed"
    allowed, default = ALLOWED[key]
    if default is None:
        assert v.initial is None, f"{v.name}: initial must not be given for causality {v.causality}"
    else:
        assert v.initial is None or v.initial in allowed, f"{v.name}: initial={v.initial} not allowed for {key}"
    initial = v.initial or default
    # A start value with exact or approx, and for inputs; none with calculated, nor for the independent one.
    if v.causality == "input" or initial in ("exact", "approx"):
        assert v.start is not None, f"{v.name}: needs a start value (initial {initial}, causality {v.causality})"
    if v.causality == "independent" or initial == "calculated":
        assert v.start is None, f"{v.name}: must have no start value"
    return initial


def variables(root, fmi):
    """The model variables in order, each a Var (index: 1-based position, FMI 2.0's reference)."""
    out = []
    models = root.find("ModelVariables")
    assert models is not None, "no ModelVariables"
    elements = list(models)
    for i, e in enumerate(elements, start=1):
        if fmi == 2:
            assert e.tag == "ScalarVariable", f"unexpected element {e.tag}"
            typed = [c for c in e if c.tag in ("Real", "Integer", "Boolean", "String", "Enumeration")]
            assert len(typed) == 1, f"{e.get('name')}: exactly one type element"
            t = typed[0]
        else:
            t = e
        out.append(Var(e.get("name"), int(e.get("valueReference")), e.get("causality", "local"),
                       e.get("variability", "continuous"), e.get("initial"), t.get("start"),
                       t.get("derivative"), i))
    return out


def check(root, fmi):
    """Every rule; returns the variables."""
    assert root.tag == "fmiModelDescription" and root.get("fmiVersion") == ("2.0" if fmi == 2 else "3.0")
    token = root.get("guid" if fmi == 2 else "instantiationToken")
    assert token, "no guid / instantiationToken"
    interfaces = [root.find(k) for k in ("ModelExchange", "CoSimulation")]
    assert any(i is not None for i in interfaces), "at least one of ModelExchange or CoSimulation"
    for i in interfaces:
        if i is not None:
            ident = i.get("modelIdentifier")
            assert ident and (ident[0].isalpha() or ident[0] == "_") and all(c.isalnum() or c == "_" for c in ident), \
                f"modelIdentifier {ident!r} must be a C identifier"
    vs = variables(root, fmi)
    names = [v.name for v in vs]
    assert len(set(names)) == len(names), "variable names must be unique"
    vrs = [v.vr for v in vs]
    assert len(set(vrs)) == len(vrs), "value references must be unique (no aliases here)"
    initial = {v.name: _check_variable(v, fmi) for v in vs}
    independent = [v for v in vs if v.causality == "independent"]
    assert len(independent) <= 1, "at most one independent variable"
    if fmi == 3:
        assert len(independent) == 1, "FMI 3.0: exactly one independent variable"
    by_index = {v.index: v for v in vs}
    by_vr = {v.vr: v for v in vs}
    derivatives = [v for v in vs if v.derivative is not None]
    states = []
    for d in derivatives:
        ref = int(d.derivative)
        state = by_index.get(ref) if fmi == 2 else by_vr.get(ref)
        assert state is not None, f"{d.name}: derivative={ref} points at no variable"
        assert state.variability == "continuous" and state.causality != "independent", f"{d.name}: not of a state"
        states.append(state)
    _check_structure(root, fmi, vs, derivatives, states, initial, by_index, by_vr)
    _check_units(root, fmi)
    return vs


def _check_units(root, fmi):
    """A unit attribute names a Unit of UnitDefinitions (FMI 2.0 2.2.2, FMI 3.0 2.4.3)."""
    defined = set(u.get("name") for u in root.iter("Unit"))
    for e in root.find("ModelVariables").iter():
        unit = e.get("unit")
        assert unit is None or unit in defined, f"unit {unit!r} is not defined in UnitDefinitions"


def _structure_lists(root, fmi, by_index, by_vr):
    s = root.find("ModelStructure")
    assert s is not None, "no ModelStructure"
    if fmi == 2:
        def lst(tag):
            e = s.find(tag)
            return [] if e is None else [by_index[int(u.get("index"))] for u in e.findall("Unknown")]
        return lst("Outputs"), lst("Derivatives"), lst("InitialUnknowns")
    def lst3(tag):
        return [by_vr[int(u.get("valueReference"))] for u in s.findall(tag)]
    return lst3("Output"), lst3("ContinuousStateDerivative"), lst3("InitialUnknown")


def _check_structure(root, fmi, vs, derivatives, states, initial, by_index, by_vr):
    outputs, ders, unknowns = _structure_lists(root, fmi, by_index, by_vr)
    # Outputs: every variable of causality output, once, in the order of ModelVariables.
    assert [v.name for v in outputs] == [v.name for v in vs if v.causality == "output"], "Outputs list"
    # Derivatives: exactly the state derivatives.
    assert sorted(v.name for v in ders) == sorted(v.name for v in derivatives), "Derivatives list"
    # InitialUnknowns: outputs with initial approx/calculated, calculated parameters, and the states and
    # derivatives with initial approx/calculated; no duplicates, ordered by index (FMI 2.0).
    expected = set(v.name for v in vs if v.causality == "output" and initial[v.name] in ("approx", "calculated"))
    expected |= set(v.name for v in vs if v.causality == "calculatedParameter")
    expected |= set(v.name for v in states + derivatives if initial[v.name] in ("approx", "calculated"))
    got = [v.name for v in unknowns]
    assert len(got) == len(set(got)), "InitialUnknowns has duplicates"
    assert set(got) == expected, f"InitialUnknowns: {sorted(set(got) ^ expected)} differ"
    if fmi == 2:
        assert [v.index for v in unknowns] == sorted(v.index for v in unknowns), "InitialUnknowns order"

"""The OpenMDAO component: exact partials, declared sparse, and a driver that reaches the
study's optimum."""

import runpy

import numpy as np
import openmdao.api as om

from conftest import ROOT, TABLE1
from flexopt.openmdao import FlexoptComponent, sparsity

# Table 1's design is symmetric, where stress_max, a maximum, has a kink: one side longer
DESIGN = dict(TABLE1, l4=2.5)


def checked(wei2017):
    prob = om.Problem(reports=False)  # no `<name>_out/` reports folder in the working directory
    prob.model.add_subsystem("bridge", FlexoptComponent(problem=wei2017), promotes=["*"])
    prob.setup()
    for name, value in DESIGN.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob, prob.check_partials(out_stream=None, method="fd", form="central", step=1e-6)


def test_check_partials_passes(wei2017):
    prob, data = checked(wei2017)
    errors = {key: entry["rel error"].forward for key, entry in data["bridge"].items()}
    worst = max(errors, key=errors.get)
    assert errors[worst] < 1e-6, (worst, errors[worst])
    values = wei2017.evaluate(DESIGN)
    for name in wei2017.outputs:
        assert prob.get_val(name)[0] == values[name]


def test_partials_are_declared_only_where_the_jacobian_is_not_zero(wei2017):
    pattern = sparsity(wei2017)
    assert 0 < pattern.sum() < pattern.size
    _, data = checked(wei2017)
    declared = set(data["bridge"])
    outputs, inputs = wei2017.outputs, wei2017.free_variables
    assert declared == {(outputs[i], inputs[k]) for i, k in zip(*np.nonzero(pattern))}
    # the undeclared ones are zero by central differences too
    x = np.array([DESIGN[n] for n in inputs])
    for k in range(len(x)):
        h = 1e-6 * max(abs(x[k]), 1.0)
        up, down = x.copy(), x.copy()
        up[k] += h
        down[k] -= h
        fd = wei2017.evaluate(up, as_array=True) - wei2017.evaluate(down, as_array=True)
        for i in np.flatnonzero(~pattern[:, k]):
            assert fd[i] == 0.0, (outputs[i], inputs[k])


def test_the_example_driver_reaches_the_analytic_optimum():
    result = runpy.run_path(str(ROOT / "python" / "examples" / "openmdao_wei2017.py"),
                            run_name="__test__")
    amplification, design = result["optimize"]()
    assert abs(abs(amplification) - 12.8979355) < 1e-6
    assert abs(design["t2"] - 0.4) < 1e-9

"""Paper 004's bridge (problems/wei2017.toml) optimized by OpenMDAO's ScipyOptimizeDriver
(SLSQP) on flexopt's component, from Table 1's rounded design, in the optimum's basin.

Run from the repository:  python python/examples/openmdao_wei2017.py
"""

import pathlib

import openmdao.api as om

import flexopt
from flexopt.openmdao import FlexoptComponent

ROOT = pathlib.Path(__file__).resolve().parents[2]
# Table 1 of the paper, mm and degrees
START = {"l2": 1.96, "delta2": 4.07, "t2": 0.4, "l3": 8.1, "delta3": 4.01,
         "l4": 1.96, "delta4": 4.07, "t4": 0.4}


def optimize(problem_file=ROOT / "problems" / "wei2017.toml"):
    """The driver's optimum: the objective as the problem states it, and the design."""
    problem = flexopt.Problem.load(problem_file)
    model_outputs = [problem.objective] + [c[0] for c in problem.constraints]
    # no reports: OpenMDAO would write them into a `<script>_out/` folder of the working
    # directory (the repository's root when run as above); the driver writes nothing else
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("bridge", FlexoptComponent(problem=problem, outputs=model_outputs),
                             promotes=["*"])
    units = dict(problem.variable_units)
    for name, lo, hi in zip(problem.free_variables, problem.lower, problem.upper):
        prob.model.add_design_var(name, lower=lo, upper=hi, units=units[name])
    # OpenMDAO minimizes; an absolute value's sign is the start's, which it keeps in its basin
    direction = -1.0 if problem.sense == "maximize" else 1.0
    if problem.absolute and problem.evaluate(START)[problem.objective] < 0:
        direction = -direction
    prob.model.add_objective(problem.objective, ref=10.0 * direction)
    for output, lower, upper in problem.constraints:
        ref = max(abs(v) for v in (lower, upper) if v is not None) or 1.0
        prob.model.add_constraint(output, lower=lower, upper=upper, ref=ref)
    prob.driver = om.ScipyOptimizeDriver(optimizer="SLSQP", tol=1e-12, maxiter=200, disp=False)
    prob.setup()
    for name, value in START.items():
        prob.set_val(name, value)
    result = prob.run_driver()
    if not result.success:
        raise RuntimeError(f"the driver did not converge: {result}")
    design = {n: float(prob.get_val(n)[0]) for n in problem.free_variables}
    return float(prob.get_val(problem.objective)[0]), design


if __name__ == "__main__":
    amplification, design = optimize()
    print(f"amplification {amplification:.7f}")
    for name, value in design.items():
        print(f"  {name} = {value:.6f}")

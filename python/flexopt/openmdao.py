"""An OpenMDAO component of a flexopt problem's model.

Its inputs are the problem's free variables in the file's units, its outputs the model's
outputs in SI, and its partials the model's exact Jacobian, declared only where it is not
structurally zero.
"""

from __future__ import annotations

import os
from typing import Optional, Sequence, Union

import numpy as np
import openmdao.api as om
from openmdao.utils.units import valid_units

from ._flexopt import FlexoptError, Problem

__all__ = ["FlexoptComponent", "sparsity"]


def _units(name: str) -> Optional[str]:
    """The unit as OpenMDAO names it, or None (dimensionless, or one it does not know)."""
    return name if name not in ("", "1", "-") and valid_units(name) else None


def sparsity(problem: Problem, samples: int = 4, seed: int = 0) -> np.ndarray:
    """Where the Jacobian (outputs x free variables) is not structurally zero: nonzero at some
    of `samples` seeded designs inside the bounds (kept away from them, where a bound such as
    a zero angle may zero a derivative by chance)."""
    rng = np.random.default_rng(seed)
    lower, upper = problem.lower, problem.upper
    pattern = np.zeros((len(problem.outputs), len(problem.free_variables)), dtype=bool)
    seen = 0
    for _ in range(20 * samples):
        design = lower + (upper - lower) * rng.uniform(0.2, 0.8, size=lower.shape)
        try:
            jac = problem.jacobian(design)
        except FlexoptError:
            continue  # outside the model's domain
        pattern |= np.isfinite(jac) & (jac != 0.0)
        seen += 1
        if seen == samples:
            return pattern
    # too few designs inside the domain to prove a zero: every partial declared
    return np.ones_like(pattern)


class FlexoptComponent(om.ExplicitComponent):
    """The model of a flexopt problem file as an ``ExplicitComponent``.

    Options: ``problem`` (a ``flexopt.Problem`` or a path to a problem file) and ``outputs``
    (the outputs to expose; all of ``Problem.outputs`` by default).
    """

    def initialize(self) -> None:
        self.options.declare("problem", desc="a flexopt.Problem or the path of a problem file")
        self.options.declare("outputs", default=None, allow_none=True,
                             desc="the model outputs to expose (default: all)")

    def setup(self) -> None:
        problem: Union[Problem, str, os.PathLike] = self.options["problem"]
        if not isinstance(problem, Problem):
            problem = Problem.load(problem)
        self.problem = problem
        units = dict(problem.variable_units)
        for name, lo, hi in zip(problem.free_variables, problem.lower, problem.upper):
            self.add_input(name, val=0.5 * (lo + hi), units=_units(units[name]))
        names: Sequence[str] = self.options["outputs"] or problem.outputs
        unknown = [n for n in names if n not in problem.outputs]
        if unknown:
            raise ValueError(
                f"{problem.file_name}: outputs {unknown} are not among the model's: "
                + ", ".join(problem.outputs))
        self._rows = [problem.outputs.index(n) for n in names]
        self._names = list(names)
        out_units = dict(problem.output_units)
        for name in names:
            self.add_output(name, units=_units(out_units[name]))

    def setup_partials(self) -> None:
        pattern = sparsity(self.problem)[self._rows]
        inputs = self.problem.free_variables
        for name, row in zip(self._names, pattern):
            wrt = [inputs[k] for k in np.flatnonzero(row)]
            if wrt:
                self.declare_partials(name, wrt)
        self._pattern = pattern

    def _design(self, inputs) -> np.ndarray:
        return np.array([inputs[n][0] for n in self.problem.free_variables])

    def compute(self, inputs, outputs) -> None:
        values = self.problem.evaluate(self._design(inputs), as_array=True)
        for name, row in zip(self._names, self._rows):
            outputs[name] = values[row]

    def compute_partials(self, inputs, partials) -> None:
        jac = self.problem.jacobian(self._design(inputs))
        inputs_ = self.problem.free_variables
        for name, row, declared in zip(self._names, self._rows, self._pattern):
            for k in np.flatnonzero(declared):
                partials[name, inputs_[k]] = jac[row, k]

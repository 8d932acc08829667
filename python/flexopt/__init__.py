"""flexopt from Python: problem files, exact gradients, multistart studies and their shards.

``flexopt.openmdao`` holds an OpenMDAO component of a problem's model and ``flexopt.dask`` a
study spread over a Dask cluster; both import their framework only when imported.
"""

from ._flexopt import FlexoptError, Problem, Study, merge

__all__ = ["FlexoptError", "Problem", "Study", "merge"]

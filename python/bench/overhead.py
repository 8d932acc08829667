"""The cost of calling flexopt from Python: `Problem.evaluate` against the same evaluation by
Rust alone (`Problem._bench_evaluate`, in the same process), and `evaluate_many` per design.

Goals (issue 26): under 2 us on top of the Rust call; `evaluate_many` within 1.5x the Rust
time per design. Writes results/bench/python_overhead.json (the median of `--repeats` runs).

Run from the repository:  python python/bench/overhead.py
"""

import argparse
import json
import pathlib
import platform
import statistics
import time

import numpy as np

import flexopt

ROOT = pathlib.Path(__file__).resolve().parents[2]
TABLE1 = [1.96, 4.07, 0.4, 8.1, 4.01, 1.96, 4.07, 0.4]


def per_call(f, n: int) -> float:
    begin = time.perf_counter()
    for _ in range(n):
        f()
    return (time.perf_counter() - begin) / n


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--calls", type=int, default=20000)
    parser.add_argument("--designs", type=int, default=20000)
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--out", default=str(ROOT / "results" / "bench" / "python_overhead.json"))
    args = parser.parse_args()

    problem = flexopt.Problem.load(ROOT / "problems" / "wei2017.toml")
    design = np.array(TABLE1)
    as_dict = dict(zip(problem.free_variables, TABLE1))
    rng = np.random.default_rng(0)
    designs = problem.lower + (problem.upper - problem.lower) * rng.uniform(
        0.2, 0.8, size=(args.designs, len(design)))
    # warm up: first calls page the code in
    problem.evaluate_many(designs[:100])
    problem._bench_evaluate(TABLE1, 1000)

    samples = {"rust": [], "array": [], "dict": [], "list": [], "many": []}
    for _ in range(args.repeats):
        samples["rust"].append(problem._bench_evaluate(TABLE1, args.calls))
        samples["array"].append(per_call(lambda: problem.evaluate(design, as_array=True), args.calls))
        samples["list"].append(per_call(lambda: problem.evaluate(TABLE1, as_array=True), args.calls))
        samples["dict"].append(per_call(lambda: problem.evaluate(as_dict), args.calls))
        begin = time.perf_counter()
        problem.evaluate_many(designs)
        samples["many"].append((time.perf_counter() - begin) / args.designs)
    median = {k: statistics.median(v) for k, v in samples.items()}
    rust = median["rust"]
    result = {
        "problem": "problems/wei2017.toml",
        "outputs": len(problem.outputs),
        "calls": args.calls,
        "designs": args.designs,
        "repeats": args.repeats,
        "python": platform.python_version(),
        "rust_evaluate_us": rust * 1e6,
        "python_evaluate_array_us": median["array"] * 1e6,
        "python_evaluate_list_us": median["list"] * 1e6,
        "python_evaluate_dict_us": median["dict"] * 1e6,
        "overhead_array_us": (median["array"] - rust) * 1e6,
        "overhead_list_us": (median["list"] - rust) * 1e6,
        "overhead_dict_us": (median["dict"] - rust) * 1e6,
        "evaluate_many_per_design_us": median["many"] * 1e6,
        "evaluate_many_over_rust": median["many"] / rust,
        "goals": {"overhead_us_below": 2.0, "evaluate_many_over_rust_below": 1.5},
        "samples_us": {k: [s * 1e6 for s in v] for k, v in samples.items()},
    }
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(result, indent=2) + "\n")
    for key in ("rust_evaluate_us", "overhead_array_us", "overhead_list_us", "overhead_dict_us",
                "evaluate_many_per_design_us", "evaluate_many_over_rust"):
        print(f"{key:32s} {result[key]:.3f}")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()

"""Problem: evaluation against `flexopt eval`, exact gradients, and errors that name the key."""

import json
import pickle

import numpy as np
import pytest

import flexopt
from conftest import TABLE1, WEI2017


def design_text(design):
    return ",".join(f"{k}={v!r}" for k, v in design.items())


def test_evaluate_equals_flexopt_eval_json_to_the_last_bit(wei2017, cli):
    done = cli("eval", str(WEI2017), "--design", design_text(TABLE1), "--format", "json")
    assert done.returncode == 0, done.stderr
    expected = json.loads(done.stdout)
    got = wei2017.evaluate(TABLE1)
    assert list(got) == list(expected["outputs"])
    for name, value in expected["outputs"].items():
        assert value is not None
        assert got[name].hex() == float(value).hex(), name
    as_array = wei2017.evaluate([TABLE1[n] for n in wei2017.free_variables], as_array=True)
    assert [v.hex() for v in as_array] == [got[n].hex() for n in wei2017.outputs]
    assert dict(wei2017.output_units) == expected["output_units"]
    assert wei2017.report(TABLE1) == expected


def test_evaluate_many_equals_evaluate_row_by_row(wei2017):
    rng = np.random.default_rng(1)
    lo, hi = wei2017.lower, wei2017.upper
    designs = lo + (hi - lo) * rng.uniform(0.2, 0.8, size=(50, len(lo)))
    many = wei2017.evaluate_many(designs)
    assert many.shape == (50, len(wei2017.outputs))
    for row, d in zip(many, designs):
        np.testing.assert_array_equal(row, wei2017.evaluate(d, as_array=True))


def test_jacobian_agrees_with_central_differences(wei2017):
    # Table 1's design is symmetric, where stress_max, a maximum of the two sides' stresses,
    # has a kink: one side made longer
    x = np.array([dict(TABLE1, l4=2.5)[n] for n in wei2017.free_variables])
    jac = wei2017.jacobian(x)
    assert jac.shape == (len(wei2017.outputs), len(x))
    for k in range(len(x)):
        h = 1e-6 * max(abs(x[k]), 1.0)
        up, down = x.copy(), x.copy()
        up[k] += h
        down[k] -= h
        fd = (wei2017.evaluate(up, as_array=True) - wei2017.evaluate(down, as_array=True)) / (2 * h)
        scale = np.maximum(np.abs(jac[:, k]), np.abs(fd)) + 1e-12 * np.abs(
            wei2017.evaluate(x, as_array=True)) / h
        rel = np.abs(jac[:, k] - fd) / np.where(scale > 0, scale, 1.0)
        assert rel.max() < 1e-5, (wei2017.free_variables[k], wei2017.outputs[int(rel.argmax())])


def test_a_problem_pickles_as_its_text(wei2017):
    again = pickle.loads(pickle.dumps(wei2017))
    assert again.file_name == wei2017.file_name
    assert again.evaluate(TABLE1) == wei2017.evaluate(TABLE1)


def test_a_bad_unit_raises_with_the_key_and_the_clis_message(cli, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(WEI2017.read_text().replace('unit = "deg"', 'unit = "furlong"', 1))
    with pytest.raises(flexopt.FlexoptError) as e:
        flexopt.Problem.load(bad)
    assert e.value.key == "variables[1].unit"
    assert e.value.file == str(bad)
    assert e.value.code == 2
    done = cli("eval", str(bad), "--design", design_text(TABLE1))
    assert done.returncode == e.value.code
    assert done.stderr.strip() == f"error: {e.value}"
    with pytest.raises(flexopt.FlexoptError, match=r"key `variables\[1\]\.unit`: unknown unit"):
        flexopt.Problem.from_toml(bad.read_text(), "bad.toml")


def test_a_bad_design_raises_as_flexopt_eval_refuses_it(wei2017, cli):
    bogus = dict(TABLE1, bogus=3.0)
    with pytest.raises(flexopt.FlexoptError) as e:
        wei2017.evaluate(bogus)
    assert e.value.key == "--design bogus"
    done = cli("eval", str(WEI2017), "--design", design_text(bogus))
    assert done.returncode == 2
    assert done.stderr.strip() == f"error: {e.value}"
    partial = {k: v for k, v in TABLE1.items() if k != "t4"}
    with pytest.raises(flexopt.FlexoptError, match="key `--design t4`: missing"):
        wei2017.evaluate(partial)
    with pytest.raises(flexopt.FlexoptError, match=r"key `design`: expected 8 values"):
        wei2017.evaluate([1.0, 2.0])
    with pytest.raises(flexopt.FlexoptError, match=r"key `designs row 1`: outside the model"):
        wei2017.evaluate_many(np.array([[TABLE1[n] for n in wei2017.free_variables],
                                        [-1.0] * 8]))


def test_run_options_are_checked_with_their_key(wei2017):
    with pytest.raises(flexopt.FlexoptError, match="key `starts`: must lie between") as e:
        wei2017.run(starts=0)
    assert e.value.key == "starts"
    with pytest.raises(flexopt.FlexoptError, match="key `solver`: unknown solver \"bfgs\""):
        wei2017.run(solver="bfgs")
    with pytest.raises(flexopt.FlexoptError, match="key `start_range`: the start range 5..2"):
        wei2017.run(starts=4, start_range=(5, 2))


def test_tolerance_equals_flexopt_tolerances_json(wei2017, cli, tmp_path):
    got = wei2017.tolerance(TABLE1, samples=2000, seed=5)
    done = cli("tolerance", str(WEI2017), "--design", design_text(TABLE1), "--samples", "2000",
               "--seed", "5", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert got == json.loads((tmp_path / "tolerance.json").read_text())
    assert got["samples"] == 2000 and got["seed"] == 5


def test_tolerance_refusals_name_the_key(wei2017):
    with pytest.raises(flexopt.FlexoptError, match="key `samples`: must lie between 2") as e:
        wei2017.tolerance(TABLE1, samples=1)
    assert e.value.key == "samples"
    text = WEI2017.read_text() + "\n[tolerances]\nt9 = { sigma = 0.01 }\n"
    with pytest.raises(flexopt.FlexoptError, match="no design variable") as e:
        flexopt.Problem.from_toml(text, "t9.toml")
    assert e.value.key == "tolerances.t9" and e.value.file == "t9.toml"


def test_export_writes_the_part_files(wei2017, tmp_path):
    files = wei2017.export(TABLE1, tmp_path / "part")
    names = sorted(p.rsplit("/", 1)[-1] for p in files)
    assert "part.dxf" in names and "part.svg" in names
    assert all((tmp_path / "part" / n).is_file() for n in names)


def test_a_value_outside_its_bounds_warns_as_flexopt_eval_does(wei2017, cli):
    outside = dict(TABLE1, t2=0.35)
    with pytest.warns(UserWarning) as warned:
        got = wei2017.evaluate(outside)
    done = cli("eval", str(WEI2017), "--design", design_text(outside), "--format", "json")
    assert done.returncode == 0, done.stderr
    assert [f"warning: {w.message}" for w in warned] == done.stderr.strip().splitlines()
    expected = json.loads(done.stdout)["outputs"]
    assert {k: v.hex() for k, v in got.items()} == {k: float(v).hex() for k, v in expected.items()}


def test_a_missing_file_raises_as_the_cli_says_it(cli, tmp_path):
    missing = tmp_path / "missing.toml"
    with pytest.raises(flexopt.FlexoptError) as e:
        flexopt.Problem.load(missing)
    assert e.value.file == str(missing) and e.value.code == 2
    done = cli("eval", str(missing), "--design", design_text(TABLE1))
    assert done.returncode == 2
    assert done.stderr.strip() == f"error: {e.value}"


def test_a_part_that_cannot_be_made_raises_with_exit_code_5(wei2017, cli, tmp_path):
    short = {"l2": 0.5, "delta2": 4.0, "t2": 2.0, "l3": 0.5, "delta3": 4.0, "l4": 0.5,
             "delta4": 4.0, "t4": 2.0}
    out = tmp_path / "part"
    with pytest.raises(flexopt.FlexoptError, match="no part that can be made") as e:
        wei2017.export(short, out)
    assert e.value.code == 5
    assert list(out.iterdir()) == []  # the folder checked writable, as the CLI leaves it
    done = cli("export", str(WEI2017), "--design", design_text(short), "--out", str(out))
    assert done.returncode == 5
    assert done.stderr.strip() == f"error: {e.value}"
    with pytest.raises(flexopt.FlexoptError, match="no part that can be made") as e:
        wei2017.verify(short)
    assert e.value.code == 5


def test_refine_equals_run_refine_fes_refined_json(wei2017, cli, tmp_path):
    done = cli("run", str(WEI2017), "--refine", "fe", "--max-fe", "2", "--quiet",
               "--out", str(tmp_path))
    assert done.returncode in (0, 3, 4), done.stderr
    design = json.loads((tmp_path / "optimum.json").read_text())["design"]
    got = wei2017.refine(design, max_fe=2)
    # the run refines the study's design in SI, this one the file's digits of it read back
    # (a last bit apart); the FE meshes follow the geometry, so the two searches part by
    # about 1e-7 of the objective, and the error estimates (differences of meshes) by 1 %
    refined = json.loads((tmp_path / "refined.json").read_text())
    for key in ("problem", "fidelity", "status", "converged", "feasible", "measurements"):
        assert got[key] == refined[key], key
    assert got["settings"] == dict(refined["settings"], enabled=True)
    for side in ("refined", "analytic_optimum"):
        assert got[side]["design"].keys() == refined[side]["design"].keys()
        for k, v in refined[side]["design"].items():
            assert got[side]["design"][k] == pytest.approx(v, rel=1e-5), (side, k)
    assert got["refined"]["objective"] == pytest.approx(refined["refined"]["objective"], rel=1e-5)
    assert got["measurements"] <= 2


def test_refine_refusals_name_the_key(wei2017):
    with pytest.raises(flexopt.FlexoptError, match="key `max_fe`: must lie between 2 and 200") as e:
        wei2017.refine(TABLE1, max_fe=1)
    assert e.value.key == "max_fe"

"""Issue 50, case 18: what the package refuses, it refuses as flexopt does, naming the key and
what to give; what `evaluate` takes, `evaluate_many` takes row by row."""

import numpy as np
import pytest

import flexopt
from conftest import TABLE1, WEI2017


def free_row(problem):
    return [TABLE1[n] for n in problem.free_variables]


def test_a_string_design_says_what_a_design_is(wei2017):
    with pytest.raises(flexopt.FlexoptError, match="a string is no design: give a dict") as e:
        wei2017.evaluate("l2=1.96,delta2=4.07")
    assert e.value.key == "design" and e.value.code == 2
    assert "extract" not in str(e.value)


def test_a_2d_array_to_evaluate_points_to_evaluate_many(wei2017):
    rows = np.array([free_row(wei2017)] * 2)
    with pytest.raises(flexopt.FlexoptError, match="a 2-D array: .*`evaluate_many`") as e:
        wei2017.evaluate(rows)
    assert e.value.key == "design"
    assert "0-dimensional" not in str(e.value)


def test_evaluate_many_takes_the_arrays_evaluate_takes(wei2017):
    base = np.array([free_row(wei2017)])
    expected = wei2017.evaluate_many(base)
    # float32 rounds the design: compared with evaluate of the same float32 row
    for dtype in (np.float32, np.float64):
        got = wei2017.evaluate_many(base.astype(dtype))
        np.testing.assert_array_equal(
            got[0], wei2017.evaluate(base[0].astype(dtype), as_array=True))
    np.testing.assert_array_equal(wei2017.evaluate_many(base.astype(np.float64)), expected)
    # an int64 array of designs (t2 = 1 and t4 = 1 mm, the lengths whole millimetres)
    ints = np.array([[2, 4, 1, 8, 4, 2, 4, 1]], dtype=np.int64)
    np.testing.assert_array_equal(
        wei2017.evaluate_many(ints)[0], wei2017.evaluate(ints[0], as_array=True))
    with pytest.raises(flexopt.FlexoptError, match="a 1-D array: give a 2-D array") as e:
        wei2017.evaluate_many(base[0])
    assert e.value.key == "designs"


def test_from_toml_applies_the_file_size_limit():
    text = WEI2017.read_text()
    big = text + "\n" + "#" * (2 << 20) + "\n"
    with pytest.raises(flexopt.FlexoptError, match=r"at most 1048576 \(1 MiB\)") as e:
        flexopt.Problem.from_toml(big, "big.toml")
    assert e.value.file == "big.toml" and e.value.code == 2
    assert flexopt.Problem.from_toml(text, "small.toml").name == "wei2017"


def test_negative_samples_name_the_key(wei2017):
    with pytest.raises(flexopt.FlexoptError, match="key `samples`: must lie between 2 and "
                       "10000000, got -5") as e:
        wei2017.tolerance(TABLE1, samples=-5)
    assert e.value.key == "samples"


def test_a_huge_value_is_shown_cut_short(wei2017):
    design = dict(TABLE1, t2=10 ** 400)
    with pytest.raises(flexopt.FlexoptError, match="key `--design t2`") as e:
        wei2017.evaluate(design)
    assert len(str(e.value)) < 200, str(e.value)
    assert "1" + "0" * 39 + "… is not a finite number" in str(e.value)


@pytest.mark.parametrize("threads", [-1, 1025, 100_000])
def test_threads_have_the_command_lines_range(wei2017, threads):
    # one range for every thread count (issue 50, case 7): a study's and a tolerance's
    for call in (lambda: wei2017.run(starts=2, threads=threads),
                 lambda: wei2017.tolerance(TABLE1, samples=10, threads=threads)):
        with pytest.raises(flexopt.FlexoptError,
                           match=f"must lie between 0 and 1024, got {threads}") as e:
            call()
        assert e.value.key == "threads" and e.value.code == 2

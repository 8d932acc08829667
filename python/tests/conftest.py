"""Fixtures: the repository's problem files and the command line the package is held to."""

import os
import pathlib
import subprocess

import pytest

import flexopt

ROOT = pathlib.Path(__file__).resolve().parents[2]
WEI2017 = ROOT / "problems" / "wei2017.toml"
# Table 1's optimum (Table 1 rounds it; the study's optimum lies next to it), file units
TABLE1 = {"l2": 1.96, "delta2": 4.07, "t2": 0.4, "l3": 8.1, "delta3": 4.01,
          "l4": 1.96, "delta4": 4.07, "t4": 0.4}


def flexopt_binary() -> pathlib.Path:
    """The command line built by the root's `cargo build --release` (or `cargo test
    --release`): $FLEXOPT_BIN, else the release binary under $CARGO_TARGET_DIR or target/."""
    if "FLEXOPT_BIN" in os.environ:
        return pathlib.Path(os.environ["FLEXOPT_BIN"])
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "release" / "flexopt"


@pytest.fixture(scope="session", autouse=True)
def openmdao_outputs_elsewhere(tmp_path_factory):
    """OpenMDAO writes a folder per problem into its working directory: a temporary one,
    so that the tests leave the checkout as it is."""
    os.environ["OPENMDAO_WORKDIR"] = str(tmp_path_factory.mktemp("openmdao"))
    os.environ["OPENMDAO_REPORTS"] = "0"


@pytest.fixture(scope="session")
def cli():
    binary = flexopt_binary()
    assert binary.is_file(), f"{binary}: build it with `cargo build --release` first"

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(binary), *args], cwd=ROOT, capture_output=True, text=True)

    return run


@pytest.fixture(scope="session")
def wei2017() -> flexopt.Problem:
    return flexopt.Problem.load(WEI2017)


@pytest.fixture(scope="session")
def study(wei2017) -> flexopt.Study:
    """The file's study: 300 starts, seed 2017."""
    return wei2017.run()

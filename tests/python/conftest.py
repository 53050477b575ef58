"""Shared fixtures of the Python module's tests: the module, the CLI to compare with, and a small
random packing configuration (a few hundred particles, well under a second)."""
import os
import subprocess

import pytest

import aggpack

CLI = os.environ.get("AGGPACK_BINARY", "build/aggpack")

# A graded random packing small enough for a test: Fuller 4-8 mm in a 40 mm cube to 20 %.
SMALL_RANDOM = """
[container]
kind = "box"
length = 0.04
width = 0.04
depth = 0.04

[particle]
alpha = 0.6
edge_length = 0.0
edge_length_ratio = 0.8

[grading]
kind = "fuller"
size_min = 0.004
size_max = 0.008
exponent = 0.5

[packer]
kind = "random"
seed = 7
target_fraction = 0.2
"""


@pytest.fixture
def small_random():
    return SMALL_RANDOM


def run_cli(*args):
    """Runs the aggpack CLI; returns the completed process (stdout and stderr as text)."""
    return subprocess.run([CLI, *args], capture_output=True, text=True, check=False)


@pytest.fixture
def cli():
    assert os.path.exists(CLI), f"the CLI {CLI} is not built (set AGGPACK_BINARY)"
    return run_cli


@pytest.fixture(scope="session")
def small_packing():
    return aggpack.pack(aggpack.pack_config(SMALL_RANDOM))

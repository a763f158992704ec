"""What both test files of the module use: a loaded cornell box, and the command line's one-line
error for the same bad input (to hold Python's ValueError to it)."""
import os
import subprocess

import pytest

import tripath

TRIPATH = os.environ.get("TRIPATH_BINARY", "")


@pytest.fixture(scope="session")
def cornell():
    return tripath.load("cornell")


def command_line_error(*args):
    """The one line `tripath` prints on stderr for bad input, without its 'error: ' prefix."""
    p = subprocess.run([TRIPATH, *args], capture_output=True, text=True)
    assert p.returncode != 0
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), p.stderr
    return lines[0][len("error: "):]


@pytest.fixture
def cli_error():
    return command_line_error

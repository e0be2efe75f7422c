"""Shared fixtures: one default plan from Python, the CLI's plan.json for the same inputs (planned
concurrently in a subprocess), and where the CLI and the shared data are."""
import json
import os
import subprocess

import pytest

import stairplan

BIN_DIR = os.environ.get("STAIRPLAN_BIN_DIR", "build/bin")
SHARED_DIR = os.environ.get("STAIRPLAN_SHARED_DIR", "../shared")


def shared_path(relative):
    """A path in ../shared, or a pytest skip naming it when the shared data is absent."""
    path = os.path.join(SHARED_DIR, relative)
    if not os.path.exists(path):
        pytest.skip(f"shared data absent: {path}")
    return path


@pytest.fixture(scope="session")
def default_plans(tmp_path_factory):
    """(Python Plan, the CLI's plan.json dict) for the default robot and stairs, going down."""
    out = tmp_path_factory.mktemp("cli_plan")
    cli = subprocess.Popen([os.path.join(BIN_DIR, "stairplan"), "plan", "--direction", "down", "--out", str(out)],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    plan = stairplan.plan(direction="down")  # releases the GIL: both plan at once
    _, err = cli.communicate()
    assert cli.returncode == 0, err.decode()
    with open(out / "plan.json") as f:
        return plan, json.load(f)


@pytest.fixture(scope="session")
def default_plan(default_plans):
    return default_plans[0]

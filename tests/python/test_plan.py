"""plan(), Plan, stairs and robots from Python against the CLI's plan.json and the library's rules."""
import json
import os
import subprocess

import numpy as np
import pytest

import stairplan
from conftest import BIN_DIR, shared_path


def test_version_is_the_library_version():
    assert stairplan.__version__.count(".") == 2
    assert stairplan.schema_version >= 1


def without_times(value):
    """The value with every wall-clock field (timing_us, *_us, *_us_*) left out: they differ run to run."""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if not (k.endswith("_us") or "_us_" in k)}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def test_plan_equals_the_cli_plan_json(default_plans):
    plan, cli = default_plans
    mine, cli = without_times(plan.to_dict()), without_times(cli)
    assert "timing_us" not in mine and "footsteps" in mine
    assert mine.keys() == cli.keys()
    for key in cli:
        assert mine[key] == cli[key], key
    assert json.loads(plan.to_json())["footsteps"] == cli["footsteps"]


def test_plan_reports_a_start_pose_as_the_cli_does(tmp_path, default_plan):
    """A robot 2.5 m before the flight (stair mode off there): `start` is the CLI's --start, and
    plan.json's stair_mode and alignment say the same, its source "given"."""
    out = tmp_path / "cli"
    cli = subprocess.Popen([os.path.join(BIN_DIR, "stairplan"), "plan", "--steps", "2", "--start=-2.5,0.3,0.5",
                            "--out", str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    plan = stairplan.plan(steps=2, start=(-2.5, 0.3, 0.5))  # releases the GIL: both plan at once
    _, err = cli.communicate()
    assert cli.returncode == 0, err.decode()
    with open(out / "plan.json") as f:
        expected = json.load(f)
    mine = plan.to_dict()
    assert mine["stair_mode"]["robot"]["source"] == "given"
    assert mine["stair_mode"]["robot"]["x"] == -2.5 and mine["stair_mode"]["engaged"] is False
    assert mine["stair_mode"] == expected["stair_mode"]
    assert mine["alignment"] == expected["alignment"]
    assert default_plan.to_dict()["stair_mode"]["robot"]["source"] == "alignment"  # none given
    with pytest.raises(ValueError, match="start"):
        stairplan.plan(steps=2, start=(1.0, 2.0))


def test_plan_arrays_match_its_dict(default_plan):
    d = default_plan.to_dict()
    steps, body = default_plan.footsteps, default_plan.body
    assert default_plan.status == "ok" and default_plan.valid and default_plan.ok
    assert len(steps) == len(d["footsteps"]) > 0 and len(body) == len(d["body"]) > 0
    assert list(steps["leg"]) == [f["leg"] for f in d["footsteps"]]
    np.testing.assert_array_equal(steps["z"], [f["z"] for f in d["footsteps"]])
    np.testing.assert_array_equal(body["pitch"], [b["pitch"] for b in d["body"]])
    assert np.all(np.diff(body["t"]) > 0)
    assert body["t"][-1] == pytest.approx(default_plan.duration)
    assert default_plan.validation["ok"] is True


def test_stairs_from_keywords_dict_and_yaml(tmp_path):
    yaml = tmp_path / "stairs.yaml"
    yaml.write_text("steps: 4\nrise: 0.15\nrises: [0.15, 0.16, 0.15, 0.15]\ndirection: down\n")
    from_yaml = stairplan.Stairs(yaml)
    assert from_yaml.steps == 4 and from_yaml.direction == "down"
    assert from_yaml.total_rise == pytest.approx(0.61)
    # A scalar field on top replaces the file's per-step list, as the CLI's flags do.
    assert stairplan.Stairs(str(yaml), rise=0.2).total_rise == pytest.approx(0.8)
    from_dict = stairplan.Stairs({"steps": 4, "rise": 0.15, "rises": [0.15, 0.16, 0.15, 0.15], "direction": "down"})
    assert from_dict.to_dict() == from_yaml.to_dict()
    assert stairplan.Stairs(steps=3, run=0.3).to_dict()["run"] == 0.3
    assert stairplan.Stairs().height_at(-0.5, 0.0) == 0.0


def test_robot_from_urdf():
    robot = stairplan.Robot(shared_path("data/robots/anymal_c.urdf"))
    assert [leg["name"] for leg in robot.legs] == ["LF", "RF", "LH", "RH"]
    assert robot.total_mass > 10 and robot.hip_length > 0.3
    assert stairplan.Robot().name == "stairbot"


def test_sweep_rows_and_progress():
    calls = []
    # Negative rises are bad stairs: the sweep machinery without the cost of planning.
    rows = stairplan.sweep(rise=(-0.2, -0.1, 2), run=0.27, directions=["up", "down"], threads=2,
                           progress=lambda done, total: calls.append((done, total)))
    assert [r["index"] for r in rows] == [0, 1, 2, 3]
    assert all(r["status"] == "bad_stairs" and "rise" in r["reason"] for r in rows)
    assert sorted(calls) == [(1, 4), (2, 4), (3, 4), (4, 4)]
    table = stairplan.sweep(rise="-0.2:-0.1:2", run=0.27, as_array=True)
    assert table.dtype.names[:6] == ("index", "direction", "steps", "nosing", "rise", "run")
    np.testing.assert_allclose(table["rise"], [-0.2, -0.1])


def test_gait_design_and_footfalls():
    design = stairplan.design_gait(rise=0.17, run=0.27, max_leg_length=0.21, body_length=0.444)
    assert design["l_min"] == pytest.approx((0.27**2 + 0.17**2) / (2 * 0.27))
    assert design["feasible"] == all(c["holds"] for c in design["conditions"])
    # Four feet up four steps of 0.17 x 0.27, two footfalls on each landing, four on each tread.
    walk = []
    for i in range(6):
        for leg, dx, y in (("LF", 0.05, 0.15), ("RF", 0.05, -0.15), ("LH", -0.05, 0.15), ("RH", -0.05, -0.15)):
            walk.append((0.3 * len(walk), leg, 0.27 * i + dx, y, 0.17 * min(i, 4)))
    found = stairplan.stairs_from_footfalls(walk)
    assert len(found) == 1 and found[0]["traversal"] == "up" and found[0]["steps"] == 4
    assert found[0]["rise"] == pytest.approx(0.17, abs=1e-9) and found[0]["run"] == pytest.approx(0.27, abs=1e-9)


def test_perceive_a_cloud_of_the_default_stairs():
    stairs = stairplan.Stairs(steps=3)
    xs, ys = np.meshgrid(np.arange(-1.0, 2.5, 0.01), np.arange(-0.4, 0.4, 0.02))
    zs = np.vectorize(stairs.height_at)(xs, ys)
    cloud = np.column_stack([xs.ravel(), ys.ravel(), zs.ravel()])
    cloud = cloud[np.isfinite(cloud[:, 2])]
    seen = stairplan.perceive(cloud)
    assert seen.found, seen.reason
    assert seen.fit["steps"] == 3 and seen.fit["rise"] == pytest.approx(0.17, abs=0.01)
    assert len(seen.map.regions) == 4
    # Planned on the perceived map, as `stairplan plan --cloud`: the fit is in plan.json.
    plan = stairplan.plan(stairs=seen)
    assert plan.ok, plan.status_reason
    assert plan.to_dict()["fitted"]["steps"] == 3
    # The alignment pose in the cloud's world too, as the CLI writes it for --cloud.
    assert "world" in plan.to_dict()["alignment"] and "world" in plan.to_dict()["stair_mode"]["robot"]
    with pytest.raises(ValueError, match="rise"):
        stairplan.plan(stairs=seen, rise=0.2)


def test_validate_and_simulate_a_short_flight(tmp_path):
    plan = stairplan.plan(steps=2)
    assert plan.ok, plan.status_reason
    # The validator run again, on the Plan and on its plan.json, gives the pipeline's report.
    assert stairplan.validate(plan) == plan.validation
    path = tmp_path / "plan.json"
    path.write_text(plan.to_json())
    assert stairplan.validate(path) == plan.validation
    outcome = stairplan.simulate(plan)
    assert outcome["passed"], outcome["cause"]
    assert outcome["final_error_m"] < 0.1 and outcome["all_landed_in_step_regions"]
    assert len(outcome["landings"]) == len(plan.footsteps)


def test_plan_gait_auto_takes_the_fastest_gait_that_validates():
    """gait='auto' is the CLI's --gait auto: up two default steps the trot validates, its dynamic
    check judged; a gait the pipeline does not plan is refused, naming the option."""
    plan = stairplan.plan(steps=2, gait="auto")
    d = plan.to_dict()
    assert plan.status == "ok"
    assert plan.gait == "trot" and d["gait"] == "trot" and d["rejected_gaits"] == []
    assert d["validation"]["ok"] and d["validation"]["dynamics"]["mode"] == "judge"
    with pytest.raises(stairplan.FieldError) as e:
        stairplan.plan(steps=2, gait="gallop")
    assert e.value.field == "gait"

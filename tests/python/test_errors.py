"""Every bad call raises the Python exception that says what is wrong; none crashes."""
import numpy as np
import pytest

import stairplan
from stairplan import optim


def test_bad_stair_field_is_a_value_error_naming_it():
    with pytest.raises(ValueError, match="rise") as e:
        stairplan.Stairs(rise=-0.1)
    assert isinstance(e.value, stairplan.FieldError) and "rise" in e.value.field
    with pytest.raises(ValueError, match="bogus"):
        stairplan.Stairs({"bogus": 1})
    with pytest.raises(ValueError, match="direction"):
        stairplan.Stairs(direction="sideways")


def test_missing_files_are_file_not_found_naming_the_file(tmp_path):
    missing = str(tmp_path / "missing.yaml")
    for call in (lambda: stairplan.Stairs(missing), lambda: stairplan.Robot(missing),
                 lambda: stairplan.plan(stairs=missing), lambda: optim.read_qps(missing),
                 lambda: stairplan.validate(missing), lambda: stairplan.read_point_cloud(missing),
                 lambda: stairplan.stairs_from_footfalls(missing)):
        with pytest.raises(FileNotFoundError) as e:
            call()
        assert e.value.filename == missing


def test_malformed_files_are_value_errors_naming_the_file(tmp_path):
    urdf = tmp_path / "bad.urdf"
    urdf.write_text("<robot name='x'><link name='a'/><joint")
    with pytest.raises(ValueError, match="bad.urdf"):
        stairplan.Robot(urdf)
    qps = tmp_path / "bad.qps"
    qps.write_text("NAME X\nROWS\n N OBJ\nCOLUMNS\n x OBJ notanumber\nENDATA\n")
    with pytest.raises(ValueError, match="bad.qps"):
        optim.read_qps(qps)


def test_bad_plan_options_name_the_option():
    for options, name in (({"facing": "sideways"}, "facing"), ({"horizon": 2}, "horizon"), ({"nlp": "cplex"}, "nlp"),
                          ({"planner": "teleport"}, "planner"), ({"bogus": 1}, "bogus"), ({"rise": -1.0}, "rise")):
        with pytest.raises(ValueError, match=name):
            stairplan.plan(**options)
    with pytest.raises(TypeError):
        stairplan.plan(stairs=42)
    with pytest.raises(ValueError, match="rise"):
        stairplan.sweep(rise="a:b:c")
    with pytest.raises(ValueError, match="rise"):
        stairplan.design_gait(rise=-1.0)


def test_program_misuse_is_a_value_error():
    prog = optim.Program()
    z = prog.add_variables("z", 2)
    with pytest.raises(ValueError, match="z"):
        prog.add_quadratic_cost(z, np.eye(3), np.zeros(3))
    with pytest.raises(ValueError, match="z"):
        prog.set_variable_bounds(z, np.array([np.nan, 0.0]), np.ones(2))
    # An exception in a Python callback comes out of solve() as itself.
    prog.add_nonlinear_cost([z], lambda v: 1 / 0, lambda v, k: v)
    with pytest.raises(ZeroDivisionError):
        optim.IpoptSolver().solve(prog)


def test_callback_and_loop_misuse(default_plan):
    def stop(done, total):
        raise KeyError("stop")
    with pytest.raises(KeyError):
        stairplan.sweep(rise=(-0.2, -0.1, 2), run=0.27, progress=stop)
    planner = stairplan.BodyPlanner(default_plan)
    with pytest.raises(ValueError):
        planner.update(stairplan.BodyState(z=float("nan")), 0.0)
    with pytest.raises(ValueError, match="bogus"):
        stairplan.simulate(default_plan, bogus=1.0)

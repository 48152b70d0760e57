"""gyro.read_scenario: a scenario as it is flown, its example or base expanded, whose sections
are the flight loop's keywords."""

import pytest

import gyro


def test_given_seeker_slew_then_it_is_the_seeker_example_with_the_files_changes(source_dir):
    doc = gyro.read_scenario(source_dir / "scenarios" / "seeker_slew.json")
    example = gyro.examples.seeker()
    assert "example" not in doc
    assert doc["gyro"]["rotor"] == example.gyro["rotor"]               # the example's rotor
    assert doc["gyro"]["torquer"]["max_torque"] == 0.05                # the file's change
    assert doc["component"]["cage_gain_1_s"] == example.component["cage_gain_1_s"]
    assert doc["component"]["max_torque"] == 0.04


def test_given_a_fault_scenario_then_its_base_is_expanded(source_dir):
    doc = gyro.read_scenario(str(source_dir / "scenarios" / "fault_dead_torquer.json"))
    slew = gyro.read_scenario(source_dir / "scenarios" / "seeker_slew.json")
    assert doc["gyro"]["faults"][0]["kind"] == "dead_torquer"
    assert {k: v for k, v in doc["gyro"].items() if k != "faults"} == slew["gyro"]


def test_given_a_dict_on_an_example_then_it_expands_and_the_loop_takes_it():
    doc = gyro.read_scenario({"example": "seeker", "run": {"rate_hz": 2000, "ticks": 4},
                              "body": {"rate_rad_s": [0.0, 0.0, 0.0]},
                              "guidance": {"schedule": [{"t_s": 0.0, "request": "uncage"}]}})
    stub = gyro.SimulatedGyro(5e-4, **doc["gyro"])
    gyro.GyroComponent(stub, 5e-4, **doc["component"])


def test_given_an_unknown_example_then_scenario_error_names_the_key():
    with pytest.raises(gyro.ScenarioError) as e:
        gyro.read_scenario({"example": "seekr"})
    assert e.value.field == "example"
    assert "one of: seeker, report" in str(e.value)

"""The names Python shows come from the C++ tables beside the enums and configuration structs
(gyro/status.hpp, the field tables): the type stubs (gyro/__init__.pyi) must agree with them."""

import re

import pytest

import gyro


def stub_members(source_dir, cls):
    text = (source_dir / "python" / "gyro" / "__init__.pyi").read_text(encoding="utf-8")
    body = re.search(rf"^class {cls}\(.*?\):\n((?:    .*\n)+)", text, re.M)
    assert body, f"class {cls} not in the stub"
    return re.findall(r"^    ([A-Z_0-9]+): int$", body.group(1), re.M)


def test_given_the_status_enum_then_its_values_count_up_in_the_stubs_order(source_dir):
    names = stub_members(source_dir, "Status")
    assert list(gyro.Status.__members__) == names
    assert [int(gyro.Status.__members__[n]) for n in names] == list(range(len(names)))
    assert int(gyro.Status.NUMERICAL_OVERFLOW) == 8  # the C++ enumerator's value


def test_given_every_status_then_each_has_its_own_description():
    texts = [gyro.status_text(s) for s in gyro.Status.__members__.values()]
    assert len(set(texts)) == len(texts) and "unknown status" not in texts
    assert gyro.status_text(gyro.Status.NON_FINITE_INPUT) == "non-finite input"


@pytest.mark.parametrize("cls, field, names", [
    (gyro.GyroModel, "torquer_axes", ["gyro", "gimbal"]),
    (gyro.GimbalPlant, "spin_drive", ["motor", "free"]),
    (gyro.GimbalPlant, "torquer_axes", ["gyro", "gimbal"]),
])
def test_given_an_enumerated_field_then_its_names_are_the_tables(cls, field, names):
    assert field in cls.config_fields
    args = (1e-3,) if cls is gyro.GimbalPlant else ()
    with pytest.raises(gyro.ConfigError, match="expected one of " + ", ".join(names)) as e:
        cls(*args, **{field: "none of them"})
    assert e.value.field == field

"""The example gyros, as the C++ headers of examples/include/gyro/ define them (nothing is
retyped here): each configuration in the form its Python constructor takes.

    ex = gyro.examples.seeker()
    stub = gyro.SimulatedGyro(ex.tick_s, **ex.gyro)             # a scenario's "gyro" section
    component = gyro.GyroComponent(stub, ex.tick_s, **ex.component)  # its "component" section
    plant = gyro.GimbalPlant(ex.tick_s, **ex.gimbal_plant)       # the seeker's gimbal alone
    model = gyro.GyroModel(**gyro.examples.report().model)      # the report's gyro

The dicts are fresh copies: change a field and pass it on.
"""

import copy
from dataclasses import dataclass
from typing import Any, Dict, Optional

from . import _gyro


@dataclass(frozen=True)
class Example:
    """An example gyro's configurations.

    tick_s: its tick (s). spin_hz: its spin (Hz).
    gyro: SimulatedGyro's keywords (the keys of a scenario's "gyro" section), or None.
    component: GyroComponent's keywords (a scenario's "component" section), or None.
    gimbal_plant: GimbalPlant's keywords, or None. model: GyroModel's keywords.
    """

    tick_s: float
    spin_hz: float
    model: Dict[str, Any]
    gyro: Optional[Dict[str, Any]] = None
    component: Optional[Dict[str, Any]] = None
    gimbal_plant: Optional[Dict[str, Any]] = None


def _example(name):
    return Example(**copy.deepcopy(_gyro._examples[name]))  # pylint: disable=protected-access


def seeker() -> Example:
    """The seeker gyro (gyro/seeker_example.hpp): SI, on the gimbal plant, 2 kHz tick, ideal
    pickoffs and torquers. scenarios/seeker_slew.json builds on it ("example": "seeker") and
    lists what the device it flies changes: 1 kHz, the imperfections, other limits
    (docs/scenarios.md, "Examples and bases")."""
    return _example("seeker")


def report() -> Example:
    """The report's sample gyro (gyro/report_sample.hpp): slug*ft^2, INITG's step."""
    return _example("report")

"""Results of SIL and campaign runs: columns as NumPy arrays, keyed by the CSV's names."""

from dataclasses import dataclass, field
from typing import Any, Dict, List

import numpy as np


@dataclass
class SilRun:
    """A SIL run's time history and the component's telemetry.

    columns: gyro_sil's CSV columns (name -> array, one entry per tick, tick 0 first):
    float64 for numbers, uint64 for the tick, flag words and status, str for mode and request.
    telemetry: the run's summary (final_mode, flags_seen, flags_seen_names, counters per
    flag, refused_steps, gimbal_stop_hits, max_abs_gimbal_rad, ...).
    """

    columns: Dict[str, np.ndarray]
    telemetry: Dict[str, Any] = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        """The column `name` (as in the CSV header)."""
        return self.columns[name]

    def __len__(self) -> int:
        """The number of rows (ticks, tick 0 included)."""
        return len(self.columns["t"])

    def keys(self):
        """The column names, in the CSV's order."""
        return self.columns.keys()


@dataclass
class CampaignRun:
    """A campaign's per-run table (gyro_campaign's runs.csv), column by column.

    columns: name -> float64 array for numeric columns (NaN where a cell is empty), else a
    list of str. header: the column names in order.
    """

    header: List[str]
    columns: Dict[str, Any]

    def __getitem__(self, name: str):
        """The column `name`."""
        return self.columns[name]

    def __len__(self) -> int:
        """The number of runs."""
        return len(self.columns["run"])

    def rows(self) -> List[Dict[str, Any]]:
        """The table as a list of dicts, one per run."""
        return [{h: self.columns[h][i] for h in self.header} for i in range(len(self))]

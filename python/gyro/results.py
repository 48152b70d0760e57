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


@dataclass(repr=False)
class CampaignRun:
    """A campaign's per-run table (gyro_campaign's runs.csv), column by column.

    columns: name -> run and seed as uint64 arrays (exact: a seed has 64 bits); the verdicts
    (pass, detected, false_alarm, safe_mode_after_stop) as lists of bool, None where a run has
    no verdict (it was refused, or has no fault to detect); other numbers as float64 arrays
    (NaN where a cell is empty); anything else (status, fault_kind, final_mode,
    safe_mode_cause, reason, ...) as lists of str.
    header: the column names in order.
    """

    header: List[str]
    columns: Dict[str, Any]

    def summary(self) -> Dict[str, Any]:
        """Runs, runs per status, and the pass verdicts: passed, failed, none (not judged)."""
        status: Dict[str, int] = {}
        for s in self.columns["status"]:
            status[s] = status.get(s, 0) + 1
        verdicts = self.columns["pass"]
        return {"runs": len(self), "status": status,
                "passed": sum(1 for v in verdicts if v is True),
                "failed": sum(1 for v in verdicts if v is False),
                "not_judged": sum(1 for v in verdicts if v is None)}

    def __repr__(self) -> str:
        s = self.summary()
        status = ", ".join(f"{k} {v}" for k, v in sorted(s["status"].items()))
        return (f"CampaignRun({s['runs']} runs, {len(self.header)} columns; status: {status}; "
                f"passed {s['passed']}, failed {s['failed']})")

    def __getitem__(self, name: str):
        """The column `name`."""
        return self.columns[name]

    def __len__(self) -> int:
        """The number of runs."""
        return len(self.columns["run"])

    def rows(self) -> List[Dict[str, Any]]:
        """The table as a list of dicts, one per run."""
        return [{h: self.columns[h][i] for h in self.header} for i in range(len(self))]

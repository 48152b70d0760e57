"""Exceptions of the gyro package.

The C++ library is exception-free: its calls return a Status, and configure() a check
naming the refused field. The bindings turn those refusals into these exceptions.
"""


class GyroError(ValueError):
    """Base of the gyro refusals (a ValueError: the input was refused)."""


class StatusError(GyroError):
    """A call refused with a gyro.Status other than OK; `status` holds it."""

    def __init__(self, message, status=None):
        super().__init__(message)
        self.status = status


class ConfigError(StatusError):
    """A configuration refused; `field` names the field (as the C++ check names it)."""

    def __init__(self, message, field, status=None):
        super().__init__(message, status)
        self.field = field


class ScenarioError(ConfigError):
    """A scenario or campaign refused; `field` is its JSON path, `file` the source."""

    def __init__(self, message, field, file):
        super().__init__(message, field)
        self.file = file


class RunError(RuntimeError):
    """A SIL run failed at run time (a call the loop relies on was refused)."""

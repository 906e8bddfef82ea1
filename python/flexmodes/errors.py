"""The exceptions flexmodes raises.

Every one carries ``kind`` (the Rust error's variant, e.g. ``"BodyFile.NotSymmetric"``) and
``data`` (its fields as a dict: file and line, node, DOF, residual, ...), besides the message
the command line prints.
"""


class FlexmodesError(Exception):
    """Base of every flexmodes error."""

    kind: str = ""
    data: object = None


class InputError(FlexmodesError, ValueError):
    """An argument flexmodes cannot use: a dense or mis-shaped matrix, an unknown method."""


class BodyFileError(FlexmodesError, ValueError):
    """A body (file or matrices) that does not check: not symmetric, mass not positive, an
    entry that is not finite, a node set out of range."""


class MechanismError(FlexmodesError, ValueError):
    """A body with more zero-energy modes than a free body's rigid motions."""


class LinalgError(FlexmodesError, ArithmeticError):
    """A factorisation or eigensolve that failed, or whose result failed its check."""


class ReductionError(FlexmodesError, ValueError):
    """A reduction that cannot be built as asked (a method's needs, an interface)."""


class DynamicsError(FlexmodesError):
    """A simulation that cannot run as asked."""


class FileError(FlexmodesError, OSError):
    """Reading or writing a file failed (the path is in ``data``)."""


class Cancelled(FlexmodesError):
    """The work was cancelled (a progress callback raised; that exception is re-raised
    instead)."""


__all__ = [
    "FlexmodesError",
    "InputError",
    "BodyFileError",
    "MechanismError",
    "LinalgError",
    "ReductionError",
    "DynamicsError",
    "FileError",
    "Cancelled",
]

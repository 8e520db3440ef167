"""Exceptions that the command line turns into one- or two-line messages (exit code 2 / 1)."""

from __future__ import annotations


class MoorlineError(Exception):
    """Base class of all errors moorline raises on purpose."""


class CaseError(MoorlineError):
    """Bad input: names the file, the key path inside it and what is wrong.

    Parameters
    ----------
    reason
        What is wrong, in words a user understands.
    file
        The case file (or ``None`` for models built in Python).
    field
        Dotted key path inside the case, e.g. ``lines.line1.length``.
    """

    def __init__(self, reason: str, file: str | None = None, field: str | None = None) -> None:
        self.reason = reason
        self.file = file
        self.field = field
        super().__init__(self.__str__())

    def __str__(self) -> str:
        where = []
        if self.file:
            where.append(str(self.file))
        if self.field:
            where.append(self.field)
        prefix = ": ".join(where)
        return f"{prefix}: {self.reason}" if prefix else self.reason


class ConvergenceError(MoorlineError):
    """A solver did not converge: says when, where and with what residual.

    Parameters
    ----------
    message
        What failed.
    time
        Simulation time [s] (``None`` in statics).
    where
        Location of the largest residual, e.g. ``"line line1, node 7"``.
    residual
        Norm of the residual when the solver gave up.
    """

    def __init__(
        self,
        message: str,
        time: float | None = None,
        where: str | None = None,
        residual: float | None = None,
    ) -> None:
        self.message = message
        self.time = time
        self.where = where
        self.residual = residual
        super().__init__(self.__str__())

    def __str__(self) -> str:
        parts = [self.message]
        if self.time is not None:
            parts.append(f"at t = {self.time:.6g} s")
        if self.where:
            parts.append(f"largest residual at {self.where}")
        if self.residual is not None:
            parts.append(f"residual {self.residual:.3e}")
        return "; ".join(parts)

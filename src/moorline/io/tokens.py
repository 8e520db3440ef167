"""Tokens of text input files (MoorDyn decks and their companion files)."""

from __future__ import annotations


def is_number(token: str) -> bool:
    """Whether ``token`` reads as a float (``nan`` and ``inf`` included)."""
    try:
        float(token)
    except ValueError:
        return False
    return True

"""Case files: YAML schema (pydantic), unit handling (pint) and the loader."""

from .case import MAX_STRAIN, load_case, load_case_text

__all__ = ["MAX_STRAIN", "load_case", "load_case_text"]

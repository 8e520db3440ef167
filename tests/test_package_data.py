"""moorline's YAML data files read with libyaml (when PyYAML has it) give what PyYAML's
pure-Python safe loader gives."""

from __future__ import annotations

from importlib import resources

import pytest
import yaml

from moorline.package_data import load_yaml

FILES = [("moorline.catalog", "lines.yaml"), ("moorline.catalog", "design.yaml"),
         ("moorline", "data/tn_curves.yaml")]


@pytest.mark.parametrize(("package", "name"), FILES)
def test_a_data_file_reads_as_the_pure_python_loader_reads_it(package: str, name: str) -> None:
    text = resources.files(package).joinpath(name).read_text(encoding="utf-8")
    expected = yaml.load(text, Loader=yaml.SafeLoader)  # noqa: S506 - the pure-Python one
    assert load_yaml(package, name) == expected
    assert expected  # not an empty file

"""CLI with bodies: statics JSON with body poses and the 6x6 mooring stiffness, dynamics with
body motion histories streamed to results.nc, plots and an animation."""

import json
import re
from pathlib import Path

import numpy as np
import xarray as xr
from click.testing import CliRunner

from moorline.cli import cli

ROOT = Path(__file__).resolve().parents[1]


def _case(tmp_path: Path) -> Path:
    text = (ROOT / "cases" / "wang_box.yaml").read_text(encoding="utf-8")
    text = re.sub(r"analyses:.*", "analyses:\n  - {kind: statics}\n  - {kind: dynamics, "
                  "duration: 3, dt: 0.05}\n", text, flags=re.S)
    text = text.replace("    kind: free\n", "    kind: free\n    force_history: {kind: harmonic, "
                        "amplitude: [1.0e5, 0, 0], period: 3.93}\n", 1)
    path = tmp_path / "box.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_statics_json_has_body_pose_and_mooring_stiffness(tmp_path):
    result = CliRunner().invoke(cli, ["statics", str(ROOT / "cases" / "wang_box.yaml"),
                                      "--out", str(tmp_path), "--json", "--quiet"])
    assert result.exit_code == 0, result.output
    body = json.loads(result.stdout)["bodies"]["box"]
    assert 0.85 < 2.5 - body["position"][2] < 0.95  # the draft (Wang: 0.896 m)
    K = np.array(body["mooring_stiffness"])
    assert K.shape == (6, 6) and K[0, 0] > 0 and K[2, 2] > 0
    assert np.allclose(K, K.T, rtol=1e-6, atol=1e-6 * np.abs(K).max())


def test_dynamics_with_a_body_streams_its_pose_and_animates(tmp_path, undescribed):
    case = _case(tmp_path)
    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["run", str(case), "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    folder = out / "wang-box"
    assert (folder / "body_motion.png").is_file()
    assert (folder / "snapshots_3d.png").is_file()
    assert undescribed(folder / "results.nc") == []
    with xr.open_dataset(folder / "results.nc", group="dynamics") as ds:
        assert list(ds["dof"].values) == ["surge", "sway", "heave", "roll", "pitch", "yaw"]
        pose = ds["body_pose"].values
        assert pose.shape[1:] == (1, 6)
        assert np.ptp(pose[:, 0, 0]) > 1e-3  # the harmonic surge force moves the box
        mooring = ds["body_mooring_force"].values
        assert mooring.shape == pose.shape and np.isfinite(mooring).all()
        assert mooring[0, 0, 2] < 0  # the lines pull the box down
    result = CliRunner().invoke(cli, ["plot", str(folder / "results.nc"), "--animate",
                                      "--quiet"])
    assert result.exit_code == 0, result.output
    assert (folder / "animation.gif").stat().st_size > 1000

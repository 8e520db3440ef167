"""CLI with bodies: statics JSON with body poses and the 6x6 mooring stiffness, dynamics with
body motion histories streamed to results.nc, plots and an animation."""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import scipy.optimize
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


def _exact_draft(text: str) -> float:
    """Wang box draft from Archimedes with the lines' top vertical forces from the closed-form
    elastic catenary (Irvine (1981) eq. 1.33, fully suspended, anchors and unstretched length
    of the case file), written here without moorline: solve
    rho g (26 x 10) h = M g + 4 V_top(h) for h, the fairleads at depth h (keel corners)."""
    num = r"([-+0-9.e]+)"
    L = float(re.search(r"length: " + num + ", segments", text).group(1))
    ax, ay = (float(v) for v in re.search(r"anchorA: .*?\[" + num + ", " + num, text).groups())
    rho, g, M, EA, m, D = 1025.0, 9.81, 1.2e5, 2e11 * math.pi * 0.1**2 / 4, 62.83185307179587, 0.1
    w = (m - rho * math.pi * D**2 / 4) * g  # submerged weight per length
    X = math.hypot(ax - 13.0, ay - 5.0)  # horizontal span anchor -> fairlead

    def top_vertical(Z: float) -> float:
        def mismatch(p: np.ndarray) -> list[float]:
            H, Va = p * w * L  # scaled unknowns
            Vb = Va + w * L
            x = H * L / EA + H / w * (math.asinh(Vb / H) - math.asinh(Va / H))
            z = (Va * L + w * L * L / 2) / EA + H / w * (math.hypot(1, Vb / H)
                                                         - math.hypot(1, Va / H))
            return [x / X - 1.0, z / Z - 1.0]

        sol = scipy.optimize.root(mismatch, [1.0, 1.0], method="hybr", tol=1e-13)
        assert np.abs(sol.fun).max() < 1e-13  # closes on both ends
        assert sol.x[1] > 0.0  # fully suspended: the line rises from the anchor
        return float((sol.x[1] + 1.0) * w * L)

    return scipy.optimize.brentq(
        lambda h: rho * 260.0 * h - M - 4.0 * top_vertical(100.0 - h) / g, 0.5, 1.5, xtol=1e-14)


def _statics_json(tmp_path: Path, text: str, name: str) -> dict:
    path = tmp_path / f"{name}.yaml"
    path.write_text(text, encoding="utf-8")
    result = CliRunner().invoke(cli, ["statics", str(path), "--out", str(tmp_path / name),
                                      "--json", "--quiet"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)["bodies"]["box"]


def test_statics_json_has_body_pose_and_mooring_stiffness(tmp_path):
    """The draft against Archimedes with the exact catenary (0.89656 m; Wang's 0.896 m comes
    from parabolic cable formulas). The error of the straight-element mesh (weights lumped at
    the nodes) is second order in the element length: from 11 to 22 elements per line it must
    fall by 4 (3.5-4.5), the Richardson extrapolation (4 d22 - d11) / 3 must match the exact
    draft to 2e-5 relative (its O(n^-4) remainder), and the 11-element draft itself lie
    within 0.2 % (about three times the mesh error the pair implies, (d22 - d11) 4/3 =
    0.07 %)."""
    text = (ROOT / "cases" / "wang_box.yaml").read_text(encoding="utf-8")
    exact = _exact_draft(text)
    body = _statics_json(tmp_path, text, "box11")
    d11 = 2.5 - body["position"][2]
    d22 = 2.5 - _statics_json(tmp_path, text.replace("segments: 11", "segments: 22"),
                              "box22")["position"][2]
    assert abs(d11 - exact) < 2e-3 * exact
    assert 3.5 < (d11 - exact) / (d22 - exact) < 4.5
    assert (4.0 * d22 - d11) / 3.0 == pytest.approx(exact, rel=2e-5)
    assert body["position"][:2] == pytest.approx([0.0, 0.0], abs=1e-9)  # symmetric
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

"""rodnet.gridshell.fit: a gridshell fitted to a target mesh, as `rodnet gridshell fit`."""

import pytest

import rodnet


def cap_obj(path, n=24):
    """z = 0.5 (1 - x^2 - y^2) over [-0.7, 0.7]^2, n x n quads split in two."""
    lines = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = -0.7 + 1.4 * i / n, -0.7 + 1.4 * j / n
            lines.append(f"v {x} {y} {0.5 * (1 - x * x - y * y)}")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            b, c, d = a + 1, a + n + 2, a + n + 1
            lines.append(f"f {a} {b} {c}")
            lines.append(f"f {a} {c} {d}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_fit_forms_a_shell_near_its_target(tmp_path):
    r = rodnet.gridshell.fit(cap_obj(tmp_path / "cap.obj"), 0.2)
    assert r.converged
    d = r.to_dict()
    t = d["target"]
    assert t["shape"] == "mesh"
    assert t["max_abs_distance"] < 0.05
    assert t["net"]["joints"] > 20
    assert d["net"] == t["net"]
    # A rod's points as a NumPy array.
    assert r.points(0).shape[1] == 3


def test_fit_errors_are_located(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.gridshell.fit(bad, 0.1)
    assert e.value.line == 2
    assert "bad.obj" in str(e.value.path)
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.gridshell.fit(cap_obj(tmp_path / "cap.obj"), -1.0)
    assert e.value.field == "spacing"
    with pytest.raises(rodnet.SolveError):
        rodnet.gridshell.fit(cap_obj(tmp_path / "cap2.obj"), 5.0, layout="between")

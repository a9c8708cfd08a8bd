"""Elastic gridshells: the hemispherical Chebyshev-net gridshell of `rodnet gridshell hemisphere`,
and gridshells fitted to a target mesh (`rodnet gridshell fit`)."""

from . import _rodnet


def hemisphere(
    rods=12,
    subdivide=4,
    joint="ball",
    *,
    radius=None,
    section=None,
    section_ratio=None,
    young_modulus=None,
    poisson_ratio=None,
    load_steps=None,
    tolerance=None,
    start_cap=None,
    path=None,
    modes=None,
    progress=None,
):
    """Generates the flat footprint of the hemispherical gridshell, form-finds it and compares
    it with the sphere and the Chebyshev net, as `rodnet gridshell hemisphere` does.

    The options are the command's (docs/cli.md); None keeps the command's default:
    `radius` R (m), `section` ("circle:r", "ellipse:a,b" or "rectangle:w,h", in units of R) or
    `section_ratio` (a circle's r/R), `young_modulus` (Pa), `poisson_ratio`, `load_steps`,
    `tolerance`, `start_cap`, `path` ("cap-nets" or "straight"), `modes` (the K lowest
    eigenvalues of the dome, in `results.stability`). `progress(step, iteration, residual,
    energy)` is called after every Newton iteration.

    Returns `Results` whose `target` holds the shape metrics and `gridshell` the generator's
    block. Raises `SceneError` (with `field`, the option) for options the command refuses.
    """
    given = {
        "radius": radius,
        "section": section,
        "section_ratio": section_ratio,
        "young_modulus": young_modulus,
        "poisson_ratio": poisson_ratio,
        "load_steps": load_steps,
        "tolerance": tolerance,
        "start_cap": start_cap,
        "path": path,
        "modes": modes,
    }
    options = [("rods", rods), ("subdivide", subdivide), ("joint", joint)]
    options += [(k, v) for k, v in given.items() if v is not None]
    return _rodnet.hemisphere(options, progress)


def options():
    """The hemisphere generator's option names (also the parameters a sweep can vary)."""
    return _rodnet.hemisphere_options()


def fit(
    target,
    spacing,
    *,
    origin=None,
    directions=None,
    layout="on",
    min_angle=None,
    subdivide=4,
    joint="ball",
    section_radius=None,
    young_modulus=1e9,
    poisson_ratio=0.3,
    tolerance=None,
    progress=None,
):
    """Fits a Chebyshev-net gridshell to the OBJ triangle mesh `target` and form-finds it from
    its net, as `rodnet gridshell fit TARGET --spacing A` does (docs/gridshell.md).

    `origin` (x, y, z) and `directions` ((x1, y1, z1), (x2, y2, z2)) place the generators
    (defaults: the highest vertex, x and y); `layout` "on" or "between"; `min_angle` the
    locking angle in degrees (default 15); `section_radius` the rods' circular section in m
    (default spacing/50). Returns `Results` whose `target` holds the mesh distances and the
    `net` block. Raises `SceneError` for a bad mesh (its file and line) or option, `SolveError`
    when no net fits or the solve fails.
    """
    return _rodnet.fit(
        str(target),
        float(spacing),
        origin=None if origin is None else tuple(float(x) for x in origin),
        directions=None
        if directions is None
        else tuple(tuple(float(x) for x in d) for d in directions),
        layout=layout,
        min_angle=min_angle,
        subdivide=subdivide,
        joint=joint,
        section_radius=section_radius,
        young_modulus=young_modulus,
        poisson_ratio=poisson_ratio,
        tolerance=tolerance,
        progress=progress,
    )

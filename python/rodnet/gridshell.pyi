from typing import List, Optional, Sequence, Tuple, Union
import os

from ._rodnet import Progress, Results

def hemisphere(
    rods: int = 12,
    subdivide: int = 4,
    joint: str = "ball",
    *,
    radius: Optional[float] = None,
    section: Optional[str] = None,
    section_ratio: Optional[float] = None,
    young_modulus: Optional[float] = None,
    poisson_ratio: Optional[float] = None,
    load_steps: Optional[int] = None,
    tolerance: Optional[float] = None,
    start_cap: Optional[float] = None,
    path: Optional[str] = None,
    modes: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> Results: ...
def options() -> List[str]: ...
def fit(
    target: Union[str, os.PathLike],
    spacing: float,
    *,
    origin: Optional[Sequence[float]] = None,
    directions: Optional[Tuple[Sequence[float], Sequence[float]]] = None,
    layout: str = "on",
    min_angle: Optional[float] = None,
    subdivide: int = 4,
    joint: str = "ball",
    section_radius: Optional[float] = None,
    young_modulus: float = 1e9,
    poisson_ratio: float = 0.3,
    tolerance: Optional[float] = None,
    progress: Optional[Progress] = None,
) -> Results: ...

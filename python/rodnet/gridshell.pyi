from typing import List, Optional

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

import os
from concurrent.futures import Executor
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

class SweepTable:
    csv: str
    rows: List[Dict[str, Any]]
    missing: List[int]
    parameters: List[str]
    quantities: List[str]
    def column(self, name: str) -> npt.NDArray[Any]: ...
    def __len__(self) -> int: ...

def run_point(source: Tuple[str, str, str, Optional[str]], index: int) -> Dict[str, Any]: ...
def sweep(
    spec: Union[str, "os.PathLike[str]", Dict[str, Any]],
    *,
    executor: Optional[Executor] = None,
    jobs: Optional[int] = None,
    output: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> SweepTable: ...

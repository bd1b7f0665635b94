# Type stubs of the package (the native part: _core.pyi; the sweep: sweeps.py, typed inline).
from typing import Any, Optional, Union
import os

import pandas

from ._core import Body as Body, SimulationError as SimulationError, World as World, __version__ as __version__
from ._core import parameters as parameters, scene_files as scene_files

def sweep(
    scene: Union[str, os.PathLike[str]],
    grid: Any,
    client: Any = None,
    *,
    workers: Optional[int] = None,
    out: Union[str, os.PathLike[str], None] = None,
    frames: Optional[int] = None,
    overwrite: bool = False,
) -> pandas.DataFrame: ...

"""SoftSculpt: soft-body physics for 3D shapes.

A mass-spring-damper engine with ideal-gas pressure (Matyka & Ollila 2003): vertices are point
masses, edges damped Hooke springs, and a gas with P = nRT / V pushes every face outward.
The same engine as the ``softsculpt`` command and the web modeler (docs/python.md).

    >>> import softsculpt
    >>> w = softsculpt.World.from_mesh("builtin:sphere", stiffness=300.0)
    >>> w.advance(0.5)
    >>> w.bodies[0].positions.shape
"""

from ._core import Body, SimulationError, World, __version__, parameters, scene_files

__all__ = ["World", "Body", "SimulationError", "parameters", "scene_files", "sweep", "__version__"]


def sweep(*args, **kwargs):
    """Run a scene over a grid of parameters on Dask; see :func:`softsculpt.sweeps.sweep`."""
    from .sweeps import sweep as _sweep

    return _sweep(*args, **kwargs)

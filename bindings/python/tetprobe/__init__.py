"""tetprobe: light probes interpolated over a tetrahedral tessellation (a thin ctypes binding).

Units, shapes and layouts (the same everywhere in the package):
- Positions and points are float32 world units, arrays of shape [N, 3] (other number dtypes are
  converted; any row stride is accepted). A single point may be given as shape [3].
- SH are 27 float32 per probe, channel-major [r0..r8, g0..g8, b0..b8] (Unity's SphericalHarmonicsL2
  layout), coefficient order L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22; a probe holds incoming
  radiance, not pre-convolved (see tetprobe.sh for the full contract and evaluation).
- Hints are int32 cell indices, one per moving object (-1 = none): pass last frame's back in.
- A Store is immutable: any number of threads may query one store at once.

Errors: the library's failures raise tetprobe.Error carrying .status (a Status) and .message; an
argument of the wrong type (an array of strings, a string for a number, a number for a Scene) raises
TypeError and a wrong shape or out-of-range value ValueError, both naming the parameter; a closed
Store or Scene raises Error(INVALID_ARGUMENT). Wherever a `scene` is taken, the path of a scene file
may be given instead (it is loaded for the call).

The library is found through $TETPROBE_LIBRARY (the library file, or a folder holding it), then next
to this package, then the source tree's build/ (when the package is used from the repository), then
the system's library path; a library whose major.minor version differs from this package's is refused
at import. The command line is the C tool `tetprobe`; `python3 -m tetprobe ARGS` runs it (see
tetprobe.tool: $TETPROBE_TOOL, beside the library, the source tree's build/, then the PATH).

    import numpy as np, tetprobe
    positions = np.random.rand(100, 3).astype(np.float32) * 10
    store = tetprobe.Store.build(positions, sh=np.ones((100, 27), np.float32))
    sh, hints = store.interpolate(np.array([[5, 5, 5]], np.float32))
    irradiance = tetprobe.sh.eval_irradiance(sh[0], (0, 1, 0))
"""

from . import sh, tool
from ._native import PACKAGE_VERSION
from .errors import Error, Status
from .library import library_path, library_version, status_name
from .placement import Placement, find_inside_probes, fix_inside_probes, place_probes
from .scene import Scene, bake, bake_occlusion, bake_plan
from .store import Store
from .volume import shadow_caster_volume, volume_test_aabb, volume_test_sphere

__version__ = "%d.%d.%d" % PACKAGE_VERSION

__all__ = ["Error", "Status", "Store", "Scene", "bake", "bake_occlusion", "bake_plan", "place_probes", "Placement",
           "find_inside_probes", "fix_inside_probes", "shadow_caster_volume", "volume_test_aabb",
           "volume_test_sphere", "sh", "tool", "library_path", "library_version", "status_name", "__version__"]

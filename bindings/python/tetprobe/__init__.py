"""tetprobe: light probes interpolated over a tetrahedral tessellation (a thin ctypes binding).

The library is found through $TETPROBE_LIBRARY, then next to this package, then the build tree
(build/libtetprobe.so in the repository), then the system; a library whose major.minor version
differs from this package's is refused. Arrays are numpy, float32 unless said.
"""

from . import sh
from ._native import PACKAGE_VERSION, library_path
from .errors import Error, Status
from .placement import Placement, find_inside_probes, fix_inside_probes, place_probes
from .scene import Scene, bake, bake_plan
from .store import Store
from .volume import shadow_caster_volume, volume_test_aabb, volume_test_sphere

__version__ = "%d.%d.%d" % PACKAGE_VERSION


def library_version():
    """The loaded library's version as a (major, minor, patch) tuple."""
    from ._native import lib
    version = lib.tp_version()
    return (version >> 16) & 0xFFFF, (version >> 8) & 0xFF, version & 0xFF


__all__ = ["Error", "Status", "Store", "Scene", "bake", "bake_plan", "place_probes", "Placement", "find_inside_probes",
           "fix_inside_probes", "shadow_caster_volume", "volume_test_aabb",
           "volume_test_sphere", "sh", "library_path", "library_version", "__version__"]

"""Makes the in-tree package importable when PYTHONPATH does not already point at it."""
import os
import sys

_BINDINGS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bindings", "python")
if os.path.normpath(_BINDINGS) not in [os.path.normpath(p) for p in sys.path]:
    sys.path.insert(0, os.path.normpath(_BINDINGS))

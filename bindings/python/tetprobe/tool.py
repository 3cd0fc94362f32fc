"""The `tetprobe` command line is the C tool (samples/cli); `python3 -m tetprobe ARGS` runs it.

There is one implementation of the command line: this module only finds the C tool and runs it with
the same arguments, standard input, output and error, and exit status. The tool is looked for the way
the library is (see find_tool): $TETPROBE_TOOL, then beside the loaded library (an installed prefix's
bin/, or a build tree's samples/), then the source tree's build/, then the PATH.
"""

import os
import shutil
import subprocess
import sys

from . import _native

__all__ = ["find_tool", "tool_candidates", "main"]

_TOOL_NAME = "tetprobe.exe" if sys.platform == "win32" else "tetprobe"

#: Exit status when the tool cannot be found or started (a shell's "command not found").
NOT_FOUND = 127


def tool_candidates():
    """The paths find_tool tries, in order (without $TETPROBE_TOOL and the PATH).

    Beside the loaded library: the library's own folder, the bin/ of the prefix it is installed under
    (lib/ or lib/<multiarch>/ below it), and a build tree's samples/ (where the build writes the tool);
    then, when the package is used from the repository, the source tree's build/samples/."""
    paths = []
    library = _native.library_path
    if os.path.dirname(library):
        folder = os.path.dirname(os.path.abspath(library))
        paths.append(os.path.join(folder, _TOOL_NAME))
        paths.append(os.path.join(folder, "samples", _TOOL_NAME))
        paths.append(os.path.normpath(os.path.join(folder, "..", "bin", _TOOL_NAME)))
        paths.append(os.path.normpath(os.path.join(folder, "..", "..", "bin", _TOOL_NAME)))
    repo_root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
    if os.path.exists(os.path.join(repo_root, "capi", "tetprobe.h")):
        paths.append(os.path.join(repo_root, "build", "samples", _TOOL_NAME))
    unique = []
    for path in paths:
        if path not in unique:
            unique.append(path)
    return unique


def _runnable(path):
    return os.path.isfile(path) and os.access(path, os.X_OK)


def find_tool():
    """The path of the C tool `tetprobe`, or FileNotFoundError saying where it was looked for.

    $TETPROBE_TOOL, when set, is the only place looked at (a path to the program, or a folder holding
    it); otherwise tool_candidates() in order, then the PATH."""
    explicit = os.environ.get("TETPROBE_TOOL")
    if explicit:
        path = os.path.join(explicit, _TOOL_NAME) if os.path.isdir(explicit) else explicit
        if _runnable(path):
            return path
        raise FileNotFoundError("TETPROBE_TOOL=%s is not an executable tetprobe tool" % explicit)
    candidates = tool_candidates()
    for path in candidates:
        if _runnable(path):
            return path
    on_path = shutil.which(_TOOL_NAME)
    if on_path:
        return on_path
    raise FileNotFoundError(
        "the tetprobe command-line tool was not found (looked in: %s, and the PATH); build it "
        "(cmake --build build --target tetprobe_cli), install it (cmake --install build), or set TETPROBE_TOOL "
        "to its path" % ", ".join(candidates or ["nowhere beside the library"]))


def main(argv=None):
    """Runs the C tool with argv (default sys.argv[1:]), passing standard input, output and error through;
    returns its exit status (on POSIX the tool replaces this process, so it does not return)."""
    if argv is not None and (not isinstance(argv, (list, tuple)) or not all(isinstance(a, str) for a in argv)):
        raise TypeError("argv must be a list of str (got %r)" % (argv,))
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        tool = find_tool()
    except FileNotFoundError as error:
        sys.stderr.write("tetprobe: %s\n" % error)
        return NOT_FOUND
    if argv is None and os.name == "posix":
        sys.stdout.flush()
        sys.stderr.flush()
        try:
            os.execv(tool, [tool] + args)
        except OSError as error:
            sys.stderr.write("tetprobe: cannot run %s: %s\n" % (tool, error))
            return NOT_FOUND
    try:
        return subprocess.call([tool] + args)
    except OSError as error:
        sys.stderr.write("tetprobe: cannot run %s: %s\n" % (tool, error))
        return NOT_FOUND

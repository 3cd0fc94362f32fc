"""The package's own PEP 517 build backend: the wheel is a zip file written here, so `pip install` needs
nothing beyond pip itself (no setuptools, no wheel package: a plain venv has neither bdist_wheel nor a
network to fetch it).

It packs tetprobe/*.py and any native library copied beside them (libtetprobe.so*, *.dylib, *.dll; the
wheel is then tagged for this platform), and writes the .dist-info metadata from pyproject.toml's
[project] table and the version constant in tetprobe/_native.py.
"""

import ast
import base64
import hashlib
import io
import os
import re
import sysconfig
import tarfile
import zipfile

_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_PACKAGE = "tetprobe"
_NATIVE = re.compile(r"\.(so(\.\d+)*|dylib|dll)$")
# Zip entries carry a fixed date so the same sources give the same wheel bytes.
_DATE = (1980, 1, 1, 0, 0, 0)


def _project():
    """pyproject.toml's [project] keys this backend uses: name, description, requires-python, dependencies."""
    with open(os.path.join(_ROOT, "pyproject.toml"), "rb") as f:
        text = f.read()
    try:
        import tomllib
    except ImportError:  # Python < 3.11: the table holds only strings and lists of strings
        table, section = {}, None
        for line in text.decode("utf-8").splitlines():
            line = line.split("#", 1)[0].strip()
            if line.startswith("["):
                section = line.strip("[]").strip()
            elif section == "project" and "=" in line:
                key, value = (part.strip() for part in line.split("=", 1))
                table[key] = re.findall(r'"([^"]*)"', value) if value.startswith("[") else value.strip('"')
        return table
    return tomllib.loads(text.decode("utf-8"))["project"]


def _version():
    """tetprobe._native.PACKAGE_VERSION, read without importing the package (importing loads the library)."""
    with open(os.path.join(_ROOT, _PACKAGE, "_native.py"), encoding="utf-8") as f:
        for node in ast.parse(f.read()).body:
            if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", None) == "PACKAGE_VERSION":
                return ".".join(str(part) for part in ast.literal_eval(node.value))
    raise RuntimeError("tetprobe/_native.py has no PACKAGE_VERSION")


def _package_files():
    """(path inside the wheel, path on disk) of the package's modules and bundled native libraries."""
    folder = os.path.join(_ROOT, _PACKAGE)
    names = sorted(n for n in os.listdir(folder) if n.endswith(".py") or _NATIVE.search(n))
    return [("%s/%s" % (_PACKAGE, n), os.path.join(folder, n)) for n in names if os.path.isfile(os.path.join(folder, n))]


def _has_native(files):
    return any(_NATIVE.search(name) for name, _ in files)


def _tag(files):
    if not _has_native(files):
        return "py3-none-any"
    return "py3-none-" + re.sub(r"[^A-Za-z0-9]", "_", sysconfig.get_platform())


def _metadata():
    project = _project()
    lines = ["Metadata-Version: 2.1", "Name: " + project["name"], "Version: " + _version()]
    if project.get("description"):
        lines.append("Summary: " + project["description"])
    if project.get("requires-python"):
        lines.append("Requires-Python: " + project["requires-python"])
    lines += ["Requires-Dist: " + d for d in project.get("dependencies", [])]
    return "\n".join(lines) + "\n"


def _dist_info():
    return "%s-%s.dist-info" % (_project()["name"], _version())


def _wheel_file(files):
    return ("Wheel-Version: 1.0\nGenerator: tetprobe_backend\nRoot-Is-Purelib: %s\nTag: %s\n" %
            ("false" if _has_native(files) else "true", _tag(files)))


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode("ascii")
    return "%s,sha256=%s,%d" % (name, digest, len(data))


def _write_wheel(directory, entries, files):
    """Writes the wheel of entries [(name, bytes)] plus the .dist-info files; returns its file name."""
    info = _dist_info()
    entries = list(entries) + [(info + "/METADATA", _metadata().encode()), (info + "/WHEEL", _wheel_file(files).encode()),
                               (info + "/top_level.txt", (_PACKAGE + "\n").encode())]
    record = "\n".join(_record_line(name, data) for name, data in entries) + "\n%s/RECORD,,\n" % info
    entries.append((info + "/RECORD", record.encode()))
    wheel_name = "%s-%s-%s.whl" % (_project()["name"], _version(), _tag(files))
    partial = os.path.join(directory, wheel_name + ".part")
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in entries:
            entry = zipfile.ZipInfo(name, _DATE)
            entry.external_attr = (0o755 if _NATIVE.search(name) else 0o644) << 16
            entry.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(entry, data)
    os.replace(partial, os.path.join(directory, wheel_name))
    return wheel_name


# ---- PEP 517 hooks


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def get_requires_for_build_editable(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    info = os.path.join(metadata_directory, _dist_info())
    os.makedirs(info, exist_ok=True)
    with open(os.path.join(info, "METADATA"), "w", encoding="utf-8") as f:
        f.write(_metadata())
    with open(os.path.join(info, "WHEEL"), "w", encoding="utf-8") as f:
        f.write(_wheel_file(_package_files()))
    return _dist_info()


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    files = _package_files()
    entries = []
    for name, source in files:
        with open(source, "rb") as f:
            entries.append((name, f.read()))
    return _write_wheel(wheel_directory, entries, files)


def build_editable(wheel_directory, config_settings=None, metadata_directory=None):
    """PEP 660: a wheel holding a .pth file that puts this source folder on sys.path."""
    return _write_wheel(wheel_directory, [("_tetprobe_editable.pth", (_ROOT + "\n").encode())], [])


def build_sdist(sdist_directory, config_settings=None):
    base = "%s-%s" % (_project()["name"], _version())
    members = [("pyproject.toml", os.path.join(_ROOT, "pyproject.toml")),
               ("backend/tetprobe_backend.py", os.path.abspath(__file__))]
    members += [(name, source) for name, source in _package_files() if not _NATIVE.search(name)]
    name = base + ".tar.gz"
    partial = os.path.join(sdist_directory, name + ".part")
    with tarfile.open(partial, "w:gz", format=tarfile.PAX_FORMAT) as archive:
        def add(member_name, data):
            entry = tarfile.TarInfo(base + "/" + member_name)
            entry.size, entry.mode, entry.mtime = len(data), 0o644, 315532800
            archive.addfile(entry, io.BytesIO(data))
        add("PKG-INFO", _metadata().encode())
        for member_name, source in members:
            with open(source, "rb") as f:
                add(member_name, f.read())
    os.replace(partial, os.path.join(sdist_directory, name))
    return name

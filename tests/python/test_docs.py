"""help() of every public name: a docstring that names every parameter, gives every array parameter its shape,
and states units and the SH layout where positions or SH pass."""
import ast
import inspect
import os
import re

import tetprobe

PACKAGE_DIR = os.path.dirname(tetprobe.__file__)


def array_parameter_names():
    """Every name the package validates as an array: the name argument of rows(), vector() and as_array()."""
    names = set()
    for file_name in os.listdir(PACKAGE_DIR):
        if not file_name.endswith(".py"):
            continue
        with open(os.path.join(PACKAGE_DIR, file_name)) as f:
            tree = ast.parse(f.read())
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) in ("rows", "vector", "as_array"):
                position = 1 if node.func.id == "as_array" else 2
                if len(node.args) > position and isinstance(node.args[position], ast.Constant):
                    names.add(node.args[position].value)
    return names


METHOD_KINDS = (property, classmethod, staticmethod)


def public_callables():
    """(qualified name, object) of every public function, class, method and property reachable from __all__."""
    found = []
    for name in tetprobe.__all__:
        value = getattr(tetprobe, name)
        if inspect.ismodule(value):
            found += [("%s.%s" % (name, n), f) for n, f in vars(value).items()
                      if not n.startswith("_") and inspect.isfunction(f) and f.__module__ == value.__name__]
        elif inspect.isclass(value):
            found.append((name, value))
            for klass in value.__mro__:
                if klass.__module__.startswith("tetprobe"):
                    found += [("%s.%s" % (name, n), m) for n, m in vars(klass).items()
                              if not n.startswith("_") and (callable(m) or isinstance(m, METHOD_KINDS))]
        elif callable(value):
            found.append((name, value))
    return found


def function_of(member):
    if isinstance(member, (classmethod, staticmethod)):
        return member.__func__
    if isinstance(member, property):
        return member.fget
    return member


def test_the_package_help_states_units_shapes_and_layouts():
    doc = tetprobe.__doc__
    for phrase in ("world units", "float32", "[N, 3]", "27 float32", "channel-major", "L00, L1-1, L10, L11",
                   "int32", "-1 = none", "threads", "ValueError", "TypeError", "tetprobe.Error", "TETPROBE_LIBRARY"):
        assert phrase in doc, phrase
    assert "pi, 2pi/3, pi/4" in tetprobe.sh.__doc__ and "channel-major" in tetprobe.sh.__doc__


def test_every_public_name_has_a_docstring_that_names_its_parameters_and_array_shapes():
    arrays = array_parameter_names()
    assert {"positions", "sh", "points", "hints", "vertices", "indices", "planes"} <= arrays
    checked = 0
    for name, member in public_callables():
        function = function_of(member)
        doc = inspect.getdoc(member) or inspect.getdoc(function)
        assert doc and len(doc) >= 30, "%s has no real docstring" % name
        if inspect.isclass(function):
            continue
        module_doc = inspect.getmodule(function).__doc__ or ""
        for parameter in inspect.signature(function).parameters:
            if parameter in ("self", "cls"):
                continue
            assert re.search(r"\b%s\b" % parameter, doc), "%s: parameter %r is not described" % (name, parameter)
            if parameter in arrays:
                # An array parameter is given with its shape (name[N, 3], "name is [27]", "name ([M, 27] ...")
                # or its components (name=(x, y, z)).
                assert re.search(r"\b%s(\s*(is\s+|\(|:\s*)?\[[^\]]*\]|=\()" % parameter, doc), \
                    "%s: array parameter %r has no shape in the docstring" % (name, parameter)
            if parameter in ("positions", "points", "point", "vertices", "position", "center"):
                assert "world units" in doc, "%s: %r without units" % (name, parameter)
            if parameter == "sh":
                assert "channel-major" in doc or "channel-major" in module_doc, "%s: sh without its layout" % name
        checked += 1
    assert checked >= 28

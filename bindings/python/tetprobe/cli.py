"""The `tetprobe` command in Python: the same subcommands, arguments and output as samples/cli.

Run it as `python3 -m tetprobe ...` or, once the package is pip-installed, as the console script
`tetprobe`. Output is the C tool's byte for byte (tests/python/test_cli_python.py runs both on the same
inputs and files), except timings and the wording of an invalid-JSON message: JSON numbers are spelled
by the same Grisu2 as nlohmann's dump (not always the shortest digits). The C tool's `demo` (pictures)
is not part of it.
"""

import contextlib
import ctypes
import json
import math
import os
import re
import struct
import sys
import time
from fractions import Fraction

import numpy as np

from . import sh as sh_functions
from .errors import Error
from . import _native
from .library import library_version, status_name
from .placement import _placement_bound, _placement_options, place_probes
from .scene import Scene, bake, bake_plan
from .store import Store

USAGE = (
    "usage:\n"
    "  tetprobe build INPUT.(csv|json) -o STORE [--compact]\n"
    "                                                csv: x,y,z[,27 sh] per line; json: {\"probes\": [[x,y,z],...],\n"
    "                                                \"sh\": [[27 floats],...]}; --compact: the smallest blob\n"
    "  tetprobe info STORE [--json]\n"
    "  tetprobe query STORE x y z [--weights] [--json]\n"
    "  tetprobe bake SCENE.json -o STORE [--rays N] [--bounces N] [--seed N] [--threads N]\n"
    "  tetprobe plan SCENE.json [--rays N] [--bounces N] [--seed N] [--threads N] [--json]\n"
    "  tetprobe place SCENE.json -o PROBES.csv [--mode whole|walkable] [--spacing S] [--margin M]\n"
    "                 [--target N] [--error E] [--rays N] [--seed N] [--threads N] [--curve CURVE.json]\n"
    "                 [--min-height H] [--max-height H]   probe positions proposed for a scene\n"
    "  tetprobe version\n"
)


class UsageError(Exception):
    """A wrong command line: reported with the usage text and exit status 2."""


class Failure(Exception):
    """A failure reported as "tetprobe: error: <message>" with exit status 1."""


def checked(call, function, *args, **kwargs):
    """function(*args, **kwargs), with a library Error turned into the C tool's "<call> failed: ..." Failure."""
    try:
        return function(*args, **kwargs)
    except Error as error:
        raise Failure("%s failed: %s: %s" % (call, status_name(error.status), error.message)) from None


# ---- the command line, parsed as samples/cli/support.cpp does

class Arguments:
    """A command's arguments: positionals, options with a value ("-o FILE") and flags ("--json")."""

    def __init__(self, args, value_options, flag_options):
        self.positional, self.values, self.flags = [], {}, set()
        index = 0
        while index < len(args):
            arg = args[index]
            looks_like_option = len(arg) > 1 and arg[0] == "-" and not arg[1].isdigit() and arg[1] != "."
            if not looks_like_option:
                self.positional.append(arg)
            elif arg in value_options:
                if index + 1 >= len(args):
                    raise UsageError(arg + " needs a value")
                index += 1
                self.values[arg] = args[index]
            elif arg in flag_options:
                self.flags.add(arg)
            else:
                raise UsageError("unknown option " + arg)
            index += 1

    def has(self, name):
        return name in self.values or name in self.flags

    def value(self, name, fallback):
        return self.values.get(name, fallback)


_C_SPACE = " \t\n\v\f\r"
# What strtod/strtof accept (after leading white space): decimal, hexadecimal, inf/infinity, nan[(...)].
_C_FLOAT = re.compile(r"(?P<sign>[+-]?)(?:(?P<dec>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
                      r"|0[xX](?P<hex>(?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+))(?:[pP](?P<hexp>[+-]?\d+))?"
                      r"|(?P<inf>[iI][nN][fF](?:[iI][nN][iI][tT][yY])?)|(?P<nan>[nN][aA][nN](?:\([0-9A-Za-z_]*\))?))")


def c_number(text):
    """The exact value of text as strtod/strtof read it whole, as (sign, Fraction or "inf"/"nan"), or None."""
    match = _C_FLOAT.fullmatch(text.lstrip(_C_SPACE))
    if not match:
        return None
    sign = -1 if match.group("sign") == "-" else 1
    if match.group("inf"):
        return sign, "inf"
    if match.group("nan"):
        return sign, "nan"
    if match.group("dec") is not None:
        return sign, Fraction(match.group("dec"))
    whole, _, fraction = match.group("hex").partition(".")
    mantissa = int((whole + fraction) or "0", 16)
    return sign, Fraction(mantissa) * Fraction(2) ** (int(match.group("hexp") or 0) - 4 * len(fraction))


def _nearest_float32(value):
    """The float32 nearest to a non-negative Fraction, ties to even, overflowing to inf (as strtof rounds)."""
    if value >= Fraction(2) ** 128 - Fraction(2) ** 103:  # from halfway above the largest float: inf
        return np.float32(np.inf)
    with np.errstate(over="ignore"):
        start = np.float32(float(value))  # correctly rounded to double, then to float: at most one step off
        candidates = {start, np.nextafter(start, np.float32(0)), np.nextafter(start, np.float32(np.inf))}
    candidates = [c for c in candidates if np.isfinite(c)]
    return min(candidates, key=lambda c: (abs(Fraction(float(c)) - value), int(np.array(c).view(np.uint32)) & 1))


def parse_float32(text):
    """strtof(text) when it reads all of text, else None: one correct rounding to float32 (no double rounding)."""
    number = c_number(text)
    if number is None:
        return None
    sign, value = number
    if value == "inf" or value == "nan":
        return np.float32(sign * float(value))
    return np.float32(sign * _nearest_float32(value))


def parse_number(text, what):
    """A finite double as strtod reads it, or UsageError naming `what`."""
    number = c_number(text) if text else None
    value = None
    if number is not None and number[1] not in ("inf", "nan"):
        try:
            value = number[0] * float(number[1])
        except OverflowError:
            value = None
    if value is None or not math.isfinite(value):
        raise UsageError("%s must be a finite number (got \"%s\")" % (what, text))
    return value


def parse_count(text, what):
    """A non-negative integer as strtoul reads it (64-bit), or UsageError naming `what`."""
    match = re.fullmatch(r"([+-]?)(\d+)", text.lstrip(_C_SPACE))
    if not text or text[0] == "-" or not match or int(match.group(2)) >= 1 << 64:
        raise UsageError("%s must be a non-negative integer (got \"%s\")" % (what, text))
    value = int(match.group(2))
    return (-value) % (1 << 64) if match.group(1) == "-" else value


# ---- output as nlohmann::json prints it: Grisu2 (Loitsch, PLDI 2010) digits, then its fixed/exponent layout

def _cached_powers_of_ten():
    """(f, e, k) with f * 2^e the 64-bit significand of 10^k rounded to nearest, for k = -300, -292, ..., 324."""
    table = []
    for k in range(-300, 325, 8):
        numerator, denominator = (10 ** k, 1) if k >= 0 else (1, 10 ** -k)
        e = numerator.bit_length() - denominator.bit_length() - 64
        while True:
            scaled_numerator = numerator << -e if e < 0 else numerator
            scaled_denominator = denominator << e if e > 0 else denominator
            quotient = scaled_numerator // scaled_denominator
            if quotient >= 1 << 64:
                e += 1
            elif quotient < 1 << 63:
                e -= 1
            else:
                break
        f = (2 * scaled_numerator + scaled_denominator) // (2 * scaled_denominator)
        table.append((f >> 1, e + 1, k) if f == 1 << 64 else (f, e, k))
    return table


_CACHED_POWERS = _cached_powers_of_ten()
_ALPHA, _GAMMA = -60, -32


def _multiply(x, y):
    """The upper 64 bits of the 128-bit product of two (significand, exponent) pairs, rounded half up."""
    return (x[0] * y[0] + (1 << 63)) >> 64, x[1] + y[1] + 64


def _normalized(f, e):
    shift = 64 - f.bit_length()
    return f << shift, e - shift


def _grisu2(value):
    """(digits, decimal exponent) with digits * 10^exponent within value's rounding interval: nlohmann's
    Grisu2, which usually but not always finds the shortest such digits."""
    bits = struct.unpack("<Q", struct.pack("<d", value))[0]
    biased, fraction = bits >> 52, bits & ((1 << 52) - 1)
    f, e = (fraction, -1074) if biased == 0 else (fraction + (1 << 52), biased - 1075)
    plus = _normalized(2 * f + 1, e - 1)
    minus_f, minus_e = (4 * f - 1, e - 2) if fraction == 0 and biased > 1 else (2 * f - 1, e - 1)
    minus = (minus_f << (minus_e - plus[1]), plus[1])
    v = _normalized(f, e)
    # The cached power that brings plus's exponent into [alpha, gamma]: k ~ ceil((alpha - e - 1) * log10(2)),
    # with 78913 / 2^18 for log10(2) and C's division, which truncates towards zero.
    scaled = (_ALPHA - plus[1] - 1) * 78913
    k = (abs(scaled) >> 18) * (1 if scaled >= 0 else -1) + (1 if scaled > 0 else 0)
    cached_f, cached_e, cached_k = _CACHED_POWERS[(300 + k + 7) // 8]
    w = _multiply(v, (cached_f, cached_e))
    w_minus = _multiply(minus, (cached_f, cached_e))
    w_plus = _multiply(plus, (cached_f, cached_e))
    high, low = w_plus[0] - 1, w_minus[0] + 1
    return _grisu2_digits(low, w[0], high, w_plus[1], -cached_k)


def _grisu2_digits(low, w, high, e, decimal_exponent):
    delta, dist = high - low, high - w
    one = 1 << -e
    p1, p2 = high >> -e, high & (one - 1)
    digits = []
    power = 10 ** (len(str(p1)) - 1)
    n = len(str(p1))
    while n > 0:
        digits.append(p1 // power)
        p1 %= power
        n -= 1
        rest = (p1 << -e) + p2
        if rest <= delta:
            return _grisu2_round(digits, dist, delta, rest, power << -e), decimal_exponent + n
        power //= 10
    m = 0
    while True:
        p2 *= 10
        digits.append(p2 >> -e)
        p2 &= one - 1
        m += 1
        delta *= 10
        dist *= 10
        if p2 <= delta:
            return _grisu2_round(digits, dist, delta, p2, one), decimal_exponent - m


def _grisu2_round(digits, dist, delta, rest, ten_k):
    while rest < dist and delta - rest >= ten_k and (rest + ten_k < dist or dist - rest > rest + ten_k - dist):
        digits[-1] -= 1
        rest += ten_k
    return "".join(str(d) for d in digits)


def _format_double(value):
    """A double as nlohmann::json's dump writes it: Grisu2 digits, "1.0" for integral values, exponents
    beyond 1e15 and below 1e-4 as "1e+16" / "1e-05", and null for NaN and infinities."""
    if not math.isfinite(value):
        return "null"
    sign = "-" if math.copysign(1.0, value) < 0 else ""
    if value == 0:
        return sign + "0.0"
    digits, exponent = _grisu2(abs(value))
    k, n = len(digits), len(digits) + exponent  # value = 0.digits * 10^n
    if k <= n <= 15:
        text = digits + "0" * (n - k) + ".0"
    elif 0 < n <= 15:
        text = digits[:n] + "." + digits[n:]
    elif -4 < n <= 0:
        text = "0." + "0" * -n + digits
    else:
        e = n - 1
        text = (digits if k == 1 else digits[0] + "." + digits[1:]) + "e" + ("-" if e < 0 else "+") + \
            "%02d" % abs(e)
    return sign + text


def dump_json(value, indent=None, level=0):
    """value (dicts keep their order) as nlohmann::json's dump(indent) writes it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return _format_double(float(value))
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, dict):
        items = [(json.dumps(str(k), ensure_ascii=False) + (": " if indent is not None else ":"), v)
                 for k, v in value.items()]
        opening, closing = "{", "}"
    else:
        items = [("", v) for v in value]
        opening, closing = "[", "]"
    if not items:
        return opening + closing
    if indent is None:
        return opening + ",".join(key + dump_json(v) for key, v in items) + closing
    inner = " " * (indent * (level + 1))
    lines = [inner + key + dump_json(v, indent, level + 1) for key, v in items]
    return opening + "\n" + ",\n".join(lines) + "\n" + " " * (indent * level) + closing


def out(text):
    sys.stdout.write(text)


def write_file_atomically(path, data):
    """data (bytes) at path through a temporary file renamed over it, as samples/cli does: a failed write
    leaves no half-written file, and reports "cannot write PATH: <strerror>"."""
    temporary = "%s.tmp%d" % (path, os.getpid())
    try:
        descriptor = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o666)
    except OSError as error:
        raise Failure("cannot write %s: %s" % (path, os.strerror(error.errno))) from None
    try:
        try:
            view = memoryview(data)
            while view:
                view = view[os.write(descriptor, view):]
            os.fsync(descriptor)
        finally:
            os.close(descriptor)
        os.rename(temporary, path)
    except OSError as error:
        with contextlib.suppress(OSError):
            os.remove(temporary)
        raise Failure("cannot write %s: %s" % (path, os.strerror(error.errno))) from None


# ---- probe files, read as samples/cli/probe_file.cpp does

def _csv_values(line):
    """The numbers of a CSV line as float32, or None if a field is not a number."""
    fields = line.split(",")
    if len(fields) > 1 and fields[-1] == "":  # std::getline drops one empty field after a final comma
        fields.pop()
    values = []
    for field in fields:
        field = field.strip(" \t\r")
        value = parse_float32(field) if field else None
        if value is None:
            return None
        values.append(value)
    return values


def _read_csv(lines, path):
    positions, sh, header_skipped = [], [], False
    for number, line in enumerate(lines, start=1):
        stripped = line.lstrip(" \t")
        if not line.strip(" \t\r") or stripped.startswith("#"):
            continue
        values = _csv_values(line)
        if values is None:
            if not positions and not header_skipped:  # one header line is allowed
                header_skipped = True
                continue
            raise Failure("%s:%d: not a list of numbers" % (path, number))
        if len(values) not in (3, 30):
            raise Failure("%s:%d: expected 3 (x,y,z) or 30 (x,y,z + 27 SH) values, got %d" %
                          (path, number, len(values)))
        if positions and (len(values) == 30) != bool(sh):
            raise Failure("%s:%d: every line must have the same columns" % (path, number))
        positions.append(values[:3])
        if len(values) == 30:
            sh.append(values[3:])
    return positions, sh


def _json_float32(value):
    """A JSON number as nlohmann's get<float>() converts it: integers rounded once, doubles via double."""
    if isinstance(value, int) and -(1 << 63) <= value < (1 << 64):
        return np.float32(-_nearest_float32(Fraction(-value)) if value < 0 else _nearest_float32(Fraction(value)))
    with np.errstate(over="ignore"):
        return np.float32(float(value))


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _reject_constant(name):
    raise ValueError("%s is not JSON" % name)


def _finite_float(text):
    value = float(text)
    if not math.isfinite(value):
        raise ValueError("number overflow parsing '%s'" % text)
    return value


def _read_json(data, path):
    try:
        document = json.loads(data, parse_constant=_reject_constant, parse_float=_finite_float)
    except (ValueError, UnicodeDecodeError) as error:
        raise Failure("%s: invalid JSON: %s" % (path, error)) from None
    if not isinstance(document, dict) or not isinstance(document.get("probes"), list):
        raise Failure("%s: expected an object with a \"probes\" array of [x, y, z]" % path)
    probes = document["probes"]
    positions = []
    for i, p in enumerate(probes):
        if not isinstance(p, list) or len(p) != 3 or not all(_is_number(v) for v in p):
            raise Failure("%s: probes[%d] is not [x, y, z]" % (path, i))
        positions.append([_json_float32(v) for v in p])
    sh = []
    if "sh" in document:
        rows = document["sh"]
        if not isinstance(rows, list) or len(rows) != len(probes):
            raise Failure("%s: \"sh\" must have one entry of 27 numbers per probe" % path)
        for i, row in enumerate(rows):
            if not isinstance(row, list) or len(row) != 27:
                raise Failure("%s: sh[%d] must have 27 numbers" % (path, i))
            if not all(_is_number(v) for v in row):
                raise Failure("%s: sh[%d] holds a non-number" % (path, i))
            sh.append([_json_float32(v) for v in row])
    return positions, sh


def read_probe_file(path):
    """(positions[N, 3] float32, sh[N, 27] float32 or None) from a .csv/.txt or .json probe file."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except IsADirectoryError:
        data = b""  # std::ifstream opens a directory and reads nothing
    except OSError:
        raise Failure("cannot read " + path) from None
    if path.endswith(".json"):
        positions, sh = _read_json(data, path)
    elif path.endswith(".csv") or path.endswith(".txt"):
        text = data.decode("latin-1")
        lines = text.split("\n")
        if lines and lines[-1] == "":
            lines.pop()
        positions, sh = _read_csv(lines, path)
    else:
        raise Failure(path + ": unknown input type (use .csv or .json)")
    positions = np.array(positions, dtype=np.float32).reshape(-1, 3)
    return positions, (np.array(sh, dtype=np.float32).reshape(-1, 27) if sh else None)


# ---- progress on stderr, as samples/cli's ProgressBar draws it

class ProgressBar:
    """A progress(fraction, stage) callable: a bar redrawn in place on a terminal, a line per 25% in a log."""

    def __init__(self, label):
        self.label, self.last_percent = label, -1
        self.interactive = sys.stderr.isatty()

    def __call__(self, fraction, stage):
        fraction = np.float32(0.0 if fraction != fraction else min(max(fraction, 0.0), 1.0))
        percent = int(math.floor(float(fraction * np.float32(100.0)) + 0.5))
        if percent == self.last_percent:
            return False
        if not self.interactive:
            if self.last_percent >= 0 and percent // 25 == self.last_percent // 25:
                return False
            self.last_percent = percent
            sys.stderr.write("%-6s %3d%% %s\n" % (self.label, percent, stage))
            return False
        self.last_percent = percent
        filled = percent * 30 // 100
        bar = "#" * filled + " " * (30 - filled)
        sys.stderr.write("\r%-6s [%s] %3d%% %-24.24s" % (self.label, bar, percent, stage))
        sys.stderr.flush()
        return False

    def finish(self):
        if self.last_percent >= 0 and self.interactive:
            sys.stderr.write("\n")
        self.last_percent = -1


# ---- the commands

def load_store(path):
    return checked("loading the store", Store.load, path)


def command_build(args):
    a = Arguments(args, {"-o"}, {"--compact"})
    if len(a.positional) != 1 or not a.has("-o"):
        raise UsageError("build takes INPUT and -o STORE")
    positions, sh = read_probe_file(a.positional[0])
    if len(positions) == 0:
        raise Failure(a.positional[0] + ": no probes")
    store = checked("building the store", Store.build, positions, sh, compact=a.has("--compact"))
    path = a.value("-o", "")
    checked("saving the store", store.save, path)
    info = store.info()
    out("built %s: %u probes (%u merged), %u cells (%u inner, %u outer), %u bytes, %s layout%s\n" % (
        path, info["probes"], info["merged_probes"], info["cells"], info["inner_cells"], info["outer_cells"],
        info["bytes"], "compact" if info["compact"] else "fast", "" if sh is not None else " (no SH given: zeros)"))
    return 0


def command_info(args):
    a = Arguments(args, set(), {"--json"})
    if len(a.positional) != 1:
        raise UsageError("info takes STORE")
    i = load_store(a.positional[0]).info()
    fields = {key: i[key] for key in ("format_version", "dimension", "probes", "input_probes", "merged_probes", "cells",
                                      "inner_cells", "outer_cells", "index_bits")}
    fields["layout"] = "compact" if i["compact"] else "fast"
    fields["extrapolation"] = i["extrapolation"]
    fields["grid"] = list(i["grid"])
    fields["bytes"] = i["bytes"]
    for key in ("origin", "bounds_min", "bounds_max"):
        fields[key] = list(i[key])
    if a.has("--json"):
        out(dump_json(fields, 2) + "\n")
        return 0
    for key, value in fields.items():
        out("%-15s %s\n" % (key + ":", dump_json(value)))
    return 0


def command_query(args):
    a = Arguments(args, set(), {"--weights", "--json"})
    if len(a.positional) != 4:
        raise UsageError("query takes STORE x y z")
    position = np.array([parse_number(text, "a coordinate") for text in a.positional[1:]], dtype=np.float32)
    store = load_store(a.positional[0])
    sh, _ = checked("tp_store_interpolate", store.interpolate, position)
    location = checked("tp_store_locate", store.locate, position)
    irradiance = checked("tp_sh_eval_irradiance", sh_functions.eval_irradiance, sh, (0.0, 1.0, 0.0))
    x, y, z = (float(v) for v in position)
    j = {"position": [x, y, z], "cell": location["cell"], "cell_kind": location["kind"], "steps": location["steps"],
         "sh": [float(v) for v in sh], "irradiance_up": [float(v) for v in irradiance]}
    weights = [float(np.float32(w)) for w in location["weights"]]
    if a.has("--weights"):
        j["probes"] = list(location["probes"])
        j["weights"] = weights
    if a.has("--json"):
        out(dump_json(j, 2) + "\n")
        return 0
    out("position   %g %g %g\n" % (x, y, z))
    out("cell       %d (%s), %u steps from a cold start\n" % (location["cell"], location["kind"], location["steps"]))
    for c, channel in enumerate("rgb"):
        out("sh.%s      " % channel + "".join(" %10.6f" % float(sh[9 * c + k]) for k in range(9)) + "\n")
    out("irradiance %g %g %g (normal +y)\n" % tuple(float(v) for v in irradiance))
    if a.has("--weights"):
        for k in range(4):
            if weights[k] != 0.0 or k == 0:
                out("probe %-8u weight %.6f\n" % (location["probes"][k], weights[k]))
    return 0


def bake_settings(a, default_rays):
    """rays, bounces, seed, threads from the command line, as the C tool's unsigned types keep them."""
    settings = {"rays": parse_count(a.value("--rays", str(default_rays)), "--rays") & 0xFFFFFFFF,
                "bounces": parse_count(a.value("--bounces", "2"), "--bounces") & 0xFFFFFFFF,
                "seed": parse_count(a.value("--seed", "0"), "--seed"),
                "threads": parse_count(a.value("--threads", "0"), "--threads") & 0xFFFFFFFF}
    if settings["rays"] == 0:
        raise UsageError("--rays must be at least 1")
    return settings


def load_scene(path):
    scene = checked("loading the scene", Scene.load, path)
    positions = checked("reading the scene's probes", lambda: scene.probes)
    if len(positions) == 0:
        raise Failure("the scene lists no probe positions")
    return scene, positions


def command_bake(args):
    a = Arguments(args, {"-o", "--rays", "--bounces", "--seed", "--threads"}, set())
    if len(a.positional) != 1 or not a.has("-o"):
        raise UsageError("bake takes SCENE.json and -o STORE")
    settings = bake_settings(a, 256)
    scene, positions = load_scene(a.positional[0])
    plan = checked("planning the bake", bake_plan, scene, positions, **settings)
    out("effects plan: %s\n" % plan["text"])
    sys.stdout.flush()
    bar = ProgressBar("bake")
    start = time.perf_counter()
    try:
        sh = checked("baking", bake, scene, positions, progress=bar, **settings)
    finally:
        seconds = time.perf_counter() - start
        bar.finish()
    probes = len(positions)
    out("baked %u probes x %u rays, %u bounces (plan: %u) in %.2f s (%.0f probe-rays/s)\n" % (
        probes, settings["rays"], settings["bounces"], plan["bounces"], seconds,
        probes * settings["rays"] / (seconds if seconds > 0 else 1e-9)))
    store = checked("building the store", Store.build, positions, sh)
    path = a.value("-o", "")
    checked("saving the store", store.save, path)
    info = store.info()
    out("wrote %s: %u probes (%u merged), %u cells, %u-bit indices, %u bytes\n" % (
        path, info["probes"], info["merged_probes"], info["cells"], info["index_bits"], info["bytes"]))
    return 0


def command_plan(args):
    a = Arguments(args, {"--rays", "--bounces", "--seed", "--threads"}, {"--json"})
    if len(a.positional) != 1:
        raise UsageError("plan takes SCENE.json")
    settings = bake_settings(a, 256)
    scene, positions = load_scene(a.positional[0])
    plan = checked("planning the bake", bake_plan, scene, positions, **settings)
    if not a.has("--json"):
        out("effects plan: %s\n" % plan["text"])
        return 0
    j = {"probes": len(positions)}
    for key in ("lights", "direct_lights", "realtime_lights", "out_of_range_lights", "sky", "emissive_meshes",
                "bounces", "shadows", "meshes", "shadow_casters", "shadow_caster_candidates", "inside_probes", "text"):
        j[key] = plan[key]
    out(dump_json(j, 2) + "\n")
    return 0


def _default_text(value):
    """A float default as std::to_string prints it ("%f"), which the C tool parses back."""
    return "%f" % float(value)


def command_place(args):
    a = Arguments(args, {"-o", "--mode", "--spacing", "--margin", "--target", "--error", "--rays", "--bounces",
                         "--seed", "--threads", "--curve", "--min-height", "--max-height"}, set())
    if len(a.positional) != 1 or not a.has("-o"):
        raise UsageError("place takes SCENE.json and -o PROBES.csv")
    defaults = _native.PlacementOptions()
    checked("tp_placement_options_init", _native.check, _native.lib.tp_placement_options_init(ctypes.byref(defaults)))
    mode = a.value("--mode", "whole")
    if mode not in ("whole", "walkable"):
        raise UsageError("--mode is whole or walkable")
    # In the C tool's order, each through a double into the float or unsigned field it fills.
    spacing = parse_number(a.value("--spacing", _default_text(defaults.spacing)), "--spacing")
    margin = parse_number(a.value("--margin", _default_text(defaults.margin)), "--margin")
    min_height = parse_number(a.value("--min-height", _default_text(defaults.walk_min_height)), "--min-height")
    max_height = parse_number(a.value("--max-height", _default_text(defaults.walk_max_height)), "--max-height")
    target = parse_count(a.value("--target", "0"), "--target") & 0xFFFFFFFF
    # A target alone places that many; an error bound alone (or with the target) also stops placement.
    error_bound = parse_number(a.value("--error", "0" if a.has("--target") else _default_text(defaults.error_bound)),
                               "--error")
    rays = parse_count(a.value("--rays", str(defaults.rays)), "--rays") & 0xFFFFFFFF
    bounces = parse_count(a.value("--bounces", str(defaults.bounces)), "--bounces") & 0xFFFFFFFF
    seed = parse_count(a.value("--seed", "0"), "--seed")
    threads = parse_count(a.value("--threads", "0"), "--threads") & 0xFFFFFFFF
    settings = {"mode": mode, "spacing": spacing, "margin": margin, "walk_height": (min_height, max_height),
                "target": target, "error_bound": error_bound, "rays": rays, "bounces": bounces, "seed": seed,
                "threads": threads}

    scene_path = a.positional[0]
    scene = checked("loading the scene", Scene.load, scene_path)
    checked("sizing the placement", lambda: _placement_bound(scene, _placement_options(**settings)))
    bar = ProgressBar("place")
    start = time.perf_counter()
    try:
        placement = checked("placing probes", place_probes, scene, progress=bar, **settings)
    finally:
        seconds = time.perf_counter() - start
        bar.finish()
    positions, curve = placement.positions, placement.error_curve

    path = a.value("-o", "")
    csv = "".join("%.9g,%.9g,%.9g\n" % tuple(float(v) for v in p) for p in positions)
    write_file_atomically(path, csv.encode())
    points = len(curve)
    error = float(curve[-1, 1]) if points else 0.0
    out("placed %u probes in %.2f s, estimated error %.4f (luminance irradiance at validation points, "
        "relative to their mean); wrote %s\n" % (len(positions), seconds, error, path))
    if a.has("--curve"):
        # nlohmann::json (not ordered): keys sorted; floats printed as the double they widen to.
        as_float = [float(np.float32(v)) for v in (spacing, margin)]
        document = {"error_curve": [{"error": float(e), "probes": int(n)} for n, e in curve],
                    "margin": as_float[1], "mode": mode, "scene": scene_path, "seconds": seconds,
                    "spacing": as_float[0]}
        curve_path = a.value("--curve", "")
        write_file_atomically(curve_path, (dump_json(document, 1) + "\n").encode())
        out("wrote %s (%u points of error against probe count)\n" % (curve_path, points))
    return 0


def command_version(args):
    out("tetprobe %u.%u.%u\n" % library_version())
    return 0


#: Subcommand -> function(args) -> exit status, as in samples/cli/main.cpp.
COMMANDS = {
    "build": command_build,
    "info": command_info,
    "query": command_query,
    "bake": command_bake,
    "plan": command_plan,
    "place": command_place,
    "version": command_version,
}


def main(argv=None):
    """Runs the command line argv (default sys.argv[1:]) and returns the exit status: 0 done, 1 failed
    (a message on stderr), 2 a wrong command line (the usage on stderr)."""
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] in ("-h", "--help", "help"):
        (sys.stderr if not args else sys.stdout).write(USAGE)
        return 2 if not args else 0
    try:
        command = COMMANDS.get(args[0])
        if command is None:
            raise UsageError("unknown command \"%s\"" % args[0])
        return command(args[1:])
    except UsageError as error:
        sys.stderr.write("tetprobe: %s\n%s" % (error, USAGE))
        return 2
    except (Failure, Error) as error:
        sys.stderr.write("tetprobe: error: %s\n" % error)
        return 1

#!/usr/bin/env bash
# The real levels of the benchmark (tetprobe_bench levels): Debian's openarena-081-maps package (50 Quake 3
# arena levels in one pk3, a zip), installed here if it is missing and read in place; the .bsp files are
# extracted into DIR (the build tree, never the repository). Usage: setup_levels.sh DIR
# Exits non-zero with a reason when the package cannot be installed; `make bench` then reports the
# real-level part as not run.
set -euo pipefail
out="$1"
pk3=/usr/share/games/openarena/baseoa/pak1-maps.pk3
if [ ! -f "$pk3" ]; then
  if [ "$(id -u)" -ne 0 ]; then echo "setup_levels.sh: $pk3 is missing and installing openarena-081-maps needs root" >&2; exit 1; fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y --no-install-recommends openarena-081-maps >/dev/null 2>&1 \
    || { apt-get update >/dev/null && apt-get install -y --no-install-recommends openarena-081-maps >/dev/null; }
fi
mkdir -p "$out"
/usr/bin/python3 - "$pk3" "$out" <<'PY'
import os, sys, zipfile
pk3, out = sys.argv[1], sys.argv[2]
count = 0
with zipfile.ZipFile(pk3) as z:
    for info in z.infolist():
        name = info.filename
        if not (name.startswith("maps/") and name.endswith(".bsp")) or "/" in name[5:]:
            continue
        target = os.path.join(out, os.path.basename(name))
        if os.path.exists(target) and os.path.getsize(target) == info.file_size:
            count += 1
            continue
        with z.open(info) as src, open(target + ".tmp", "wb") as dst:
            dst.write(src.read())
        os.replace(target + ".tmp", target)
        count += 1
print("setup_levels.sh: %d levels in %s" % (count, out))
PY

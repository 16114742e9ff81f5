"""Finding and running the tessera command line: the add-on's preference, $TESSERA, then PATH."""

import os
import shutil
import subprocess


class TesseraError(Exception):
    """A failure to show the user as one report."""


def find_tessera(preference):
    """The tessera executable, or TesseraError saying where it looked and how to set it."""
    looked = []
    for where, value, unset in (("the add-on preference", preference, "empty"),
                                ("$TESSERA", os.environ.get("TESSERA", ""), "unset")):
        if not value:
            looked.append("%s (%s)" % (where, unset))
            continue
        path = os.path.abspath(os.path.expanduser(value))
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        looked.append("%s (%s: not an executable file)" % (where, path))
    found = shutil.which("tessera")
    if found:
        return found
    looked.append("PATH (%s)" % os.environ.get("PATH", ""))
    raise TesseraError(
        "tessera not found: looked in " + ", ".join(looked) +
        "; set Edit > Preferences > Add-ons > Tessera > Tessera executable, or TESSERA=/path/to/tessera")


WARNING = "tessera: warning: "


def run(tessera, args):
    """Runs tessera with `args`; returns its warnings (what a scheme cannot honour, ...) and stdout. A
    non-zero exit raises TesseraError with the command's own one-line message."""
    try:
        r = subprocess.run([tessera] + args, capture_output=True, text=True)
    except OSError as e:
        raise TesseraError("cannot run %s: %s" % (tessera, e))
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    if r.returncode != 0:
        raise TesseraError(lines[-1] if lines else "tessera %s exited with %d" % (args[0], r.returncode))
    return [l[len(WARNING):] for l in lines if l.startswith(WARNING)], r.stdout

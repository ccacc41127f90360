"""Imported first by every plot script: makes `import matplotlib` work with any python3.

The plots use Debian's python3-matplotlib (scripts/packages.txt, installed by
scripts/setup.sh). A python3 earlier on PATH (pyenv, a venv) does not see it; then the
script re-runs itself with the system interpreter, /usr/bin/python3, or says what to install.
"""
import os
import sys

try:
    import matplotlib  # noqa: F401
except ImportError:
    system = "/usr/bin/python3"
    if os.path.realpath(sys.executable) != os.path.realpath(system) and os.access(system, os.X_OK):
        os.execv(system, [system] + sys.argv)
    sys.exit(f"{os.path.basename(sys.argv[0])}: matplotlib is missing: run scripts/setup.sh "
             "(it installs python3-matplotlib) or `apt-get install python3-matplotlib`")
matplotlib.use("Agg")

#!/usr/bin/python3
"""rollsim_post: figures and CSV from rollsim netCDF output. See postproc/README.md.

Run with Debian's /usr/bin/python3 (python3-netcdf4, python3-matplotlib, python3-numpy).
The code lives in the package rollsim_post/ beside this script.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from rollsim_post.cli import main  # noqa: E402  (the package directory, not this script)

if __name__ == "__main__":
    sys.exit(main())

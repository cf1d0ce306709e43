"""python -m rollsim_post COMMAND ...: the same as postproc/rollsim_post.py (an installed package)."""
import sys

from .cli import main

sys.exit(main())

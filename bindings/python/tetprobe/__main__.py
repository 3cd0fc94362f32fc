"""`python3 -m tetprobe ARGS`: runs the C command-line tool with ARGS (see tetprobe.tool)."""
import sys

from .tool import main

sys.exit(main())

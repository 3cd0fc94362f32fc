"""`python3 -m tetprobe ...`: the tetprobe command (see tetprobe.cli)."""
import sys

from .cli import main

sys.exit(main())

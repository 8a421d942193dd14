"""``python -m surfwave``: the command line (:mod:`surfwave.cli`)."""
import sys

from surfwave.cli import main

sys.exit(main())

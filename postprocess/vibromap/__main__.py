"""python -m vibromap SCRIPT [ARGS...]: the scripts of vibromap-post (vibromap._post)."""

import sys

from ._post import main

sys.exit(main())

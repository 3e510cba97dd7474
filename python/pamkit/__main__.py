import sys

from pamkit.cli import main

sys.exit(main())

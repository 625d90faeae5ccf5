"""`python -m refracta` runs the command-line interface."""

from refracta.cli import main

raise SystemExit(main())

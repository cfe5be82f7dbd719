"""``python -m camgen`` runs the command line."""
from camgen.cli import main

main()

"""``python -m linkgen`` runs the command line."""
from linkgen.cli import main

main()

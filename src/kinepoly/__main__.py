"""``python -m kinepoly``."""

from kinepoly.cli import main_exit

main_exit()

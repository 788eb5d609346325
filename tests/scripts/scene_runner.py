"""The name under which doc/scripts (iol_refinement.py, iol_nozzle_sweep.py)
import the checkers' shared helpers: see coshell_checks.py."""
from coshell_checks import read_rows, surgical_real_time_factor  # noqa: F401

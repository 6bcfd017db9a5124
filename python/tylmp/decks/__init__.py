"""Support of the shipped decks (inputs/*.in), called from LAMMPS with the `python` command.

Every deck starts with

    python tylmp_deck input 1 SELF format p here "from tylmp.decks import begin as tylmp_deck"
    python tylmp_deck invoke

which checks the deck's `-var` choices against CHOICES and its numeric options against
NUMBERS and sets `tylmp_common`, the directory of the shared fragments (inputs/common/*.in),
then includes `${tylmp_common}/specimen.in`. That
fragment calls `specimen_cache`, which decides whether the cached specimen can be reused, and
inputs/common/prepare.in ends with `specimen_commit`, which moves the freshly written restart
file onto its final name. docs/specimen.md ("Decks and the specimen cache") describes the cache.

Errors are LAMMPS-style lines "ERROR: ..." on the screen and in the log, and the run stops with
exit status 1 (LAMMPS 29 Sep 2021 has no library call to raise a LAMMPS error from Python).

Modules: options (the deck's start: -var options, fragments, material), restitution (damping
ratio and restitution), cache (the specimen cache), preparation (its progress and diagnosis),
session (the running LAMMPS: variables, command line, messages); this package holds the names
the decks call.
"""

from .cache import check_cached, prep_key, specimen_cache, specimen_commit
from .options import CHOICES, MATERIAL, NUMBERS, begin, check_number, fragments_dir, material
from .preparation import prep_report, prep_status, prep_track
from .restitution import damping_ratio_for_restitution, restitution_of_damping_ratio

__all__ = ["CHOICES", "NUMBERS", "MATERIAL", "check_number", "begin", "material",
           "restitution_of_damping_ratio", "damping_ratio_for_restitution",
           "specimen_cache", "specimen_commit", "prep_track", "prep_status", "prep_report",
           "check_cached", "fragments_dir", "prep_key"]

"""The names and defaults of the multi-target tracker's options, in a module of their own: the command line builds
its parser from them without importing the tracker, whose import loads every model's kernels (the IMM bank's
dispatch), about 0.4 s of every `lgekf` command.

The tracker (``tracker.py``), the association (``association.py``) and the PMBM filter (``pmbm.py``) read them from
here and re-export them.
"""

from __future__ import annotations

__all__ = ["MARGINAL_ASSOCIATIONS", "ASSOCIATIONS", "INITIATIONS", "DEFAULT_INITIATION", "BIRTH_EXISTENCE",
           "SPEED_STD_FRACTION", "PMBM_DEFAULTS"]

#: the associations that give marginal probabilities p_ij (``association.association_marginals``)
MARGINAL_ASSOCIATIONS = ("jpda", "jpdastar", "pda", "gnn")
#: every association of ``MultiTargetTracker``: the marginal ones and the PMBM filter (``pmbm.py``)
ASSOCIATIONS = MARGINAL_ASSOCIATIONS + ("pmbm",)
INITIATIONS = ("one-point", "two-point")
#: the initiation of each association when none is given (measured: docs/multi_target.md); the PMBM's is its Poisson part
DEFAULT_INITIATION = {"jpda": "one-point", "jpdastar": "one-point", "gnn": "one-point", "pda": "two-point", "pmbm": "one-point"}
BIRTH_EXISTENCE = {"one-point": 0.02, "two-point": 0.1}  # a new track's existence without birth_density
SPEED_STD_FRACTION = 1.0 / 3.0  # one-point: the velocity prior's std per axis is max_speed/3
PMBM_DEFAULTS = {"max_hypotheses": 50, "hypothesis_prune": 1e-3}  # measured: docs/multi_target.md

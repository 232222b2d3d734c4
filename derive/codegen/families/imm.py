"""The IMM family: ``generated/imm.py``, the IMM's loop in numba, with its per-measurement parts emitted from the
measurement definitions (no runtime code names a measurement); one module per mixing space (``derive.space.Space``:
``imm.py`` for the plane, ``imm_3d.py`` for 3-D space), sized by its common coordinates.

The model-independent part (``templates/imm_helpers.py.tmpl``: the workspace, mixing on the group and in the common
coordinates, the mode probabilities, the combined estimate, ``imm_predict``, ``imm_step``, ``imm_loglik_one``,
``imm_run_one``; the maths in ``lgekf.estimators.imm.kernels``) is emitted with the space's facts filled in (the
number of common coordinates, which are angles, where the body velocity is); every model is reached through the
space's ``generated/dispatch.py``. Per measurement (``templates/imm_measurement.py.tmpl``): ``imm_update_<meas>`` (each
mode's log det S and update), ``_modes_<meas>`` (each mode's fused step ``step_ll_<meas>``, with its fallback),
``_run_<meas>`` and ``imm_run_batch_<meas>`` (the loop over a trajectory, compiling only that measurement's
kernels). The generic functions take the measurement as an index ``meas`` into ``MEASUREMENT_NAMES`` (sorted) and
reach those through the chains ``imm_update``, ``_modes`` and ``_run`` (``if meas == i``, inlined), so one compiled
loop serves every measurement, as the model chains of ``generated/dispatch.py`` serve every model.
"""

from __future__ import annotations

import re

from ..printer import HEADER
from ..template import load

__all__ = ["render_imm"]


def _chain(fname: str, params: str, names: list, call: str, ret: bool) -> str:
    """``fname(..., meas, ...)``: the per-measurement kernel ``call`` (with ``{meas}``) of measurement index ``meas``."""
    lines = ['@nb.njit(cache=True, inline="always")', f"def {fname}({params}):",
             f'    """``{call.split("(")[0]}`` of the measurement MEASUREMENT_NAMES[meas] (derive/codegen/families/imm.py)."""']
    body = ("return " if ret else "") + call
    if len(names) == 1:
        lines.append("    " + body.replace("{meas}", names[0]))
    for i, name in enumerate(names if len(names) > 1 else []):
        if i == 0:
            lines.append(f"    if meas == {i}:")
        elif i < len(names) - 1:
            lines.append(f"    elif meas == {i}:")
        else:
            lines.append("    else:")
        lines.append("        " + body.replace("{meas}", name))
    return "\n".join(lines) + "\n"


def render_imm(space, measurements: dict) -> str:
    """``generated/<space.imm_module>.py`` (``imm.py`` for the plane) for the measurements of one mixing space (sorted
    names = measurement indices): the loop sized by the space's common coordinates (``NC``), told which are angles
    (``Space.common_angles``: wrapped when mixed, std capped) and where the body velocity is (``Space.common_velocity``),
    and reaching the space's models through its ``generated/<space.dispatch_module>.py``."""
    names = sorted(measurements)
    nc = len(space.common)
    helpers = (load("imm_helpers.py.tmpl").replace("{dispatch}", space.dispatch_module).replace("{n_common}", str(nc))
               .replace("{is_angle}", repr([1.0 if a in space.common_angles else 0.0 for a in range(nc)]))
               .replace("{velocity}", repr(list(space.common_velocity))))
    per = "".join(load("imm_measurement.py.tmpl").replace("{meas}", name) for name in names)
    chains = [
        _chain("imm_update", "models, S, Pp, mu, r, z, meas, nis_out, ws", names,
               "imm_update_{meas}(models, S, Pp, mu, r, z, nis_out, ws)", True),
        _chain("_modes", "ws, M, m, dt, meas", names, "_modes_{meas}(ws, M, m, dt)", False),
        _chain("_run", "ws, M, z, dts, same_group, meas, out_c, out_P, out_mu", names,
               "_run_{meas}(ws, M, z, dts, same_group, out_c, out_P, out_mu)", False),
    ]
    body = helpers + per + "\n\n" + "\n\n".join(chains)
    public = [n for n in re.findall(r"^def (\w+)\(", body, flags=re.M) if not n.startswith("_")]
    head = HEADER.format(title="The IMM's loop: mixing, mode-matched steps, mode probabilities and the combined estimate.",
                         source="derive/codegen/templates/imm_*.py.tmpl through derive/codegen/families/imm.py")
    decl = (f"\n__all__ = {['MEASUREMENT_NAMES', *public]!r}\n\n"
            "#: the measurements, by index (the IMM's ``meas`` argument)\n"
            f"MEASUREMENT_NAMES = {tuple(names)!r}\n")
    i = body.index("\n\n\n")  # after the imports
    return head + body[:i + 1] + decl + body[i + 1:]

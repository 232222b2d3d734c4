"""The divergence monitor of ``lgekf track``, compiled (``lgekf.apps.divergence``): templates of the emitter.

``MONITOR_HELPERS`` is the body of ``generated/monitor.py``: the model-independent parts (the two-point estimate and
the initial covariance of ``lgekf.core.initiation``, the earlier row of a re-initialisation, the finite check, the
NIS-window scan, the speed's std). ``MODEL_TEMPLATE`` (once per model) and ``RECOVER_TEMPLATE`` (once per model and
measurement) call the model's own kernels: the re-initialisation of one row, the speed's std, the first alarm of a
range of rows, and the whole monitor-and-recover loop of
``lgekf.apps.divergence.recover``, segment after segment, so that an alarm costs no round of Python (the noise
search's low-noise candidates on one long object raise an alarm every few hundred rows: 0.15 ms of Python each).
"""

import re

from ..template import load

MONITOR_HELPERS = load("monitor_helpers.py.tmpl")  # the body of generated/monitor.py

MONITOR_NAMES = re.findall(r"^def (\w+)\(", MONITOR_HELPERS, flags=re.M)  # what generated/monitor.py exports

MODEL_TEMPLATE = load("monitor_model.py.tmpl")

RECOVER_TEMPLATE = load("monitor_recover.py.tmpl")


# the helpers of generated/monitor.py that the templates call: imported into every generated model module
TEMPLATE_HELPERS = [name for name in MONITOR_NAMES if re.search(rf"\b{name}\(", MODEL_TEMPLATE + RECOVER_TEMPLATE)]


def model_monitor_kernels() -> list:
    """(label, source) of the monitor's kernels of one model (``MODEL_TEMPLATE``), for ``render_module``."""
    return [("monitor", MODEL_TEMPLATE)]


def measurement_monitor_kernels(meas: str) -> list:
    """(label, source) of the monitor's kernels of one model and measurement (``RECOVER_TEMPLATE``)."""
    return [(f"monitor_{meas}", RECOVER_TEMPLATE.replace("{meas}", meas))]


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): (slot, kernel) pairs of one model module; none for a model whose
    space the monitor's two-point restart does not serve (``derive.space.Space.monitored``)."""
    if not model.space.monitored:
        return []
    out = [("monitor_model", k) for k in model_monitor_kernels()]
    for meas in measurements.values():
        out += [(("monitor", meas.name), k) for k in measurement_monitor_kernels(meas.name)]
    return out

"""The public API documents itself: numpydoc sections, the conventions, and examples that run."""

from __future__ import annotations

import doctest
import pydoc

import numpy as np
import pytest

import lgekf
from lgekf.core import common, filters


@pytest.mark.parametrize("module", [common, filters])
def test_docstring_examples_run(module):
    res = doctest.testmod(module, extraglobs={"np": np}, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert res.attempted > 0 and res.failed == 0


@pytest.mark.parametrize("name", [n for n in lgekf.__all__ if n.endswith("Filter")])
def test_help_of_every_filter_class_documents_parameters_and_conventions(name):
    text = pydoc.render_doc(getattr(lgekf, name), renderer=pydoc.plaintext)
    assert "Parameters" in text and "meas_std" in text and "measurement" in text
    assert "State x = [" in text or name == "Filter"  # each model's own state names


@pytest.mark.parametrize("name", ["filter_batch", "make_filter", "state_from_common", "covariance_from_common", "get_model"])
def test_public_functions_have_numpydoc_and_type_hints(name):
    fn = getattr(lgekf, name)
    assert fn.__doc__ and ("Parameters" in fn.__doc__ or "Examples" in fn.__doc__)
    assert fn.__annotations__, f"{name} has no type hints"

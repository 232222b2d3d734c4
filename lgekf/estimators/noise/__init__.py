"""Noise learning: maximum likelihood (``tuning``) and EM (``em``) of the process and measurement noise on a file's own tracks (``tracks``)."""

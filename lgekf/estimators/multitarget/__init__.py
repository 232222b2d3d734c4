"""Multi-target tracking: the tracker (initiation, track existence, deletion), association (JPDA, PDA, GNN; the PMBM filter with Murty's k best assignments), gating and the per-track filter bank."""
